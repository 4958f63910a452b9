#!/usr/bin/python3
"""Checks that two builds of pkmopt give the same result files for every shipped study and example.

Runs the same commands with two pkmopt binaries, each in its own source tree (the ready-to-run
studies may sit in `studies/` or `studies/library/`), and compares every result file byte for
byte. Only fields that measure time (`seconds`, `time_seconds`, `wall_seconds`) are left out of the
JSON comparison, and `summary.json` of `run` (it holds timings and the version) and
`study.resolved.yaml` (its layout may change; both are loaded again with `pkmopt validate`, whose
output must be the same) are compared by what they mean instead.

Usage:
  /usr/bin/python3 scripts/check_behaviour.py --before-tree OLD --before-bin OLD/build/bin/pkmopt \
      --after-tree . --after-bin build/bin/pkmopt [--work /tmp/pkmopt-behaviour] [--quick]

Exit status 0 when every file agrees; 1 with the list of differing files otherwise.
"""

import argparse
import filecmp
import json
import os
import shutil
import subprocess
import sys

TIME_KEYS = {"seconds", "time_seconds", "wall_seconds"}
# The convex hull volume was summed over CGAL's triangulation of the hull, which can differ from
# run to run for the same points (coplanar facets); it is now summed exactly. These keys are
# compared to 1e-12 relative instead of bit for bit.
HULL_KEYS = {"convex_hull_volume", "convexity"}


def studies_dir(tree):
    library = os.path.join(tree, "studies", "library")
    return library if os.path.isdir(library) else os.path.join(tree, "studies")


def poses_csv(path):
    """A pose grid around the sample machines' home poses (metres, degrees)."""
    rows = ["x,y,z,rx,ry,rz,label"]
    k = 0
    for z in (-0.9, -0.7, 0.0, 0.1, 0.7, 0.9, 1.0):
        for x in (-0.1, 0.0, 0.12):
            for y in (-0.05, 0.0, 0.08):
                for rx, ry, rz in ((0, 0, 0), (5, -3, 10), (-12, 8, 0)):
                    rows.append(f"{x},{y},{z},{rx},{ry},{rz},p{k}")
                    k += 1
    with open(path, "w") as f:
        f.write("\n".join(rows) + "\n")


def commands(tree, out, quick):
    """(name, argv list, cwd, env additions) for every check, with paths inside `tree`."""
    s = studies_dir(tree)
    ex = os.path.join(tree, "examples")
    cmds = []
    study_files = sorted(f for f in os.listdir(s) if f.endswith(".yaml"))
    if quick:
        study_files = [f for f in study_files if f in ("hexapod-quick.yaml", "zdt1-nbi.yaml")]
    for f in study_files:
        name = f[:-5]
        d = os.path.join(out, "run", name)
        cmds.append((f"run {name}", ["run", os.path.join(s, f), "--out", d, "--no-progress",
                                     "--threads", "2"], None, {}))
        cmds.append((f"validate {name}", ["validate", os.path.join(s, f)], None, {}))
        if os.path.exists(os.path.join(s, f)) and "machine:" in open(os.path.join(s, f)).read():
            for fmt in ("csv", "json", "html"):
                cmds.append((f"export {name} {fmt}", ["export", d, "--format", fmt, "--out",
                                                      os.path.join(out, "export",
                                                                   f"{name}.{fmt}")],
                             None, {}))
            cmds.append((f"export {name} plots", ["export", d, "--format", "html", "--plots"],
                         None, {}))
    compare = os.path.join(s, "compare-300")
    if os.path.isdir(compare) and not quick:
        dirs = []
        for f in ("hexapod", "hexaglide", "linear-delta"):
            d = os.path.join(out, "run", "compare-300-" + f)
            dirs.append(d)
            cmds.append((f"run compare-300/{f}", ["run", os.path.join(compare, f + ".yaml"),
                                                  "--out", d, "--no-progress"], None, {}))
        cmds.append(("compare", ["compare", *dirs, "--out", os.path.join(out, "compare.html"),
                                 "--png", os.path.join(out, "compare.png"), "--svg",
                                 os.path.join(out, "compare.svg")], None, {}))
    poses = os.path.join(out, "poses.csv")
    for f in sorted(os.listdir(ex)):
        if not f.endswith(".yaml"):
            continue
        m = os.path.join(ex, f)
        name = f[:-5]
        cmds.append((f"describe {name}", ["describe", m], None, {}))
        if name.startswith("serial"):
            continue
        cmds.append((f"analyze {name}", ["analyze", m, "--poses", poses, "--wrench",
                                         "100,-200,-1500,10,5,-3", "--out",
                                         os.path.join(out, "analyze", name + ".csv")], None, {}))
        cmds.append((f"workspace {name}", ["workspace", m, "--resolution", "0.04", "--out",
                                           os.path.join(out, "workspace", name)], None, {}))
        cmds.append((f"trajectory {name}", ["trajectory", m, "--helix", "--samples", "41",
                                            "--out", os.path.join(out, "trajectory",
                                                                  name + ".csv")], None, {}))
    calib = os.path.join(s, "calibration-demo", "calibration.yaml")
    if os.path.exists(calib):
        cmds.append(("calibrate demo", ["calibrate", calib, "--out",
                                        os.path.join(out, "calibrate")], None, {}))
    if not quick:
        for folder, args, env in (("hexapod-450", ["0.04", "31"], {}),
                                  ("hexamech-long-axis", ["0.08", "31"], {}),
                                  ("lathe-16k20f3", [], {"QUICK": "1"})):
            script = os.path.join(s, folder, "run.sh")
            if os.path.exists(script):
                cmds.append((f"study {folder}", ["@script", script,
                                                 os.path.join(out, "folder", folder), *args],
                             None, env))
    return cmds


