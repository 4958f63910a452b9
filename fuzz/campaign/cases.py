"""Cases: one generator per command (and the Python module) builds a valid run. (the mutation campaign: fuzz/campaign/main.py)."""

import argparse
import concurrent.futures
import csv
import errno
import hashlib
import io
import json
import math
import multiprocessing
import os
import random
import re
import resource
import shlex
import shutil
import signal
import stat
import struct
import subprocess
import sys
import threading
import time
import traceback
from pathlib import Path

from .values import b2s, fmt  # noqa: F401
# ----------------------------------------------------------------------------------------------
# Cases
# ----------------------------------------------------------------------------------------------

class Case:
    """One run: the files of its folder, the command line and what was mutated."""

    def __init__(self, k, cmd):
        self.k = k
        self.cmd = cmd
        self.trees = []          # (relpath, source folder) copied first
        self.files = {}          # relpath -> ("file", str) | ("dir",) | ("fifo", feed or None)
        #                          | ("fifo_out",) | ("symlink", target)
        self.kinds = {}          # relpath -> "yaml:GROUP" | "csv" | "json" | "text": mutable files
        self.items = []          # ["pos", value] | ["opt", name, value or None, form]
        self.spec = {}           # option -> kind
        self.fixed = set()       # options never mutated
        self.mutations = []
        self.mutated = False
        self.meta = {}

    def add_file(self, rel, text, kind=None):
        self.files[rel] = ("file", text)
        if kind:
            self.kinds[rel] = kind

    def opt(self, name, value=None):
        self.items.append(["opt", name, value, "sep"])

    def pos(self, value):
        self.items.append(["pos", value])

    def argv(self):
        if self.cmd == "python":
            return ["case.py"]
        out = [self.cmd]
        for it in self.items:
            if it[0] == "pos":
                out.append(it[1])
            elif it[2] is None:
                out.append(it[1])
            elif it[3] == "eq":
                out.append(f"{it[1]}={it[2]}")
            else:
                out.extend([it[1], it[2]])
        return out

    def opt_value(self, name):
        for it in self.items:
            if it[0] == "opt" and it[1] == name:
                return it[2]
        return None


def read_text(path):
    return b2s(Path(path).read_bytes())


def add_machine(case, ctx, m, rel="machine.yaml"):
    """Copies machine file m (and the module files it names) into the case; returns its path."""
    text = read_text(m["path"])
    case.add_file(rel, text, "yaml:machine")
    for dep in m["deps"]:
        case.add_file(dep, read_text(Path(m["path"]).parent / dep), "yaml:machine")
    return rel


def wrench(rng):
    return ",".join(fmt(round(rng.uniform(-2000, 2000), 1)) for _ in range(3)) + "," + \
        ",".join(fmt(round(rng.uniform(-50, 50), 1)) for _ in range(3))


def pt(m):
    return m["point"]


def gen_describe(case, rng, ctx):
    m = rng.choice(ctx.machines_for["describe"])
    case.pos(add_machine(case, ctx, m))
    case.meta["pos_kinds"] = ["in_file"]


def gen_analyze(case, rng, ctx):
    m = rng.choice(ctx.machines_for["analyze"])
    case.pos(add_machine(case, ctx, m))
    case.add_file("poses.csv", m["poses_csv"], "csv")
    case.opt("--poses", "poses.csv")
    case.spec = {"--poses": "in_file", "--wrench": "list6", "--out": "out_file",
                 "--compliance": "flag", "--mode-shapes": "flag"}
    if rng.random() < 0.5:
        case.opt("--wrench", wrench(rng))
    if rng.random() < 0.3:
        case.opt("--compliance")
    if m["masses"] and rng.random() < 0.4:
        case.opt("--mode-shapes")
    if rng.random() < 0.5:
        case.opt("--out", "out.csv")
    case.meta["pos_kinds"] = ["in_file"]


