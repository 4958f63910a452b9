#!/usr/bin/env python3
"""Snapshot every output of the shipped studies and example machines, and compare two snapshots.

A change that should not change any result (a refactoring, a faster kernel) is checked by
taking a snapshot with the binary before it and one with the binary after it:

  /usr/bin/python3 scripts/compare_outputs.py snapshot --binary OLD/build/bin/pkmopt --out before
  /usr/bin/python3 scripts/compare_outputs.py snapshot --binary build/bin/pkmopt --out after
  /usr/bin/python3 scripts/compare_outputs.py compare before after

`snapshot` runs, from the repository this script is in:
  * every study file of studies/library (and its folders) with `pkmopt validate` and
    `pkmopt run` (NSGA-II at most 12 generations, hybrid polish at most 10 iterations, as the
    shipped_fronts test), then `pkmopt export` as CSV, JSON and HTML of each design study;
  * every study folder's run.sh in its quick form (QUICK=1);
  * every machine file of examples/ with `describe`, `draw`, `workspace` (50 mm grid), `analyze`
    at the first 40 workspace points (with compliance and a wrench), `fk` at the actuator
    coordinates `analyze` gave for the first point, and a short `trajectory` helix there.
Each command's standard output, standard error, exit status and every file it wrote are kept.
Values that differ from run to run by nature (wall-clock seconds, dates, the binary's version
line, a run's lock file) are masked or left out before the files are stored; the commands run in
one fixed scratch folder (a study's hash covers the paths it names), so two snapshots must not
be taken at once.

`compare` prints every file that differs or exists in one snapshot only, and exits 1 if any.
Run it with two cores free: a snapshot takes about 5 minutes.
"""
import argparse
import filecmp
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
TIMEOUT = 900


def mask(text, scratch):
    text = text.replace(str(scratch), "SCRATCH").replace(str(ROOT), "ROOT")
    # wall-clock seconds in summaries and printed lines
    text = re.sub(r'"(wall_seconds|seconds|elapsed_seconds|time_seconds|started|finished|'
                  r'created|date|timestamp|pkmopt_version|version|git_commit)": *("[^"]*"|[-0-9.eE+]+)',
                  r'"\1": MASKED', text)
    text = re.sub(r"\b\d+(\.\d+)? ?(s|ms|µs)\b(?=[ ,)\n;]|$)", "T s", text)
    text = re.sub(r"\d{4}-\d{2}-\d{2}[T ]\d{2}:\d{2}:\d{2}(\.\d+)?Z?", "DATE", text)
    text = re.sub(r"(wall_seconds|seconds)=[-0-9.eE+]+", r"\1=MASKED", text)
    # progress lines come every few seconds of wall-clock time: how many is not a result
    text = re.sub(r"(?m)^pkmopt: run: \d+/\d+ evaluations .*\n", "", text)
    return text


def store(src_dir, dest_dir, scratch):
    for path in sorted(src_dir.rglob("*")):
        if not path.is_file() or path.name == "run.lock":  # run.lock holds a process id
            continue
        target = dest_dir / path.relative_to(src_dir)
        target.parent.mkdir(parents=True, exist_ok=True)
        data = path.read_bytes()
        if path.suffix in {".png", ".stl"}:
            target.write_bytes(data)
            continue
        try:
            text = data.decode()
        except UnicodeDecodeError:
            target.write_bytes(data)
            continue
        target.write_text(mask(text, scratch))


class Snapshot:
    def __init__(self, binary, out, scratch):
        self.binary = str(pathlib.Path(binary).resolve())
        self.out = out
        self.scratch = scratch
        self.count = 0

    def run(self, name, args, cwd=None, env=None, files=None):
        """Runs one command; keeps its streams, status and the files under `files`."""
        self.count += 1
        work = self.scratch / name
        work.mkdir(parents=True, exist_ok=True)
        cmd = [a if a != "PKMOPT" else self.binary for a in args]
        proc = subprocess.run(cmd, cwd=cwd or work, env=env, capture_output=True, text=True,
                              timeout=TIMEOUT)
        dest = self.out / name
        dest.mkdir(parents=True, exist_ok=True)
        (dest / "_command.txt").write_text(
            mask(" ".join(args), self.scratch) + f"\nexit {proc.returncode}\n")
        (dest / "_stdout.txt").write_text(mask(proc.stdout, self.scratch))
        (dest / "_stderr.txt").write_text(mask(proc.stderr, self.scratch))
        if files is not None and files.exists():
            store(files, dest / "files", self.scratch)
        return proc


def reduced_copy(path, scratch):
    text = path.read_text()
    text = re.sub(r"generations: *(\d+)", lambda m: f"generations: {min(int(m.group(1)), 12)}",
                  text)
    text = re.sub(r"polish_iterations: *(\d+)",
                  lambda m: f"polish_iterations: {min(int(m.group(1)), 10)}", text)
    copy = scratch / "studies" / path.relative_to(ROOT / "studies/library")
    copy.parent.mkdir(parents=True, exist_ok=True)
    # the study's folder comes along: catalogs, machine files and CSVs it names by relative path
    if path.parent != ROOT / "studies/library" and not (copy.parent / "_copied").exists():
        shutil.copytree(path.parent, copy.parent, dirs_exist_ok=True)
        (copy.parent / "_copied").write_text("")
    if path.parent == ROOT / "studies/library":
        shutil.copytree(ROOT / "studies/library/catalogs", scratch / "studies/catalogs",
                        dirs_exist_ok=True)
    copy.write_text(text)
    return copy


