#!/usr/bin/env python3
"""studies/distribute.cpp: `mpirun -np N pkmopt run` against the run on one process.

  * the same study gives byte-identical pareto.csv, pareto.json, evaluations.csv and journal.txt
    for the run without MPI on 1 and 2 threads and for mpirun -np 1, 3 and 4 (a design study and
    a benchmark study);
  * a run whose mpirun is killed (SIGKILL) resumes under MPI with another N and then without MPI,
    re-evaluating nothing the journal holds, and ends with the uninterrupted run's files;
  * a worker killed mid-run (SIGKILL) stops the run with a line naming it and what it held, the
    journal intact (the resumed run reads it without a damaged line and ends with the same files);
  * a worker that does not answer within --worker-timeout (stopped with SIGSTOP) stops the run
    with exit status 4 and a line naming its rank, PID and designs; the run resumes;
  * `pkmopt analyze` (compliance and mode-shape columns, a quoted pass-through column, to a file
    and to stdout) and `pkmopt workspace` (fixed resolution; tilt cone with the volume tolerance)
    under mpirun write the files the run on one process writes;
  * a bad study file under mpirun gives one `pkmopt: error:` line and exit status 2, and so does
    a synthesis study (it runs on one process).

Usage: mpi_runs_test.py PKMOPT_BINARY SOURCE_DIR SCRATCH_DIR
mpirun runs with --oversubscribe (more ranks than cores) and --allow-run-as-root.
"""
import json
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import time

import yaml

BINARY, SOURCE, SCRATCH = (pathlib.Path(a).resolve() for a in sys.argv[1:4])
MPIRUN = ["mpirun", "--oversubscribe", "--allow-run-as-root"]
# Under scripts/sanitize.sh: Open MPI's components are unloaded at MPI_Finalize, and what they
# keep to the end is reported by LeakSanitizer without a module to suppress it by. The ranks run
# without leak checking; every other test checks pkmopt's own memory.
MPI_ENV = dict(os.environ)
if "ASAN_OPTIONS" in MPI_ENV:
    MPI_ENV["ASAN_OPTIONS"] += ":detect_leaks=0"
FILES = ["pareto.csv", "evaluations.csv", "journal.txt"]

# The shipped hexapod-quick study with a smaller budget (written as JSON, which is YAML).
DESIGN = yaml.safe_load((SOURCE / "studies" / "library" / "hexapod-quick.yaml").read_text())
DESIGN["optimizer"].update(population=24, generations=8, seed=5)


def benchmark(generations):
    return {"study": "mpi-zdt1", "problem": {"benchmark": "zdt1", "variables": 30},
            "optimizer": {"algorithm": "nsga2", "population": 100, "generations": generations,
                          "seed": 11}}


failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print(f"FAIL: {what}", flush=True)


def write_study(name, study):
    path = SCRATCH / f"{name}.yaml"
    path.write_text(json.dumps(study))
    return path


def run(args, ranks=None, timeout=600, **kw):
    cmd = ([*MPIRUN, "-np", str(ranks)] if ranks else []) + [str(BINARY), *map(str, args)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=SCRATCH,
                          env=MPI_ENV if ranks else None, **kw)


def same_files(a, b, names):
    return [n for n in names if (a / n).read_bytes() != (b / n).read_bytes()]


def pkmopt_lines(stderr):
    return [l for l in stderr.splitlines() if l.startswith("pkmopt:")]


def wait_for_lines(path, count, proc, limit=120):
    start = time.monotonic()
    while time.monotonic() - start < limit and proc.poll() is None:
        if path.exists() and path.read_bytes().count(b"\n") >= count:
            return True
        time.sleep(0.02)
    return False


def wait_until_gone(lock):
    # A rank 0 orphaned by a killed mpirun ends on its own; the run lock names its PID.
    for _ in range(600):
        try:
            pid = int(lock.read_text().split()[0])
            os.kill(pid, 0)
        except (OSError, ValueError, IndexError):
            return
        time.sleep(0.05)