def gen_fk(case, rng, ctx):
    m = rng.choice(ctx.machines_for["fk"])
    case.pos(add_machine(case, ctx, m))
    q = list(m["q"])
    if rng.random() < 0.3:
        q = [v + rng.uniform(-0.01, 0.01) * (1 if abs(v) < 10 else 100) for v in q]
    case.opt("--q", ",".join(fmt(v) for v in q))
    # A forward solve that does not converge from its start (the home pose, or --guess) exits 3
    # with a warning: a documented outcome for unmodified input too.
    case.meta["ok_status"] = 3
    case.spec = {"--q": f"list{len(q)}", "--guess": "list6", "--max-iterations": "int"}
    if rng.random() < 0.4:
        p = pt(m)
        case.opt("--guess", ",".join(fmt(round(v + rng.uniform(-0.01, 0.01), 4)) for v in p)
                 + ",0,0,0")
    if rng.random() < 0.3:
        case.opt("--max-iterations", str(rng.choice([5, 20, 100, 300])))
    case.meta["pos_kinds"] = ["in_file"]


def gen_workspace(case, rng, ctx):
    m = rng.choice(ctx.machines_for["workspace"])
    case.pos(add_machine(case, ctx, m))
    res = m["resolution"]
    case.spec = {"--orientation": "list3", "--tilt": "float", "--yaw-range": "float",
                 "--mode": "enum:all,some", "--orientation-step": "float",
                 "--resolution": "float", "--tolerance": "float", "--min-margin": "float",
                 "--min-stiffness": "float", "--wrench": "list6",
                 "--slice-axis": "enum:x,y,z", "--slice-at": "float",
                 "--slice-metric": "enum:singularity_margin,stiffness_min,max_leg_force,"
                                   "tcp_error_max,tcp_deflection,stiffness_min_loaded,"
                                   "natural_frequency_1",
                 "--slice-pixel": "float", "--out": "out_dir"}
    orient = m["orient_ok"] and rng.random() < 0.25
    if orient:
        # Orientation workspaces cost (orientations x grid nodes): kept well under a second so
        # that a mild change of one option (a finer grid, a wider cone) stays within the timeout.
        res = 0.2
        case.opt("--tilt", str(rng.choice([3, 5])))
        case.opt("--orientation-step", "5")
        if rng.random() < 0.4:
            case.opt("--mode", rng.choice(["all", "some"]))
    case.opt("--resolution", fmt(res))
    if rng.random() < 0.2:
        case.opt("--orientation", "2,-1,3")
    if rng.random() < 0.2:
        case.opt("--min-margin", str(rng.choice([0.01, 0.05, 0.1])))
    if rng.random() < 0.15:
        case.opt("--min-stiffness", str(rng.choice([1e4, 1e6])))
    if rng.random() < 0.3:
        case.opt("--wrench", wrench(rng))
    if rng.random() < 0.6:
        case.opt("--out", "ws")
        if rng.random() < 0.4:
            axis = rng.choice("xyz")
            case.opt("--slice-axis", axis)
            case.opt("--slice-at", fmt(pt(m)["xyz".index(axis)]))
        if rng.random() < 0.3:
            metrics = ["singularity_margin", "stiffness_min", "max_leg_force", "tcp_error_max",
                       "tcp_deflection", "stiffness_min_loaded"]
            if m["masses"]:
                metrics.append("natural_frequency_1")
            case.opt("--slice-metric", rng.choice(metrics))
        if rng.random() < 0.2:
            case.opt("--slice-pixel", "0.02")
    case.meta["pos_kinds"] = ["in_file"]