def snapshot_studies(snap):
    library = ROOT / "studies/library"
    files = sorted(library.glob("*.yaml")) + sorted(library.glob("*/*.yaml"))
    for path in files:
        if not re.search(r"^optimizer:", path.read_text(), re.M):
            continue
        rel = path.relative_to(library).with_suffix("")
        tag = str(rel).replace("/", "__")
        copy = reduced_copy(path, snap.scratch)
        snap.run(f"study/{tag}/validate", ["PKMOPT", "validate", str(copy)])
        out = snap.scratch / f"study/{tag}/run/out"
        snap.run(f"study/{tag}/run", ["PKMOPT", "run", str(copy), "--out", str(out),
                                      "--threads", "2"], files=out)
        if (out / "pareto.json").exists() and "machine:" in path.read_text():
            for fmt in ("csv", "json", "html"):
                dest = snap.scratch / f"study/{tag}/export-{fmt}/out"
                dest.mkdir(parents=True, exist_ok=True)
                target = dest / {"csv": "front.csv", "json": "front.json", "html": "report.html"}[fmt]
                snap.run(f"study/{tag}/export-{fmt}",
                         ["PKMOPT", "export", str(out), "--format", fmt, "--out", str(target)],
                         files=dest)
    for script in sorted(library.glob("*/run.sh")):
        tag = script.parent.name
        out = snap.scratch / f"runsh/{tag}/out"
        env = dict(os.environ, PKMOPT=snap.binary, QUICK="1")
        snap.run(f"runsh/{tag}", ["bash", str(script), str(out)], env=env, files=out)


def snapshot_machines(snap):
    for machine in sorted((ROOT / "examples").glob("*.yaml")):
        tag = f"machine/{machine.stem}"
        m = str(machine)
        snap.run(f"{tag}/describe", ["PKMOPT", "describe", m])
        draw = snap.scratch / f"{tag}/draw/out"
        draw.mkdir(parents=True, exist_ok=True)
        snap.run(f"{tag}/draw", ["PKMOPT", "draw", m, "--out", str(draw / "machine.svg")],
                 files=draw)
        ws = snap.scratch / f"{tag}/workspace/out"
        proc = snap.run(f"{tag}/workspace",
                        ["PKMOPT", "workspace", m, "--resolution", "0.05", "--out", str(ws)],
                        files=ws)
        points = ws / "points.csv"
        if proc.returncode != 0 or not points.exists():
            continue
        lines = points.read_text().splitlines()[1:41]
        if not lines:
            continue
        poses = snap.scratch / f"{tag}/poses.csv"
        poses.write_text("x,y,z\n" + "".join(",".join(l.split(",")[:3]) + "\n" for l in lines))
        az = snap.scratch / f"{tag}/analyze/out"
        az.mkdir(parents=True, exist_ok=True)
        snap.run(f"{tag}/analyze", ["PKMOPT", "analyze", m, "--poses", str(poses), "--compliance",
                                    "--wrench", "100,-50,200,5,-3,2", "--out",
                                    str(az / "analyze.csv")], files=az)
        table = (az / "analyze.csv")
        if table.exists():
            rows = table.read_text().splitlines()
            header = rows[0].split(",")
            first = rows[1].split(",")
            q = [first[i] for i, h in enumerate(header) if re.fullmatch(r"q_\d+", h)]
            if q:
                snap.run(f"{tag}/fk", ["PKMOPT", "fk", m, "--q", ",".join(q)])
        centre = ",".join(lines[0].split(",")[:3])
        tr = snap.scratch / f"{tag}/trajectory/out"
        tr.mkdir(parents=True, exist_ok=True)
        snap.run(f"{tag}/trajectory",
                 ["PKMOPT", "trajectory", m, "--helix", "--helix-centre", centre,
                  "--helix-radius", "0.005,0.002", "--helix-height", "0.002,0.002",
                  "--samples", "21", "--out", str(tr / "trajectory.csv")], files=tr)


def snapshot(args):
    out = pathlib.Path(args.out).resolve()
    if out.exists():
        sys.exit(f"compare_outputs: {out} exists; give a new folder")
    out.mkdir(parents=True)
    # One fixed scratch folder: a study's hash covers the paths it names (a catalog file).
    scratch = pathlib.Path(tempfile.gettempdir()) / "pkmopt-snapshot"
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir()
    try:
        snap = Snapshot(args.binary, out, scratch)
        snapshot_machines(snap)
        snapshot_studies(snap)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    (out / "_snapshot.json").write_text(json.dumps({"commands": snap.count}) + "\n")
    print(f"compare_outputs: {snap.count} commands -> {out}")


def compare(args):
    a, b = pathlib.Path(args.a), pathlib.Path(args.b)
    files_a = {p.relative_to(a) for p in a.rglob("*") if p.is_file()}
    files_b = {p.relative_to(b) for p in b.rglob("*") if p.is_file()}
    differ = []
    for rel in sorted(files_a | files_b):
        if rel not in files_b:
            differ.append(f"only in {a}: {rel}")
        elif rel not in files_a:
            differ.append(f"only in {b}: {rel}")
        elif not filecmp.cmp(a / rel, b / rel, shallow=False):
            differ.append(f"differs: {rel}")
    for line in differ:
        print(line)
    print(f"compare_outputs: {len(files_a | files_b)} files, {len(differ)} differ")
    return 1 if differ else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("snapshot")
    s.add_argument("--binary", required=True)
    s.add_argument("--out", required=True)
    c = sub.add_parser("compare")
    c.add_argument("a")
    c.add_argument("b")
    args = parser.parse_args()
    if args.command == "snapshot":
        snapshot(args)
        return 0
    return compare(args)


if __name__ == "__main__":
    sys.exit(main())
