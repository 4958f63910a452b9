#!/usr/bin/env python3
"""Every shipped study's front is the non-dominated set of its run.

Runs every study file of studies/library (the library's own folders included) with `pkmopt run`
and checks, from the files the run wrote:

  * no design in pareto.csv is dominated by any feasible row of evaluations.csv;
  * every design in pareto.csv is a feasible row of evaluations.csv (the same numbers);
  * without output.front_size the front holds every non-dominated feasible row (computed here
    independently of pkmopt), and summary.json's archive_size says how many there are.

Usage: shipped_fronts_test.py PKMOPT_BINARY SOURCE_DIR SCRATCH_DIR [--full]
Without --full, NSGA-II studies run at most 12 generations (hybrid: 12 generations and 10 polish
iterations): the front is built by the same code at any budget. --full runs the studies as
shipped (about five minutes on two cores).
"""
import csv
import json
import math
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np


def study_files(library):
    files = sorted(library.glob("*.yaml")) + sorted(library.glob("*/*.yaml"))
    return [f for f in files if re.search(r"^optimizer:", f.read_text(), re.M)]


def reduce_budget(path):
    text = path.read_text()
    text = re.sub(r"generations: *(\d+)", lambda m: f"generations: {min(int(m.group(1)), 12)}",
                  text)
    text = re.sub(r"polish_iterations: *(\d+)",
                  lambda m: f"polish_iterations: {min(int(m.group(1)), 10)}", text)
    path.write_text(text)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def objective_columns(out):
    """(names, signs): the objective columns and +1 (minimised) or -1 (maximised)."""
    summary = json.loads((out / "summary.json").read_text())
    objectives = summary["objectives"]
    if isinstance(objectives, int):  # a benchmark study: f_1..f_m, minimised
        return [f"f_{i + 1}" for i in range(objectives)], [1.0] * objectives
    return ([o["name"] for o in objectives],
            [-1.0 if o["sense"] == "maximize" else 1.0 for o in objectives])


def matrix(header, rows, names, signs):
    cols = [header.index(n) for n in names]
    return np.array([[s * float(r[c]) for c, s in zip(cols, signs)] for r in rows]).reshape(
        len(rows), len(names))


def non_dominated(points):
    keep = []
    for k, p in enumerate(points):
        dominated = np.any(np.all(points <= p, axis=1) & np.any(points < p, axis=1))
        if not dominated:
            keep.append(k)
    return keep


def check_synthesis(out):
    """A synthesis: the merged front against every structure's evaluations, each structure's own
    folder as a design study's."""
    problems = []
    names, signs = objective_columns(out)
    evals = []
    for folder in sorted((out / "candidates").iterdir()):
        eh, erows = read_csv(folder / "evaluations.csv")
        feasible_rows = [r for r in erows if r[eh.index("feasible")] == "1"]
        if feasible_rows:
            evals.append(matrix(eh, feasible_rows, names, signs))
        problems += [f"candidates/{folder.name}: {p}" for p in check_run(folder)
                     if "pareto.csv is empty" not in p and "hypervolume None" not in p]
    evals = np.vstack(evals) if evals else np.zeros((0, len(names)))
    ph, prows = read_csv(out / "pareto.csv")
    front = matrix(ph, prows, names, signs)
    if len(prows) == 0:
        problems.append("the merged pareto.csv is empty")
    for k, p in enumerate(front):
        if np.any(np.all(evals <= p, axis=1) & np.any(evals < p, axis=1)):
            problems.append(f"merged pareto.csv row {k + 1} is dominated by an evaluation")
        if not np.any(np.all(evals == p, axis=1)):
            problems.append(f"merged pareto.csv row {k + 1} is not a feasible evaluation")
    return problems


def check_run(out):
    problems = []
    if (out / "candidates").is_dir():
        return check_synthesis(out)
    names, signs = objective_columns(out)
    if len(names) < 2:
        return problems  # a single-objective run: its solver's answer
    eh, erows = read_csv(out / "evaluations.csv")
    ph, prows = read_csv(out / "pareto.csv")
    feasible_rows = [r for r in erows if r[eh.index("feasible")] == "1"]
    evals = matrix(eh, feasible_rows, names, signs)
    front = matrix(ph, prows, names, signs)
    if len(prows) == 0:
        problems.append("pareto.csv is empty")
    for k, p in enumerate(front):
        beaten = np.all(evals <= p, axis=1) & np.any(evals < p, axis=1)
        if np.any(beaten):
            j = int(np.argmax(beaten))
            problems.append(f"pareto.csv row {k + 1} is dominated by evaluation "
                            f"{feasible_rows[j][0]}")
        if not np.any(np.all(evals == p, axis=1)):
            problems.append(f"pareto.csv row {k + 1} is not a feasible evaluation")
    # Without thinning the front holds every distinct non-dominated objective vector.
    summary = json.loads((out / "summary.json").read_text())
    distinct = np.unique(evals, axis=0) if len(evals) else evals
    expected = len(non_dominated(distinct)) if len(distinct) else 0
    if summary.get("archive_size") != expected:
        problems.append(f"summary.json archive_size {summary.get('archive_size')}, "
                        f"the evaluations hold {expected} non-dominated designs")
    if "front_size" not in (out / "study.resolved.yaml").read_text() and len(prows) != expected:
        problems.append(f"pareto.csv holds {len(prows)} designs, expected all {expected}")
    hv = summary.get("hypervolume")
    if hv is None or not math.isfinite(hv) or hv < 0:
        problems.append(f"summary.json hypervolume {hv}")
    return problems


def main():
    binary, source, scratch = (pathlib.Path(a) for a in sys.argv[1:4])
    full = "--full" in sys.argv[4:]
    if scratch.exists():
        shutil.rmtree(scratch)
    library = scratch / "library"
    shutil.copytree(source / "studies" / "library", library)
    failures = 0
    for study in study_files(library):
        if not full:
            reduce_budget(study)
        name = str(study.relative_to(library))
        out = scratch / "out" / name.replace("/", "_").removesuffix(".yaml")
        run = subprocess.run([str(binary), "run", str(study), "--out", str(out), "--threads", "2"],
                             capture_output=True, text=True)
        if run.returncode not in (0, 3):
            print(f"FAIL {name}: pkmopt run exited {run.returncode}: {run.stderr.strip()}")
            failures += 1
            continue
        problems = check_run(out)
        for p in problems:
            print(f"FAIL {name}: {p}")
        failures += bool(problems)
        if not problems:
            summary = json.loads((out / "summary.json").read_text())
            print(f"ok   {name}: {summary.get('points')} designs on the front, archive "
                  f"{summary.get('archive_size')}, {summary.get('evaluations')} evaluations")
    print(f"{failures} of {len(study_files(library))} studies failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