def gen_trajectory(case, rng, ctx):
    m = rng.choice(ctx.machines_for["trajectory"])
    case.pos(add_machine(case, ctx, m))
    case.spec = {"--path": "in_file", "--helix": "flag", "--helix-centre": "list3",
                 "--helix-radius": "list2", "--helix-height": "list2",
                 "--helix-angles": "list3", "--helix-orientation": "list3",
                 "--helix-frequency": "float", "--t-start": "float", "--t-end": "float",
                 "--samples": "int", "--dt": "float", "--jacobian": "flag",
                 "--out": "out_file", "--singular-out": "out_file", "--wrench": "list6",
                 "--catalog": "in_file", "--drive": "text"}
    if rng.random() < 0.35:
        case.add_file("path.csv", m["path_csv"], "csv")
        case.opt("--path", "path.csv")
    else:
        case.opt("--helix")
        case.opt("--helix-centre", ",".join(fmt(v) for v in pt(m)))
        case.opt("--helix-radius", "0.005,0.005")
        case.opt("--helix-height", "0,0.005")
        if rng.random() < 0.3:
            case.opt("--dt", "0.3")
        else:
            case.opt("--samples", "21")
        if rng.random() < 0.3:
            case.opt("--helix-angles", "2,2,2")
        if rng.random() < 0.2:
            case.opt("--helix-frequency", str(rng.choice([0.5, 2, 6])))
        if rng.random() < 0.15:
            case.opt("--t-start", "0.5")
            case.opt("--t-end", "3")
        if rng.random() < 0.1:
            case.opt("--helix-orientation", "1,1,0")
    if rng.random() < 0.3:
        case.opt("--jacobian")
    if rng.random() < 0.4:
        case.opt("--wrench", wrench(rng))
    if rng.random() < 0.5:
        case.opt("--out", "traj.csv")
    if rng.random() < 0.3:
        case.opt("--singular-out", "singular.csv")
    if m["masses"] and rng.random() < 0.5:
        case.add_file("catalog.yaml", ctx.catalog_text, "yaml:catalog")
        case.opt("--catalog", "catalog.yaml")
        case.opt("--drive", rng.choice(ctx.catalog_entries))
    case.meta["pos_kinds"] = ["in_file"]


def gen_calibration_poses(case, rng, ctx):
    m = rng.choice(ctx.machines_for["calibration-poses"])
    case.pos(add_machine(case, ctx, m))
    case.spec = {"--count": "int", "--candidates": "in_file", "--grid": "flag",
                 "--xy-range": "float", "--z-range": "list2", "--angle-range": "float",
                 "--steps": "int", "--model": "enum:42,48", "--zero-length": "float",
                 "--sigma-position": "float", "--sigma-orientation-deg": "float",
                 "--sigma-actuator": "float", "--out": "out_file"}
    case.opt("--count", str(rng.choice([10, 12, 16])))
    if rng.random() < 0.4:
        case.add_file("candidates.csv", ctx.candidates_csv, "csv")
        case.opt("--candidates", "candidates.csv")
    else:
        case.opt("--grid")
        case.opt("--steps", "3")
        if rng.random() < 0.3:
            case.opt("--xy-range", "0.12")
        if rng.random() < 0.3:
            case.opt("--angle-range", "10")
    if rng.random() < 0.3:
        case.opt("--model", rng.choice(["42", "48"]))
    if rng.random() < 0.2:
        case.opt("--zero-length", "0.7")
    for o, v in (("--sigma-position", "2e-5"), ("--sigma-orientation-deg", "0.003"),
                 ("--sigma-actuator", "1e-6")):
        if rng.random() < 0.15:
            case.opt(o, v)
    if rng.random() < 0.5:
        case.opt("--out", "selected.csv")
    case.meta["pos_kinds"] = ["in_file"]


def gen_simulate(case, rng, ctx):
    m = rng.choice(ctx.machines_for["simulate-measurements"])
    case.pos(add_machine(case, ctx, m))
    case.spec = {"--out": "out_dir", "--poses": "int", "--seed": "uint", "--outliers": "int",
                 "--model": "enum:42,48", "--unit": "enum:mm,m", "--zero-length": "float",
                 "--holdout-every": "int", "--joint-error": "float", "--tracker-sigma": "float",
                 "--tracker-sigma-per-metre": "float", "--orientation-sigma-deg": "float",
                 "--actuator-sigma": "float"}
    case.opt("--out", "sim")
    case.opt("--poses", str(rng.choice([12, 20, 30])))
    for o, vals in (("--seed", ["1", "7", "123"]), ("--outliers", ["0", "1", "3"]),
                    ("--model", ["42", "48"]), ("--unit", ["mm", "m"]),
                    ("--zero-length", ["0.7", "0.5"]), ("--holdout-every", ["3", "4"]),
                    ("--joint-error", ["1e-3", "5e-4"]), ("--tracker-sigma", ["15e-6"]),
                    ("--tracker-sigma-per-metre", ["6e-6"]),
                    ("--orientation-sigma-deg", ["0.003"]), ("--actuator-sigma", ["1e-6"])):
        if rng.random() < 0.15:
            case.opt(o, rng.choice(vals))
    case.meta["pos_kinds"] = ["in_file"]