def test_same_files_for_any_rank_count():
    for name, study, names in [("design", DESIGN, FILES + ["pareto.json"]),
                               ("bench", benchmark(40), FILES)]:
        path = write_study(name, study)
        ref = SCRATCH / f"{name}-t1"
        r = run(["run", path, "--out", ref, "--threads", "1", "--no-progress"])
        check(r.returncode == 0, f"{name}: serial run exit {r.returncode}: {r.stderr}")
        variants = [(None, ["--threads", "2"]), (1, []), (3, []), (4, []), (3, ["--threads", "2"])]
        for ranks, extra in variants:
            out = SCRATCH / f"{name}-np{ranks}-{'-'.join(extra) or 'default'}"
            r = run(["run", path, "--out", out, "--no-progress", *extra], ranks=ranks)
            label = f"{name}: -np {ranks} {' '.join(extra)}"
            check(r.returncode == 0, f"{label}: exit {r.returncode}: {r.stderr}")
            if r.returncode == 0:
                differ = same_files(ref, out, names)
                check(not differ, f"{label}: differs from the serial run in {differ}")
                check(r.stdout.count("\n") == 1, f"{label}: expected one summary line (rank 0 "
                      f"only), found {r.stdout!r}")
                ranks_said = json.loads((out / "summary.json").read_text())["mpi_ranks"]
                check(ranks_said == (ranks or 1),
                      f"{label}: summary.json says mpi_ranks {ranks_said}")


