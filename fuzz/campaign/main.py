"""Hostile-input mutation campaign over every pkmopt command: checks the tool's error contract.

Each run takes a valid input of one command (the shipped machine files, studies, the calibration
demo, pose and path CSVs, result folders of small `pkmopt run` studies), damages it in a seeded,
reproducible way (hostile numbers, deleted/duplicated/misspelled keys, wrong types, truncation,
invalid bytes, deep nesting, very long strings, broken CSV rows and headers, hostile option
values, directories, FIFOs, /dev/null and missing files in place of files), runs pkmopt on it in
a fresh folder and checks the error contract:

  * no crash (death by a signal) and no hang (the run ends within --timeout seconds, 120 by
    default; a run that ends but takes longer than --slow seconds, 20 by default, is listed as
    slow in the summary without breaking the contract: a mutated number can ask for real work,
    such as the workspace of a 700 m axis at 50 mm resolution);
  * the exit status is 0 (success), 2 (bad input) or 3 (result written but probably wrong, with a
    `pkmopt: warning:` line on stderr); 1 (internal fault) or any other status is a failure;
  * on exit 2, stderr is exactly one line starting with `pkmopt: error: `;
  * on exit 2 no new output file is left (for `run`, the journal files journal.txt,
    evaluations.csv, run.lock, study.resolved.yaml and journal.damaged.txt in --out may stay);
  * no output (stdout, every file written) holds a NaN: a CSV cell, a YAML scalar, a JSON value
    or a number token of a text output equal to nan/-nan/NaN/.nan (JSON null and `inf` are fine).

The Python module is a command of its own here ("python"): a run writes a script that calls one
function (load_machine and the Machine methods analyze, ik, fk, jacobian, workspace;
machine_from_dict, optimize on a benchmark or on a Python problem whose fitness returns hostile
values or raises now and then, run_study, read_front, calibrate) with arguments of which some are
replaced by hostile Python values (NaN, 1e308, 5e-324, huge ints, strings with lone surrogates,
bytes, arrays of the wrong shape, dtype or layout, ...) and its input files damaged as above. Its
contract: no crash of the interpreter and no hang; only pkmopt.InputError or TypeError raised, with
a one-line InputError message; no NaN in what it returns; nothing left behind by an InputError.

Usage:
  /usr/bin/python3 scripts/mutation_campaign.py [--runs 1000] [--seed 1] [--jobs NCORES]
      [--timeout 120] [--slow 20] [--binary build/bin/pkmopt] [--out /tmp/pkmopt-campaign] [--only K]
      [--resume]

The mutations of run K depend only on (--seed, K), so `--only K` repeats run K alone and prints
what it did. Every run works in its own folder under OUT/runs/, removed when the run keeps the
contract; a run that breaks it is kept as OUT/failures/K/ with its input files (input/), the
folder after the run (work/), the command line, stdout, stderr, exit status, the list of
mutations and a `repro.sh` that repeats it. Before the first run the campaign prepares its seed
inputs in OUT/prep/ from the unmodified shipped files (each is checked to pass there first).

Each finished run is appended to OUT/runs.jsonl at once, so a campaign that is killed (or
stopped with Ctrl-C) continues with `--resume`: the runs already there are kept and only the
others are run (the same --seed and the same binary, by its SHA-256 in OUT/campaign.json, are
required). The runs are spread over --jobs worker processes.

At the end a summary is printed and written to OUT/summary.json: runs, runs per command and the
share of them that exit 0, the exit status histogram, crashes, hangs, NaN outputs, exit 1 on
mutated input, multi-line exit-2 messages, exit-2 runs that leave files, runs per second.

Exit status: 0 when no run broke the contract, 1 otherwise (2 for a bad campaign invocation or a
seed input that fails unmodified).

Runs use OMP_NUM_THREADS=1 (--omp-threads) and limits per run: 4 GiB address space, 512 MiB per
written file, no core files.
"""

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