def gen_calibrate(case, rng, ctx):
    s = rng.choice(ctx.calibration_sets)
    case.add_file("calibration.yaml", s["calibration"], "yaml:calibration")
    case.add_file(s["machine_rel"], s["machine"], "yaml:machine")
    case.add_file(s["measurements_rel"], s["measurements"], "csv")
    case.pos("calibration.yaml")
    case.spec = {"--out": "out_dir"}
    case.opt("--out", "cal")
    case.meta["pos_kinds"] = ["in_file"]
    case.meta["ok_status"] = s["status"]


def add_study(case, ctx, st, rel="study.yaml"):
    case.add_file(rel, st["text"], "yaml:study")
    if st["catalog"]:
        case.add_file("catalogs/sew-cms.yaml", ctx.catalog_text, "yaml:catalog")
    return rel


def gen_validate(case, rng, ctx):
    st = rng.choice(ctx.studies)
    case.pos(add_study(case, ctx, st))
    case.meta["pos_kinds"] = ["in_file"]


def gen_run(case, rng, ctx):
    st = rng.choice([s for s in ctx.studies if s["runnable"]])
    case.pos(add_study(case, ctx, st))
    case.spec = {"--out": "out_dir", "--threads": "threads", "--resume": "flag",
                 "--force": "flag"}
    case.fixed = {"--no-progress"}
    case.opt("--out", "res")
    case.opt("--threads", "1")
    case.opt("--no-progress")
    case.meta["pos_kinds"] = ["in_file"]
    case.meta["ok_status"] = st["status"]
    if st["result"] and not st["catalog"] and rng.random() < 0.3:
        # (A study naming a catalog is not resumable from a moved folder: the journal's study
        # hash holds the catalog's absolute path.)
        # Resume (or replace) a previous run of the same study, whose files get damaged.
        case.trees.append(("res", st["result"]))
        how = rng.choice(["resume", "resume", "force", "none"])
        if how == "resume":
            case.opt("--resume")
        elif how == "force":
            case.opt("--force")
        else:
            # Neither --resume nor --force into a folder that holds a run: refused (exit 2) even
            # unmutated.
            case.meta["ok_status"] = 2
        res = Path(st["result"])
        if rng.random() < 0.6:
            case.files["res/pareto.json"] = ("gone",)
            case.files["res/summary.json"] = ("gone",)
            case.files["res/pareto.csv"] = ("gone",)
            case.meta["killed"] = True
        for name, kind in (("journal.txt", "text"), ("evaluations.csv", "csv"),
                           ("study.resolved.yaml", "yaml:study"), ("run.lock", "text")):
            if (res / name).exists():
                case.add_file("res/" + name, read_text(res / name), kind)
        case.meta["resume"] = how


def gen_draw(case, rng, ctx):
    m = rng.choice(ctx.machines_for["analyze"])
    case.pos(add_machine(case, ctx, m))
    case.spec = {"--pose": "list6", "--out": "out_file"}
    if rng.random() < 0.6:
        p = pt(m)
        angles = [round(rng.uniform(-5, 5), 2) for _ in range(3)] if rng.random() < 0.5 else \
            [0, 0, 0]
        case.opt("--pose", ",".join(fmt(round(v, 6)) for v in list(p) + angles))
    if rng.random() < 0.5:
        case.opt("--out", "machine.svg")
    case.meta["pos_kinds"] = ["in_file"]


def gen_task_poses(case, rng, ctx):
    st = rng.choice([s for s in ctx.studies if s["design"]])
    case.pos(add_study(case, ctx, st))
    case.spec = {"--home-height": "float", "--out": "out_file", "--design": "in_file"}
    if st["result"] and st["knee_file"] and rng.random() < 0.4:
        case.trees.append(("res", st["result"]))
        case.add_file("res/pareto.json", read_text(Path(st["result"]) / "pareto.json"), "json")
        case.opt("--design", "res/" + st["knee_file"])
    elif rng.random() < 0.4:
        case.opt("--home-height", fmt(round(rng.uniform(0, 1.2), 3)))
    if rng.random() < 0.5:
        case.opt("--out", "poses.csv")
    case.meta["pos_kinds"] = ["in_file"]