def test_killed_mpirun_resumes_with_other_ranks_and_without_mpi():
    path = write_study("long", benchmark(250))
    ref = SCRATCH / "long-ref"
    check(run(["run", path, "--out", ref, "--threads", "1", "--no-progress"]).returncode == 0,
          "long: reference run failed")
    total = (ref / "journal.txt").read_bytes().count(b"\n") - 1
    out = SCRATCH / "long-killed"
    for ranks, lines in [(3, total // 4), (2, total // 2)]:
        # SIGKILL to mpirun and every rank at once, as a batch system does at its time limit (a
        # rank whose mpirun alone is killed runs on to the end of the study).
        proc = subprocess.Popen([*MPIRUN, "-np", str(ranks), str(BINARY), "run", str(path),
                                 "--out", str(out), "--no-progress"]
                                + (["--resume"] if (out / "journal.txt").exists() else []),
                                cwd=SCRATCH, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True, env=MPI_ENV)
        reached = wait_for_lines(out / "journal.txt", lines, proc)
        # The ranks are in process groups of their own, in mpirun's session.
        subprocess.run(["pkill", "-KILL", "-s", str(proc.pid)], check=False)
        proc.wait()
        check(reached, f"long: the journal never reached {lines} lines under -np {ranks}")
        wait_until_gone(out / "run.lock")
    held = (out / "journal.txt").read_bytes()
    complete = held.count(b"\n") - 1  # a cut last line does not count
    check(0 < complete < total, f"long: killed twice, the journal holds {complete} of {total}")
    r = run(["run", path, "--out", out, "--resume", "--threads", "1", "--no-progress"])
    check(r.returncode == 0, f"long: resume without MPI exit {r.returncode}: {r.stderr}")
    if r.returncode == 0:
        summary = json.loads((out / "summary.json").read_text())
        check(summary["evaluations_loaded_from_journal"] == complete,
              f"long: loaded {summary['evaluations_loaded_from_journal']}, journal held "
              f"{complete}")
        check(summary["evaluations_new"] == total - complete,
              f"long: evaluated {summary['evaluations_new']} again, expected {total - complete}")
        differ = same_files(ref, out, FILES)
        check(not differ, f"long: resumed run differs from the uninterrupted one in {differ}")


def start_long_run(out, extra=()):
    """mpirun -np 3 on the long ZDT1 study, in a session of its own; returns (process, the three
    rank PIDs in rank order: rank 0 first), once the run has got going."""
    path = write_study("long", benchmark(250))
    proc = subprocess.Popen([*MPIRUN, "-np", "3", str(BINARY), "run", str(path), "--out",
                             str(out), "--no-progress", *extra], cwd=SCRATCH,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, env=MPI_ENV)
    check(wait_for_lines(out / "journal.txt", 3000, proc), f"{out.name}: the run never got going")
    children = map(int, subprocess.run(["ps", "--ppid", str(proc.pid), "-o", "pid="],
                                       capture_output=True, text=True).stdout.split())
    ranks = [pid for _, pid in sorted((rank_of(pid), pid) for pid in children)]
    check(len(ranks) == 3, f"{out.name}: expected 3 ranks under mpirun, found {ranks}")
    return path, proc, ranks


def rank_of(pid):
    """The MPI rank of a process under mpirun (Open MPI's OMPI_COMM_WORLD_RANK); its PID when the
    environment cannot be read. PIDs alone do not give the start order: they wrap around."""
    try:
        for item in pathlib.Path(f"/proc/{pid}/environ").read_bytes().split(b"\0"):
            if item.startswith(b"OMPI_COMM_WORLD_RANK="):
                return int(item.split(b"=", 1)[1])
    except (OSError, ValueError):
        pass
    return pid


def finish_and_resume(path, proc, out, ranks):
    """Waits for the stopped run, then resumes it under -np `ranks`: the journal must be whole
    and the resumed run end with the uninterrupted run's files. Returns the stopped run's
    pkmopt lines."""
    try:
        _, err = proc.communicate(timeout=120)
    finally:
        subprocess.run(["pkill", "-KILL", "-s", str(proc.pid)], check=False)
    check(not (out / "pareto.csv").exists(), f"{out.name}: a stopped run wrote pareto.csv")
    wait_until_gone(out / "run.lock")
    r = run(["run", path, "--out", out, "--resume", "--no-progress"], ranks=ranks)
    check(r.returncode == 0, f"{out.name}: resume exit {r.returncode}: {r.stderr}")
    check("damaged" not in r.stderr, f"{out.name}: the journal was damaged: {r.stderr}")
    ref = SCRATCH / "long-ref"
    if r.returncode == 0 and ref.exists():
        differ = same_files(ref, out, FILES)
        check(not differ, f"{out.name}: resumed run differs in {differ}")
    return pkmopt_lines(err)


def test_killed_worker_is_named_and_the_journal_resumes():
    # In about one run in four to eight on Debian 12 (Open MPI 4.1), mpirun's standard error of a
    # job whose worker was killed holds mpirun's own two notices but not rank 0's line, which the
    # other runs show between them (rank 0's handler has odls_base_sigkill_timeout, 1 s, to write
    # it). Why the line is lost is not known yet: until it is, the scenario is tried up to three
    # times, and a handler that never writes still fails every one.
    for attempt in range(3):
        out = SCRATCH / f"worker-killed-{attempt}"
        path, proc, ranks = start_long_run(out)
        if len(ranks) == 3:
            os.kill(ranks[1], signal.SIGKILL)  # a worker
        lines = finish_and_resume(path, proc, out, 2)
        if lines:
            break
        print("worker: no line of rank 0 in mpirun's standard error; trying again", flush=True)
    check(proc.returncode != 0, "worker: a run that lost a worker exited 0")
    check(len(lines) == 1 and "stopped by mpirun" in lines[0] and f"(pid {ranks[1]})" in lines[0]
          and "--resume" in lines[0], f"worker: expected one line naming the rank, found {lines}")


def test_silent_worker_stops_the_run_with_status_4():
    # A worker stopped with SIGSTOP holds its designs and never answers: a hung evaluation.
    out = SCRATCH / "timeout"
    path, proc, ranks = start_long_run(out, ["--worker-timeout", "2"])
    stopped = ranks[2] if len(ranks) == 3 else None
    if stopped:
        os.kill(stopped, signal.SIGSTOP)
    lines = finish_and_resume(path, proc, out, 3)
    check(proc.returncode == 4, f"timeout: expected exit 4, found {proc.returncode}: {lines}")
    check(len(lines) == 1 and f"(pid {stopped} on " in lines[0]
          and re.search(r"MPI rank \d+ \(pid \d+ on .*\) did not answer within "
                        r"--worker-timeout 2 s; it held batch \d+ design", lines[0])
          and "--resume" in lines[0],
          f"timeout: expected one line naming the stopped rank and its designs, found {lines}")


def test_analyze_and_workspace_write_the_files_of_one_process():
    # 500 poses with a pass-through text column, compliance columns and mode shapes.
    poses = SCRATCH / "poses.csv"
    rows = ["x,y,z,rx,ry,rz,label"]
    for i in range(500):
        rows.append(f"{0.2 * ((i * 37) % 100 / 100 - 0.5):.4f},{0.2 * ((i * 53) % 100 / 100 - 0.5):.4f},"
                    f"{0.7 + 0.4 * ((i * 71) % 100) / 100:.4f},{(i % 7) - 3},{(i % 5) - 2},"
                    f"{(i % 11) - 5},\"pose {i}, \"\"quoted\"\"\"")
    poses.write_text("\n".join(rows) + "\n")
    machine = SOURCE / "examples" / "hexapod_masses.yaml"
    for extra in [["--compliance"], ["--mode-shapes"]]:
        outs = []
        for ranks in [None, 3]:
            out = SCRATCH / f"analyze-{ranks}{extra[0]}.csv"
            r = run(["analyze", machine, "--poses", poses, "--out", out, *extra], ranks=ranks)
            check(r.returncode == 0, f"analyze -np {ranks} {extra}: exit {r.returncode}: {r.stderr}")
            outs.append(out)
        if all(o.exists() for o in outs):
            check(outs[0].read_bytes() == outs[1].read_bytes(),
                  f"analyze {extra}: -np 3 differs from one process")
    r1 = run(["analyze", machine, "--poses", poses])
    r4 = run(["analyze", machine, "--poses", poses], ranks=4)
    check(r1.stdout == r4.stdout and r4.stdout.count("\n") == 501,
          "analyze to stdout: -np 4 differs from one process (or printed more than once)")
    for args in [["--resolution", "0.04"], ["--tilt", "10", "--slice-metric", "max_leg_force"]]:
        dirs = []
        for ranks in [None, 3]:
            out = SCRATCH / f"ws-{ranks}-{args[0]}"
            r = run(["workspace", SOURCE / "examples" / "hexapod.yaml", "--out", out, *args],
                    ranks=ranks)
            check(r.returncode == 0, f"workspace -np {ranks} {args}: exit {r.returncode}: "
                  f"{r.stderr}")
            check(r.stdout.count("\n") == 1, f"workspace -np {ranks}: expected one summary "
                  f"line, found {r.stdout!r}")
            dirs.append(out)
        if all(d.exists() for d in dirs):
            names = sorted(p.name for p in dirs[0].iterdir())
            check(names == sorted(p.name for p in dirs[1].iterdir()),
                  f"workspace {args}: other files under -np 3")
            for name in names:
                a, b = (d / name for d in dirs)
                if name == "summary.json":  # the same but for the time it took
                    ja, jb = json.loads(a.read_text()), json.loads(b.read_text())
                    ja.pop("seconds", None), jb.pop("seconds", None)
                    check(ja == jb, f"workspace {args}: summary.json differs under -np 3")
                else:
                    check(a.read_bytes() == b.read_bytes(),
                          f"workspace {args}: {name} differs under -np 3")


def test_bad_study_gives_one_line():
    path = SCRATCH / "bad.yaml"
    path.write_text("study: bad\nmachine: 3\n")
    r = run(["run", path, "--out", SCRATCH / "bad-out", "--no-progress"], ranks=3)
    lines = pkmopt_lines(r.stderr)
    check(r.returncode == 2, f"bad: expected exit 2, found {r.returncode}")
    check(len(lines) == 1 and lines[0].startswith("pkmopt: error: ") and "bad.yaml:2" in lines[0],
          f"bad: expected one error line from rank 0, found {lines}")
    check(not (SCRATCH / "bad-out").exists(), "bad: a refused study left its --out folder")


def test_synthesis_runs_on_one_process():
    path = SCRATCH / "synthesis.yaml"
    path.write_text("study: syn\ncandidates: [hexapod, linear_delta]\n"
                    "task: {region: {shape: box, centre: [0, 0, 0], size: [0.3, 0.3, 0.2]}}\n"
                    "objectives: [{minimize: tcp_deflection_max}, {minimize: swept_volume}]\n"
                    "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 1}\n")
    r = run(["run", path, "--out", SCRATCH / "syn-out", "--no-progress"], ranks=2)
    lines = pkmopt_lines(r.stderr)
    check(r.returncode == 2, f"synthesis: expected exit 2, found {r.returncode}")
    check(len(lines) == 1 and "expected one process for a synthesis study" in lines[0],
          f"synthesis: expected one error line, found {lines}")
    check(not (SCRATCH / "syn-out").exists(), "synthesis: a refused run left its --out folder")


def main():
    if shutil.which("mpirun") is None:
        print("mpirun not found (scripts/install-deps.sh installs openmpi-bin)")
        return 1
    shutil.rmtree(SCRATCH, ignore_errors=True)
    SCRATCH.mkdir(parents=True)
    tests = [test_same_files_for_any_rank_count,
             test_killed_mpirun_resumes_with_other_ranks_and_without_mpi,
             test_killed_worker_is_named_and_the_journal_resumes,
             test_silent_worker_stops_the_run_with_status_4,
             test_analyze_and_workspace_write_the_files_of_one_process,
             test_bad_study_gives_one_line,
             test_synthesis_runs_on_one_process]
    for test in tests:
        start = time.monotonic()
        test()
        print(f"{test.__name__}: {time.monotonic() - start:.1f} s", flush=True)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