from .common import COMMANDS, REPO  # noqa: F401
from .options import make_case  # noqa: F401
from .checks import execute  # noqa: F401
from .prepare import prepare  # noqa: F401
# Main
# ----------------------------------------------------------------------------------------------

CATEGORY_LABELS = [
    ("crash", "crashes (death by a signal)"),
    ("hang", "hangs (timeout)"),
    ("nan_output", "NaN in an output"),
    ("exit1_mutated", "exit 1 on mutated input"),
    ("exit1_unmutated", "exit 1 on unmutated input"),
    ("bad_exit_status", "other exit statuses"),
    ("exit2_message", "exit 2 without exactly one 'pkmopt: error: ' line"),
    ("exit2_leftover", "exit 2 leaving new files"),
    ("exit3_no_warning", "exit 3 without a warning line"),
    ("baseline_failed", "unmutated seed input failing"),
    ("python_foreign_exception", "Python: an exception other than InputError or TypeError"),
    ("python_multiline_message", "Python: an InputError message of more than one line"),
]


_WORKER = None  # (seed, ctx, binary, scratch, timeout, env, failures), set before the pool forks


def worker_run(k):
    seed, ctx, binary, scratch, timeout, env, failures = _WORKER
    case = None
    try:
        case = make_case(seed, k, ctx)
        return execute(case, binary, scratch, timeout, env, failures)
    except Exception as e:  # a harness error is reported, never hidden
        return {"k": k, "cmd": case.cmd if case else COMMANDS[k % len(COMMANDS)],
                "rc": "harness-error", "secs": 0,
                "mutated": bool(case and case.mutated),
                "mutations": case.mutations if case else [],
                "findings": [["harness_error", repr(e)]],
                "traceback": traceback.format_exc(limit=8),
                "argv": case.argv() if case else []}


def file_sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def read_journal(path):
    """The results of runs.jsonl; a line cut by a kill (the last one) is dropped and rerun."""
    results, seen = [], set()
    if not path.exists():
        return results
    for line in path.read_text().splitlines():
        try:
            r = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(r, dict) and "k" in r and r["k"] not in seen:
            seen.add(r["k"])
            results.append(r)
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--slow", type=float, default=20.0)
    ap.add_argument("--binary", default=str(REPO / "build" / "bin" / "pkmopt"))
    ap.add_argument("--out", default="/tmp/pkmopt-campaign")
    ap.add_argument("--only", type=int, default=None, help="run only run K and print it")
    ap.add_argument("--omp-threads", type=int, default=1)
    ap.add_argument("--resume", action="store_true",
                    help="continue a killed campaign in --out (same --seed and binary)")
    args = ap.parse_args()
    binary = os.path.abspath(args.binary)
    if not os.access(binary, os.X_OK):
        print(f"mutation_campaign: {binary}: not an executable", file=sys.stderr)
        return 2
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ)
    env["OMP_NUM_THREADS"] = str(args.omp_threads)
    env["LC_ALL"] = "C"
    env.pop("PKMOPT", None)
    t_prep = time.monotonic()
    try:
        ctx = prepare(binary, out, env, print)
    except SystemExit as e:
        print(e, file=sys.stderr)
        return 2
    t_prep = time.monotonic() - t_prep
    scratch = out / "runs"
    failures = out / "failures"
    if args.only is not None:
        case = make_case(args.seed, args.only, ctx)
        res = execute(case, binary, scratch, args.timeout, env, failures)
        print(json.dumps(res, indent=2, default=str))
        return 1 if res["findings"] else 0
    # The campaign's identity: a resumed campaign must run the same binary with the same seed.
    identity = {"seed": args.seed, "binary_sha256": file_sha256(binary)}
    ident_path = out / "campaign.json"
    journal = out / "runs.jsonl"
    results = []
    if args.resume and ident_path.exists():
        old = json.loads(ident_path.read_text())
        if old != identity:
            print(f"mutation_campaign: --resume: {ident_path} holds {old}, this campaign is "
                  f"{identity} (the same --seed and binary are needed)", file=sys.stderr)
            return 2
        results = read_journal(journal)
        print(f"  resuming: {len(results)} runs already in {journal}", file=sys.stderr)
    else:
        for d in (scratch, failures):
            if d.exists():
                shutil.rmtree(d)
        journal.unlink(missing_ok=True)
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir(parents=True)
    ident_path.write_text(json.dumps(identity) + "\n")
    done_ks = {r["k"] for r in results}
    todo = [k for k in range(args.runs) if k not in done_ks]
    t0 = time.monotonic()
    global _WORKER
    _WORKER = (args.seed, ctx, binary, scratch, args.timeout, env, failures)
    # Processes, not threads: the harness's own work (mutating, checking outputs) runs on every
    # core. Forked workers inherit the prepared inputs.
    pool = concurrent.futures.ProcessPoolExecutor(
        max_workers=max(1, args.jobs), mp_context=multiprocessing.get_context("fork"))
    done = 0
    with pool as ex, open(journal, "a") as jf:
        for res in ex.map(worker_run, todo, chunksize=8):
            jf.write(json.dumps(res, default=str) + "\n")
            jf.flush()
            results.append(res)
            done += 1
            if done % 100 == 0 or done == len(todo):
                bad = sum(1 for r in results if r["findings"])
                print(f"  {len(results)}/{args.runs} runs, {bad} breaking the contract, "
                      f"{done / (time.monotonic() - t0):.1f} runs/s", file=sys.stderr)
    elapsed = time.monotonic() - t0
    results.sort(key=lambda r: r["k"])
    shutil.rmtree(scratch, ignore_errors=True)
    summary = summarise(results, args, binary, elapsed, t_prep, ctx, done)
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    tmp = journal.with_suffix(".jsonl.tmp")
    with open(tmp, "w") as f:
        for r in results:
            f.write(json.dumps(r, default=str) + "\n")
    os.replace(tmp, journal)
    print_summary(summary, out)
    return 1 if summary["contract_failures"] else 0