# ---- The Python module -----------------------------------------------------------------------
# A python case is a script, case.py, that calls one function of the module with arguments
# (valid ones, some replaced by hostile Python values) and prints one JSON line: "ok" with the
# NaN found in what it returned, "raised" for pkmopt.InputError or TypeError (the module's
# contract), "foreign" for any other exception.

PY_HOSTILE = [
    "float('nan')", "float('inf')", "-float('inf')", "1e308", "-1e308", "5e-324", "1e-310",
    "1e16", "-1e16", "10**30", "-10**30", "2**63", "2**64", "-1", "0", "1", "True", "None",
    "'abc'", "''", "'\\udcff'", "b'x'", "[]", "{}", "()", "object()", "1j", "[float('nan')]",
    "np.zeros((0, 6))", "np.zeros((3,))", "np.full((2, 6), np.nan)", "np.full((2, 6), np.inf)",
    "np.zeros((2, 6), dtype=complex)", "np.array([['a'] * 6])", "np.zeros((4, 12))[:, ::2]",
    "np.zeros((2, 6), dtype=np.float32)", "np.zeros((2, 6), dtype=np.int64)",
    "np.zeros((1, 6, 1))", "np.zeros(10**6)", "lambda *a: 1", "[[1e15] * 6]",
    "np.array([0, 0, 0.9, 0, 0, 90.0])", "np.array([[0, 0, 1e4, 0, 0, 0.0]])",
    "{'a': float('nan')}", "[1, 2, 3, 4, 5, 6, 7]", "'0,0,0.9,0,0,0'",
]

PY_TEMPLATE = """import json, math, os, sys
import numpy as np
import pkmopt


def nan_paths(x, path, out, depth=0):
    if len(out) > 5 or depth > 6:
        return out
    if isinstance(x, float):
        if math.isnan(x):
            out.append(path)
    elif isinstance(x, np.ndarray):
        if x.dtype.kind in 'fc' and np.isnan(x).any():
            out.append(path)
    elif isinstance(x, dict):
        for k, v in x.items():
            nan_paths(v, f'{{path}}[{{k!r}}]', out, depth + 1)
    elif isinstance(x, (list, tuple)):
        for i, v in enumerate(x[:10000]):
            nan_paths(v, f'{{path}}[{{i}}]', out, depth + 1)
    return out


try:
{setup}
except BaseException as e:  # the harness's own arguments (numpy) failed: not pkmopt's
    print(json.dumps({{'status': 'setup', 'type': type(e).__name__, 'message': str(e)[:200]}}))
    sys.exit(0)
try:
{call}
    print(json.dumps({{'status': 'ok', 'nan': nan_paths(result, 'result', [])}}))
except (pkmopt.InputError, TypeError) as e:
    print(json.dumps({{'status': 'raised', 'type': type(e).__name__,
                      'lines': str(e).strip().count(chr(10)) + 1, 'message': str(e)[:300]}}))
except BaseException as e:
    print(json.dumps({{'status': 'foreign', 'type': type(e).__module__ + '.' + type(e).__name__,
                      'message': str(e)[:300]}}))
"""


def py_args(rng, args):
    """args: [(name, valid expression)]; some replaced by hostile ones. Returns (text, notes)."""
    notes = []
    out = []
    hostile = set()
    if rng.random() < 0.85:
        for _ in range(rng.choice([1, 1, 2])):
            hostile.add(rng.randrange(len(args)))
    for i, (name, expr) in enumerate(args):
        if i in hostile:
            new = rng.choice(PY_HOSTILE)
            notes.append(f"{name or 'arg ' + str(i)}: {expr[:40]} -> {new}")
            expr = new
        out.append(f"{name}={expr}" if name else expr)
    return ", ".join(out), notes


