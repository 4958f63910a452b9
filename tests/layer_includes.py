#!/usr/bin/python3
"""Fails when a source file includes a header of a layer above its own.

The layers, lowest first (docs/architecture.md):
  models, optimizer  <  problems  <  io  <  report  <  studies  <  app, python, fuzz
models and optimizer know nothing of each other. Every `#include "LAYER/..."` line of every
.hpp, .cpp and .inc file under a layer's folder is checked; tests/ and bench/ may include
anything. Also fails when app/ holds anything but main.cpp, cli_args.*, error_report.*,
commands.hpp and commands/cmd_*.cpp (the command line only).

Inside models/, every source file lives in a folder that names what it holds, and the folders are
layered too: core/ (Machine, capabilities, poses) includes only core/; the shared capability
folders (stiffness, dynamics, geometry, motion, workspace) include core/ and each other; a model's
folder (hexapod, leg_chain, serial, hybrid) includes core/, the shared folders and itself (a hybrid
machine also its serial axes). No model's folder reaches into another's.

Usage: /usr/bin/python3 tests/layer_includes.py [SOURCE_ROOT]
"""

import os
import re
import sys

# For each layer: the layers it may include (itself included).
ALLOWED = {
    "models": {"models", "pkmopt"},
    "optimizer": {"optimizer", "pkmopt"},
    "problems": {"problems", "models", "optimizer", "pkmopt"},
    "io": {"io", "problems", "models", "optimizer", "pkmopt"},
    "report": {"report", "io", "problems", "models", "optimizer", "pkmopt"},
    "studies": {"studies", "report", "io", "problems", "models", "optimizer", "pkmopt"},
    "app": {"app", "studies", "report", "io", "problems", "models", "optimizer", "pkmopt"},
    "python": {"python", "studies", "report", "io", "problems", "models", "optimizer", "pkmopt"},
    "fuzz": {"fuzz", "studies", "report", "io", "problems", "models", "optimizer", "pkmopt"},
}
LAYERS = set(ALLOWED) - {"pkmopt"}
# models/ folders: the folders of models/ each may include (itself included).
SHARED = {"core", "stiffness", "dynamics", "geometry", "motion", "workspace"}
MODEL_FOLDERS = {
    "core": {"core"},
    **{shared: SHARED for shared in SHARED - {"core"}},
    "hexapod": SHARED | {"hexapod"},
    "leg_chain": SHARED | {"leg_chain"},
    "serial": SHARED | {"serial"},
    "hybrid": SHARED | {"hybrid", "serial"},
}
# Files of models/ outside its folders: the named sample machines of tests and benchmarks.
MODELS_TOP = {"sample_machines.hpp", "CMakeLists.txt"}
MODELS_INCLUDE = re.compile(r'^\s*#\s*include\s*"models/([^"/]+)/[^"]+"')
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"/]+)/[^"]+"')
APP_FILES = re.compile(r"^(main\.cpp|(cli_args|error_report)\.(hpp|cpp)|commands\.hpp"
                       r"|commands/cmd_[a-z_]+\.cpp"
                       r"|CMakeLists\.txt)$")


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    problems = []
    checked = 0
    for layer in sorted(ALLOWED):
        top = os.path.join(root, layer)
        if not os.path.isdir(top):
            continue
        for dirpath, _dirs, files in os.walk(top):
            for name in sorted(files):
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, top)
                if layer == "app" and not APP_FILES.match(rel):
                    problems.append(f"app/{rel}: app/ holds command-line code only (main.cpp, "
                                    "cli_args, error_report, commands.hpp, commands/cmd_*.cpp)")
                folder = rel.split(os.sep)[0] if os.sep in rel else None
                if layer == "models" and folder is None and name not in MODELS_TOP:
                    problems.append(f"models/{rel}: a file of models/ lives in the folder of what "
                                    f"it holds ({', '.join(sorted(MODEL_FOLDERS))})")
                if layer == "models" and folder is not None and folder not in MODEL_FOLDERS:
                    problems.append(f"models/{rel}: '{folder}/' is not a folder of models/ this "
                                    "check knows (add it to MODEL_FOLDERS with what it may include)")
                if not name.endswith((".hpp", ".cpp", ".inc", ".h")):
                    continue
                checked += 1
                with open(path, encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        target = m.group(1)
                        sub = MODELS_INCLUDE.match(line)
                        if layer == "models" and folder in MODEL_FOLDERS and sub:
                            if sub.group(1) not in MODEL_FOLDERS[folder]:
                                problems.append(f"models/{rel}:{number}: includes "
                                                f"'models/{sub.group(1)}/', which "
                                                f"'models/{folder}/' may not use")
                        if target in LAYERS and target not in ALLOWED[layer]:
                            problems.append(f"{layer}/{rel}:{number}: includes '{target}/', a "
                                            f"layer above '{layer}'")
    for p in problems:
        print(p)
    print(f"layer_includes: {checked} files checked, {len(problems)} problem(s)")
    return 1 if problems or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