def summarise(results, args, binary, elapsed, t_prep, ctx, runs_now):
    per_cmd = {}
    hist = {}
    cats = {c: [] for c, _ in CATEGORY_LABELS}
    cats["harness_error"] = []
    for r in results:
        rc = "timeout" if r["rc"] is None else str(r["rc"])
        hist[rc] = hist.get(rc, 0) + 1
        pc = per_cmd.setdefault(r["cmd"], {"runs": 0, "mutated": 0, "exit_status": {},
                                           "failures": 0})
        pc["runs"] += 1
        pc["mutated"] += bool(r["mutated"])
        pc["exit_status"][rc] = pc["exit_status"].get(rc, 0) + 1
        if r["findings"]:
            pc["failures"] += 1
        for cat, _ in r["findings"]:
            cats.setdefault(cat, []).append(r["k"])
    for c, pc in per_cmd.items():
        pc["exit0_share"] = round(pc["exit_status"].get("0", 0) / pc["runs"], 3)
        pc["exit2_share"] = round(pc["exit_status"].get("2", 0) / pc["runs"], 3)
    failing = [r for r in results if r["findings"]]
    return {
        "binary": binary, "binary_sha256": file_sha256(binary), "seed": args.seed, "runs": len(results), "jobs": args.jobs,
        "timeout_s": args.timeout, "slow_s": args.slow, "elapsed_s": round(elapsed, 1),
        "prep_s": round(t_prep, 1), "runs_this_invocation": runs_now,
        "runs_per_second": round(runs_now / elapsed, 2) if elapsed else None,
        "mutated_runs": sum(1 for r in results if r["mutated"]),
        "per_command": dict(sorted(per_cmd.items())),
        "exit_status_histogram": dict(sorted(hist.items())),
        "crashes": len(cats["crash"]), "hangs": len(cats["hang"]),
        "nan_outputs": len(cats["nan_output"]),
        "exit1_on_mutated_input": len(cats["exit1_mutated"]),
        "exit1_on_unmutated_input": len(cats["exit1_unmutated"]),
        "other_exit_statuses": len(cats["bad_exit_status"]),
        "multiline_or_malformed_exit2_messages": len(cats["exit2_message"]),
        "exit2_with_leftover_files": len(cats["exit2_leftover"]),
        "exit3_without_warning": len(cats["exit3_no_warning"]),
        "baseline_failures": len(cats["baseline_failed"]),
        "harness_errors": len(cats["harness_error"]),
        "contract_failures": len(failing),
        "info_slow_runs": [{"k": r["k"], "cmd": r["cmd"], "secs": r["secs"], "rc": r["rc"],
                            "mutations": r["mutations"]}
                           for r in results if r["rc"] is not None and r["secs"] > args.slow],
        "info_exit2_new_empty_folders": [r["k"] for r in results if r.get("exit2_new_dirs")],
        "info_nan_possibly_echoed_from_input": [r["k"] for r in results
                                                if r.get("nan_echo_notes")],
        "failing_runs": {cat: ks for cat, ks in cats.items() if ks},
        "failures": [{"k": r["k"], "cmd": r["cmd"], "rc": r["rc"],
                      "findings": r["findings"], "mutations": r["mutations"]}
                     for r in failing],
        "seed_notes": ctx.seed_notes,
    }