def gen_python(case, rng, ctx):
    case.meta["python"] = True
    scenario = rng.choice(["machine", "machine", "machine", "optimize", "problem", "run_study",
                           "read_front", "calibrate", "machine_from_dict"])
    setup = ["import yaml"]
    if scenario == "machine":
        m = rng.choice(ctx.machines_for["analyze"])
        rel = add_machine(case, ctx, m)
        p = [round(v, 6) for v in pt(m)]
        pose = f"[{p[0]}, {p[1]}, {p[2]}, 0, 0, 0]"
        setup.append(f"machine = pkmopt.load_machine({rel!r})")
        what = rng.choice(["analyze", "analyze", "ik", "fk", "jacobian", "workspace", "load"])
        if what == "analyze":
            rows = m["poses_csv"].strip().split("\n")[1:]
            poses = "np.array([" + ", ".join("[" + r + "]" for r in rows) + "], dtype=float)"
            args = [("", poses), ("wrench", "[100, -50, -300, 5, -4, 3]"), ("threads", "1"),
                    ("compliance", rng.choice(["False", "True"]))]
            if m["masses"]:
                args.append(("mode_shapes", rng.choice(["False", "True"])))
            text, notes = py_args(rng, args)
            call = f"result = machine.analyze({text})"
        elif what == "ik":
            text, notes = py_args(rng, [("", pose)])
            call = f"result = machine.ik({text})"
        elif what == "jacobian":
            text, notes = py_args(rng, [("", pose)])
            call = f"result = machine.jacobian({text})"
        elif what == "fk":
            q = "[" + ", ".join(fmt(v) for v in m.get("q", [])) + "]"
            text, notes = py_args(rng, [("", q), ("guess", rng.choice(["None", pose])),
                                        ("max_iterations", "100")])
            call = f"result = machine.fk({text})"
        elif what == "workspace":
            text, notes = py_args(rng, [("resolution", fmt(m["resolution"] * 2)),
                                        ("threads", "1")])
            call = f"result = machine.workspace({text})"
        else:
            notes, call = [], "result = machine.model"
        case.mutations.extend(notes)
        case.meta["py_call"] = what
    elif scenario in ("optimize", "problem"):
        problem = rng.choice(["'zdt1'", "{'name': 'dtlz2', 'variables': 6, 'objectives': 3}",
                              "'hs71'", "'rosenbrock'", "'bnh'"])
        algorithm = rng.choice(["nsga2", "nsga2", "nlopt:LN_COBYLA", "ipopt",
                                "epsilon_constraint", "nbi"])
        opt = {"nsga2": "{'algorithm': 'nsga2', 'population': 8, 'generations': 3, 'seed': 1}",
               "ipopt": "{'algorithm': 'ipopt', 'max_iterations': 20}",
               "nlopt:LN_COBYLA": "{'algorithm': 'nlopt:LN_COBYLA', 'max_evaluations': 50}",
               "epsilon_constraint": "{'algorithm': 'epsilon_constraint', 'points': 3}",
               "nbi": "{'algorithm': 'nbi', 'points': 3}"}[algorithm]
        if scenario == "problem":
            # A Python problem whose fitness returns hostile values now and then.
            bad = rng.choice(PY_HOSTILE + ["raise_it"])
            setup.append(
                "class P:\n"
                "    bounds = ([0.0, 0.0], [1.0, 1.0])\n"
                "    n_obj = 2\n"
                "    calls = 0\n"
                "    def fitness(self, x):\n"
                "        P.calls += 1\n"
                f"        if P.calls % {rng.choice([1, 3, 7])} == 0:\n"
                + ("            raise RuntimeError('user fitness failed')\n" if bad == "raise_it"
                   else f"            return {bad}\n") +
                "        return [x[0], 1 - x[0] + x[1] ** 2]\n"
                "    def gradient(self, x):\n"
                "        return [[1.0, 0.0], [-1.0, 2 * x[1]]]")
            problem = "P()"
            case.mutations.append(f"fitness returns {bad} now and then")
        text, notes = py_args(rng, [("", problem), ("", opt), ("threads", "1")])
        case.mutations.extend(notes)
        call = f"result = pkmopt.optimize({text})"
    elif scenario == "run_study":
        st = rng.choice([s for s in ctx.studies if s["runnable"]])
        rel = add_study(case, ctx, st)
        text, notes = py_args(rng, [("", repr(rel)), ("out", "'res'"), ("threads", "1")])
        case.mutations.extend(notes)
        call = f"result = pkmopt.run_study({text})"
        case.meta["py_out_dir"] = "res"
    elif scenario == "read_front":
        r = rng.choice(ctx.results)
        case.trees.append(("res", r["dir"]))
        case.add_file("res/pareto.json", read_text(Path(r["dir"]) / "pareto.json"), "json")
        case.add_file("res/pareto.csv", read_text(Path(r["dir"]) / "pareto.csv"), "csv")
        text, notes = py_args(rng, [("", "'res'")])
        case.mutations.extend(notes)
        call = f"result = pkmopt.read_front({text})"
    elif scenario == "calibrate":
        c = rng.choice(ctx.calibration_sets)
        case.add_file("calibration.yaml", c["calibration"], "yaml:calibration")
        case.add_file(c["machine_rel"], c["machine"], "yaml:machine")
        case.add_file(c["measurements_rel"], c["measurements"], "csv")
        text, notes = py_args(rng, [("", "'calibration.yaml'"),
                                    ("out", rng.choice(["None", "'cal'"]))])
        case.mutations.extend(notes)
        call = f"result = pkmopt.calibrate({text})"
    else:
        m = rng.choice(ctx.machines_for["describe"])
        rel = add_machine(case, ctx, m)
        setup.append(f"d = yaml.safe_load(open({rel!r}, encoding='utf-8'))")
        text, notes = py_args(rng, [("", "d")])
        case.mutations.extend(notes)
        call = f"result = pkmopt.machine_from_dict({text})"
    case.add_file("case.py", PY_TEMPLATE.format(
        setup="\n".join("    " + ln for blk in setup for ln in blk.split("\n")),
        call="\n".join("    " + ln for ln in call.split("\n"))))
    case.meta["pos_kinds"] = []