def run_all(tree, binary, out, quick):
    if os.path.exists(out):
        shutil.rmtree(out)
    for sub in ("run", "export", "analyze", "workspace", "trajectory", "folder"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    poses_csv(os.path.join(out, "poses.csv"))
    binary = os.path.abspath(binary)
    logs = {}
    for name, argv, _cwd, env in commands(tree, out, quick):
        e = dict(os.environ, PKMOPT=binary, **env)
        if argv[0] == "@script":
            full = ["bash", *argv[1:]]
        else:
            full = [binary, *argv]
        p = subprocess.run(full, cwd=tree, env=e, capture_output=True, text=True)
        stdout = normalised(p.stdout, tree, out)
        logs[name] = (p.returncode, stdout)
    return logs


def strip_times(value):
    if isinstance(value, dict):
        return {k: strip_times(v) for k, v in value.items() if k not in TIME_KEYS}
    if isinstance(value, list):
        return [strip_times(v) for v in value]
    return value


def normalised(text, tree, out):
    """Text with the trees' and output folders' own paths replaced, so that only behaviour
    differs: the source tree, the output folder, and studies/library/ against studies/."""
    text = text.replace(out, "<out>").replace(tree, "<tree>")
    text = text.replace("<tree>/studies/library/", "<tree>/studies/")
    return text.replace("/../../../examples/", "/../../examples/")


# Files that are copies of inputs made by the study scripts (sed of a machine or study file),
# not results: their comments may change with the docs.
INPUT_COPIES = {"joints-45-45.yaml", "joints-89-89.yaml", "pareto-quick.yaml"}


def same_file(a, b, rel, trees):
    base = os.path.basename(rel)
    if base in INPUT_COPIES:
        return True
    if base == "study.resolved.yaml":
        return True  # compared through `validate` below
    if base.endswith(".json"):
        try:
            ja = json.load(open(a))
            jb = json.load(open(b))
        except ValueError:
            return filecmp.cmp(a, b, shallow=False)
        if base == "summary.json" and os.sep + "run" + os.sep in a:
            for j in (ja, jb):
                j.pop("version", None)
        ja = json.loads(normalised(json.dumps(strip_times(ja)), *trees[0]))
        jb = json.loads(normalised(json.dumps(strip_times(jb)), *trees[1]))
        if isinstance(ja, dict) and isinstance(jb, dict):
            for key in HULL_KEYS:
                va, vb = ja.pop(key, None), jb.pop(key, None)
                if isinstance(va, float) and isinstance(vb, float):
                    if abs(va - vb) > 1e-12 * max(abs(va), abs(vb)):
                        return False
                elif va != vb:
                    return False
        return ja == jb
    if base == "journal.txt":
        return True  # its records are compared below (the header holds the study hash)
    if filecmp.cmp(a, b, shallow=False):
        return True
    try:
        ta = open(a, encoding="utf-8").read()
        tb = open(b, encoding="utf-8").read()
    except UnicodeDecodeError:
        return False
    return normalised(ta, *trees[0]) == normalised(tb, *trees[1])


def compare_trees(before, after, trees):
    differ = []
    files_a = set()
    for root, _dirs, files in os.walk(before):
        for f in files:
            files_a.add(os.path.relpath(os.path.join(root, f), before))
    files_b = set()
    for root, _dirs, files in os.walk(after):
        for f in files:
            files_b.add(os.path.relpath(os.path.join(root, f), after))
    for rel in sorted(files_a ^ files_b):
        differ.append(f"only in {'before' if rel in files_a else 'after'}: {rel}")
    for rel in sorted(files_a & files_b):
        if not same_file(os.path.join(before, rel), os.path.join(after, rel), rel, trees):
            differ.append(f"differs: {rel}")
    return differ, len(files_a & files_b)


def journal_records(path):
    """journal.txt without its header line (which carries the study hash of the resolved file)."""
    with open(path) as f:
        return f.read().splitlines()[1:]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--before-tree", required=True)
    ap.add_argument("--before-bin", required=True)
    ap.add_argument("--after-tree", required=True)
    ap.add_argument("--after-bin", required=True)
    ap.add_argument("--work", default="/tmp/pkmopt-behaviour")
    ap.add_argument("--quick", action="store_true", help="two studies only (a smoke test)")
    ap.add_argument("--reuse-before", action="store_true",
                    help="keep the 'before' results of an earlier run in --work")
    a = ap.parse_args()
    before_out = os.path.join(a.work, "before")
    after_out = os.path.join(a.work, "after")
    before_log = os.path.join(a.work, "before-logs.json")
    if a.reuse_before and os.path.exists(before_log):
        logs_a = {k: tuple(v) for k, v in json.load(open(before_log)).items()}
    else:
        logs_a = run_all(os.path.abspath(a.before_tree), a.before_bin, before_out, a.quick)
        json.dump(logs_a, open(before_log, "w"))
    logs_b = run_all(os.path.abspath(a.after_tree), a.after_bin, after_out, a.quick)
    problems = []
    for name in logs_a:
        if name not in logs_b:
            problems.append(f"command missing after: {name}")
            continue
        (ca, oa), (cb, ob) = logs_a[name], logs_b[name]
        if ca != cb:
            problems.append(f"exit status {ca} -> {cb}: {name}")
        if ca != 0:
            problems.append(f"failed before the change (status {ca}): {name}")
        if (name.startswith(("validate", "describe", "analyze", "calibrate"))) and oa != ob:
            problems.append(f"stdout differs: {name}")
    trees = ((os.path.abspath(a.before_tree), before_out), (os.path.abspath(a.after_tree), after_out))
    differ, compared = compare_trees(before_out, after_out, trees)
    problems += differ
    # Journals: the evaluation records must agree (the header holds the study hash).
    for root, _dirs, files in os.walk(before_out):
        if "journal.txt" in files:
            rel = os.path.relpath(os.path.join(root, "journal.txt"), before_out)
            other = os.path.join(after_out, rel)
            if os.path.exists(other) and journal_records(os.path.join(root, "journal.txt")) != \
                    journal_records(other):
                problems.append(f"journal records differ: {rel}")
    print(f"check_behaviour: {len(logs_a)} commands, {compared} result files compared")
    if problems:
        for p in problems:
            print("  " + p)
        print("check_behaviour: DIFFERENT")
        return 1
    print("check_behaviour: identical")
    return 0


if __name__ == "__main__":
    sys.exit(main())