def print_summary(s, out):
    print(f"pkmopt mutation campaign: {s['runs']} runs ({s['mutated_runs']} mutated), seed "
          f"{s['seed']}; this invocation {s['runs_this_invocation']} runs in {s['elapsed_s']} s, "
          f"{s['runs_per_second']} runs/s")
    print("per command: runs, exit 0 share, exit 2 share, failures")
    for c, pc in s["per_command"].items():
        print(f"  {c:22s} {pc['runs']:5d}  {pc['exit0_share']:6.1%}  {pc['exit2_share']:6.1%}"
              f"  {pc['failures']}")
    print("exit status histogram: " + ", ".join(f"{k}: {v}" for k, v in
                                               s["exit_status_histogram"].items()))
    for key, label in [("crashes", "crashes"), ("hangs", "hangs"), ("nan_outputs", "NaN outputs"),
                       ("exit1_on_mutated_input", "exit 1 on mutated input"),
                       ("exit1_on_unmutated_input", "exit 1 on unmutated input"),
                       ("other_exit_statuses", "other exit statuses"),
                       ("multiline_or_malformed_exit2_messages",
                        "exit-2 messages not exactly one 'pkmopt: error:' line"),
                       ("exit2_with_leftover_files", "exit 2 with leftover files"),
                       ("exit3_without_warning", "exit 3 without a warning line"),
                       ("baseline_failures", "unmutated seeds failing"),
                       ("harness_errors", "harness errors")]:
        print(f"  {label}: {s[key]}")
    slow = s["info_slow_runs"]
    print(f"  (not counted) runs that ended after more than {s['slow_s']} s: {len(slow)}"
          + (f" (longest {max(r['secs'] for r in slow):.1f} s: "
             f"{', '.join(str(r['k']) for r in slow[:20])})" if slow else ""))
    print(f"  (not counted) exit 2 leaving only new empty folders: "
          f"{len(s['info_exit2_new_empty_folders'])}; NaN words in text outputs whose input "
          f"holds one: {len(s['info_nan_possibly_echoed_from_input'])}")
    print(f"runs breaking the contract: {s['contract_failures']}"
          + (f" (kept in {out / 'failures'})" if s["contract_failures"] else ""))
    for cat, ks in s["failing_runs"].items():
        print(f"  {cat}: runs {', '.join(map(str, ks[:20]))}{' ...' if len(ks) > 20 else ''}")
    print(f"summary: {out / 'summary.json'}")


if __name__ == "__main__":
    sys.exit(main())