def gen_export(case, rng, ctx):
    r = rng.choice(ctx.results)
    case.trees.append(("res", r["dir"]))
    case.add_file("res/pareto.json", read_text(Path(r["dir"]) / "pareto.json"), "json")
    if r["knee_file"]:
        case.add_file("res/" + r["knee_file"], read_text(Path(r["dir"]) / r["knee_file"]),
                      "yaml:machine")
    case.pos("res")
    case.spec = {"--format": "enum:csv,json,html", "--out": "out_file", "--plots": "flag"}
    fmt_ = rng.choice(["csv", "json", "html"])
    case.opt("--format", fmt_)
    if rng.random() < 0.4:
        case.opt("--out", "export." + fmt_)
    if fmt_ != "html" and rng.random() < 0.3:
        case.opt("--plots")
    case.meta["pos_kinds"] = ["in_dir"]


def gen_compare(case, rng, ctx):
    n = rng.choice([2, 2, 3])
    rs = rng.sample(ctx.compare_results, n)
    for i, r in enumerate(rs):
        case.trees.append((f"r{i + 1}", r["dir"]))
        case.add_file(f"r{i + 1}/pareto.json", read_text(Path(r["dir"]) / "pareto.json"),
                      "json")
        case.pos(f"r{i + 1}")
    case.spec = {"--out": "out_file", "--png": "out_file", "--svg": "out_file",
                 "--x": "text_obj", "--y": "text_obj"}
    case.opt("--out", "compare.html")
    if rng.random() < 0.3:
        case.opt("--png", "compare.png")
    if rng.random() < 0.3:
        case.opt("--svg", "compare.svg")
    if rng.random() < 0.3:
        case.opt("--x", "machine_size")
        case.opt("--y", "stiffness_min")
    case.meta["pos_kinds"] = ["in_dir"] * n


GENERATORS = {
    "describe": gen_describe, "analyze": gen_analyze, "fk": gen_fk,
    "workspace": gen_workspace, "trajectory": gen_trajectory,
    "calibration-poses": gen_calibration_poses, "simulate-measurements": gen_simulate,
    "calibrate": gen_calibrate, "validate": gen_validate, "run": gen_run,
    "export": gen_export, "compare": gen_compare, "draw": gen_draw,
    "task-poses": gen_task_poses, "python": gen_python,
}
