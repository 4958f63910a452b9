"""pkmopt: multi-objective design optimisation of parallel kinematic machine tools.

The same engine as the `pkmopt` command line, with numpy arrays in and out:

    import pkmopt
    m = pkmopt.load_machine("examples/hexapod.yaml")
    r = m.analyze(poses)                  # poses: (N, 6) array, m and degrees
    r["stiffness_min"], r["tau"]          # (N,) in N/m, (N, 6) in N
    front = pkmopt.run_study("studies/library/hexapod-quick.yaml", out="results/quick")

Bad input raises pkmopt.InputError (a ValueError) with the message the command line prints.
Units and frames: docs/conventions.md; this module: docs/python.md.
"""

import tempfile as _tempfile

from ._core import (  # noqa: F401
    InputError,
    Machine,
    __version__,
    calibrate,
    load_machine,
    machine_from_dict,
    optimize,
    read_front,
)
from . import _core

__all__ = [
    "InputError",
    "Machine",
    "calibrate",
    "load_machine",
    "machine_from_dict",
    "optimize",
    "read_front",
    "run_study",
]


def run_study(study, out=None, threads=None, resume=False, force=False, progress=None,
              show_progress=False):
    """Runs a study as `pkmopt run STUDY --out OUT` does and returns its front.

    study: a study file's path, or a dict with the keys of a study file (relative paths in
        a dict, e.g. an actuator catalog, are taken from the working directory).
    out: the results folder (journal.txt, evaluations.csv, pareto.csv, pareto.json,
        summary.json, designs/); default: a new temporary folder.
    threads: OpenMP threads for the evaluations (default: all cores).
    resume: continue the run in `out` from its journal (after a kill or Ctrl-C);
        force: replace a previous run in `out`.
    progress: called after every batch of evaluations with a dict of counts (requests,
        expected_requests, cache_hits, failed, distinct, feasible_front).
    show_progress: also print the command line's progress lines on stderr.

    Ctrl-C (KeyboardInterrupt) stops the run after the batch in progress; the journal keeps
    every evaluation finished, and run_study(..., resume=True) continues from there.

    Returns read_front(out) with 'run': what the run says about itself (status, designs,
    evaluations, from_cache, failed, wall_seconds, out, ...).
    """
    if out is None:
        out = _tempfile.mkdtemp(prefix="pkmopt-study-")
    run = _core._run_study(study, out, threads, resume, force, progress, show_progress)
    front = read_front(run["out"])
    front["run"] = run
    return front
