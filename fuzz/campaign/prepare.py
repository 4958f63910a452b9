"""Preparation of the seed inputs every case starts from. (the mutation campaign: fuzz/campaign/main.py)."""

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

from .common import CAMPAIGN_VERSION, REPO  # noqa: F401
from .values import fmt, parse_doc_fields, s2b  # noqa: F401
from .cases import read_text  # noqa: F401
# Preparation of the seed inputs
# ----------------------------------------------------------------------------------------------

class Context:
    pass


def tiny_study(text, population=12, generations=2):
    text = re.sub(r"population: \d+", f"population: {population}", text)
    text = re.sub(r"generations: \d+", f"generations: {generations}", text)
    text = re.sub(r"points: (\d+), seed", "points: 4, seed", text)
    text = re.sub(r"max_evaluations: \d+", "max_evaluations: 40", text)
    text = re.sub(r"polish_iterations: \d+", "polish_iterations: 3", text)
    text = re.sub(r"catalog: (\.\./)?catalogs/", "catalog: catalogs/", text)
    return text


def prep_run(binary, argv, cwd, env, timeout=120):
    p = subprocess.run([binary] + argv, cwd=cwd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, timeout=timeout, stdin=subprocess.DEVNULL)
    return p.returncode, p.stdout.decode("utf-8", "replace"), p.stderr.decode("utf-8", "replace")


def prepare(binary, out, env, log):
    """Builds the seed inputs from the shipped files and checks each unmodified."""
    bin_hash = hashlib.sha256(Path(binary).read_bytes()).hexdigest()
    prep = out / "prep"
    stamp = prep / "context.json"
    key = {"binary": bin_hash, "version": CAMPAIGN_VERSION,
           "script": hashlib.sha256(Path(__file__).read_bytes()).hexdigest()}
    if stamp.exists():
        try:
            data = json.loads(stamp.read_text())
            if data.get("key") == key:
                ctx = Context()
                ctx.__dict__.update(data["ctx"])
                return ctx
        except (ValueError, KeyError):
            pass
    if prep.exists():
        shutil.rmtree(prep)
    prep.mkdir(parents=True)
    lib = REPO / "studies" / "library"
    ctx = Context()
    ctx.doc_keys = parse_doc_fields()
    ctx.catalog_text = read_text(lib / "catalogs" / "sew-cms.yaml")
    ctx.catalog_entries = re.findall(r"name: ([A-Z0-9]+S?L?/\d+)", ctx.catalog_text) or \
        ["CMS50S/70"]
    machine_files = sorted((REPO / "examples").glob("*.yaml")) + [
        lib / "hexapod-450" / "hexapod-450.yaml", lib / "tripod-z3" / "z3-axial.yaml",
        lib / "tripod-z3" / "z3-tube.yaml", lib / "lathe-16k20f3" / "lathe.yaml",
        lib / "lathe-16k20f3" / "turret-centre.yaml", lib / "calibration-demo" / "nominal.yaml",
        lib / "calibration-demo" / "truth.yaml"]
    machines = []
    ctx.machines_for = {c: [] for c in ("describe", "analyze", "fk", "workspace", "trajectory",
                                        "calibration-poses", "simulate-measurements")}
    ctx.seed_notes = []
    for mf in machine_files:
        if not mf.exists():
            continue
        text = mf.read_text(encoding="utf-8", errors="replace")
        deps = re.findall(r"^\s*file:\s*\"?([\w./\-]+\.yaml)", text, re.M)
        name = mf.parent.name + "_" + mf.stem if mf.parent.name != "examples" else mf.stem
        m = {"name": name, "path": str(mf), "deps": deps, "masses": "masses:" in text or any(
            "masses:" in (mf.parent / d).read_text() for d in deps),
            "model": (re.findall(r"^model:\s*(\S+)", text, re.M) or ["?"])[0]}
        work = prep / "machines" / name
        work.mkdir(parents=True)
        rc, so, se = prep_run(binary, ["describe", str(mf)], work, env)
        if rc == 0:
            ctx.machines_for["describe"].append(m)
        else:
            ctx.seed_notes.append(f"describe {mf.relative_to(REPO)}: exit {rc}: {se.strip()}")
        rc, so, se = prep_run(binary, ["workspace", str(mf), "--resolution", "0.05", "--out",
                                       "ws"], work, env)
        if rc != 0:
            ctx.seed_notes.append(f"workspace {mf.relative_to(REPO)}: exit {rc}: {se.strip()}")
            continue
        summ = json.loads((work / "ws" / "summary.json").read_text())
        m["resolution"] = 0.1 if summ.get("seconds", 0) > 0.25 else 0.05
        with open(work / "ws" / "points.csv") as f:
            pts = list(csv.DictReader(f))
        if not pts:
            continue
        bb = summ["bounding_box"]
        centre = [(a + b) / 2 for a, b in zip(bb["min"], bb["max"])]
        pts.sort(key=lambda r: sum((float(r[c]) - centre[i]) ** 2
                                   for i, c in enumerate("xyz")))
        chosen = [pts[0], pts[len(pts) // 3], pts[2 * len(pts) // 3], pts[-1]]
        rows = ["x,y,z,rx,ry,rz"]
        for r in chosen:
            rows.append(",".join([r["x"], r["y"], r["z"], "0", "0", "0"]))
        rows.append(",".join([pts[0]["x"], pts[0]["y"], pts[0]["z"], "2", "-1", "3"]))
        m["poses_csv"] = "\n".join(rows) + "\n"
        m["point"] = [float(pts[0][c]) for c in "xyz"]
        (work / "poses.csv").write_text(m["poses_csv"])
        rc, so, se = prep_run(binary, ["analyze", str(mf), "--poses", "poses.csv"], work, env)
        if rc != 0:
            ctx.seed_notes.append(f"analyze {mf.relative_to(REPO)}: exit {rc}: {se.strip()}")
            continue
        ctx.machines_for["analyze"].append(m)
        ctx.machines_for["workspace"].append(m)
        # Orientation workspaces only for machines where one is cheap (some leg models cost
        # seconds per orientation grid).
        t0 = time.monotonic()
        rc_o, _, _ = prep_run(binary, ["workspace", str(mf), "--tilt", "5", "--orientation-step",
                                       "5", "--resolution", "0.2", "--mode", "some"], work, env)
        m["orient_ok"] = rc_o == 0 and time.monotonic() - t0 < 1.5
        out_rows = list(csv.DictReader(io.StringIO(so)))
        qcols = [c for c in out_rows[0] if re.fullmatch(r"q_\d+", c)]
        m["q"] = [float(out_rows[0][c]) for c in qcols]
        rc, so, se = prep_run(binary, ["fk", str(mf), "--q", ",".join(fmt(v) for v in m["q"])],
                              work, env)
        if rc == 0:
            ctx.machines_for["fk"].append(m)
        else:
            ctx.seed_notes.append(f"fk {mf.relative_to(REPO)}: exit {rc}: {se.strip()}")
        p = m["point"]
        path = ["t,x,y,z,rx,ry,rz"]
        for i in range(11):
            t = i * 0.1
            path.append(",".join(fmt(round(v, 6)) for v in (
                t, p[0] + 0.005 * math.cos(2 * math.pi * t), p[1] + 0.005 * math.sin(
                    2 * math.pi * t), p[2], 0, 0, 0)))
        m["path_csv"] = "\n".join(path) + "\n"
        (work / "path.csv").write_text(m["path_csv"])
        ok = True
        for argv in (["trajectory", str(mf), "--path", "path.csv"],
                     ["trajectory", str(mf), "--helix", "--helix-centre",
                      ",".join(fmt(v) for v in p), "--helix-radius", "0.005,0.005",
                      "--helix-height", "0,0.005", "--samples", "21"]):
            rc, so, se = prep_run(binary, argv, work, env)
            if rc != 0:
                ok = False
                ctx.seed_notes.append(f"{' '.join(argv[:3])}: exit {rc}: {se.strip()}")
        if ok:
            ctx.machines_for["trajectory"].append(m)
        if m["model"] == "hexapod":
            rc, so, se = prep_run(binary, ["calibration-poses", str(mf), "--grid", "--count",
                                           "16", "--steps", "3"], work, env)
            if rc == 0:
                ctx.machines_for["calibration-poses"].append(m)
            else:
                ctx.seed_notes.append(f"calibration-poses {mf.name}: exit {rc}: {se.strip()}")
            rc, so, se = prep_run(binary, ["simulate-measurements", str(mf), "--out", "sim",
                                           "--poses", "30"], work, env)
            if rc == 0:
                ctx.machines_for["simulate-measurements"].append(m)
            else:
                ctx.seed_notes.append(f"simulate {mf.name}: exit {rc}: {se.strip()}")
        machines.append(m)
    # Calibration candidates: the poses of a simulated measurement file.
    sim = prep / "machines" / "calibration-demo_nominal" / "sim"
    with open(sim / "measurements.csv") as f:
        rows = list(csv.reader(f))
    ctx.candidates_csv = "\n".join(",".join(r[:6]) for r in rows[:41]) + "\n"
    # Calibration sets.
    ctx.calibration_sets = []
    cal_root = prep / "calibration"
    demo = lib / "calibration-demo"
    variants = [("demo", None)] + [(f"sim{i}", a) for i, a in enumerate([
        ["--poses", "24", "--model", "42"], ["--poses", "30", "--unit", "m", "--seed", "5"],
        ["--poses", "20", "--outliers", "0"], ["--poses", "40", "--seed", "3"]])]
    for name, args in variants:
        d = cal_root / name
        if args is None:
            shutil.copytree(demo, d)
        else:
            d.parent.mkdir(parents=True, exist_ok=True)
            rc, so, se = prep_run(binary, ["simulate-measurements", str(demo / "nominal.yaml"),
                                           "--out", str(d)] + args, prep, env)
            if rc != 0:
                ctx.seed_notes.append(f"simulate {name}: exit {rc}: {se.strip()}")
                continue
        rc, so, se = prep_run(binary, ["calibrate", "calibration.yaml", "--out", "cal"], d, env)
        if rc not in (0, 3):
            ctx.seed_notes.append(f"calibrate {name}: exit {rc}: {se.strip()}")
            continue
        ctext = read_text(d / "calibration.yaml")
        mrel = re.search(r"^machine:\s*(\S+)", ctext, re.M).group(1)
        srel = re.search(r"^measurements:\s*(\S+)", ctext, re.M).group(1)
        ctx.calibration_sets.append({"name": name, "calibration": ctext, "machine_rel": mrel,
                                     "machine": read_text(d / mrel), "measurements_rel": srel,
                                     "measurements": read_text(d / srel), "status": rc})
    # Studies: every library study, made small.
    study_files = sorted(lib.glob("*.yaml")) + sorted((lib / "compare-300").glob("*.yaml")) + \
        sorted((lib / "hexapod-rapid").glob("*.yaml")) + [lib / "lathe-16k20f3" / "pareto.yaml"]
    ctx.studies = []
    ctx.results = []
    ctx.compare_results = []
    sroot = prep / "studies"
    sroot.mkdir()
    for sf in study_files:
        name = (sf.parent.name + "_" if sf.parent != lib else "") + sf.stem
        text = tiny_study(read_text(sf))
        d = sroot / name
        d.mkdir()
        (d / "study.yaml").write_bytes(s2b(text))
        cat = "catalog: catalogs/" in text
        if cat:
            (d / "catalogs").mkdir()
            (d / "catalogs" / "sew-cms.yaml").write_bytes(s2b(ctx.catalog_text))
        rc, so, se = prep_run(binary, ["validate", "study.yaml"], d, env)
        if rc != 0:
            ctx.seed_notes.append(f"validate {name}: exit {rc}: {se.strip()}")
            continue
        st = {"name": name, "text": text, "catalog": cat, "runnable": False, "result": None,
              "status": None, "design": bool(re.search(r"(?m)^machine:", text)),
              "knee_file": None}
        t0 = time.monotonic()
        rc, so, se = prep_run(binary, ["run", "study.yaml", "--out", "res", "--threads", "1",
                                       "--no-progress"], d, env)
        secs = time.monotonic() - t0
        if rc in (0, 3) and secs < 2.0:
            # Exit 3: the run found no usable (feasible) design, a result all the same.
            st["runnable"] = True
            st["status"] = rc
            st["result"] = str(d / "res")
            pj = d / "res" / "pareto.json"
            if pj.exists():
                front = json.loads(pj.read_text())
                knee = next((x.get("machine_file") for x in front.get("designs", [])
                             if x.get("id") == front.get("knee")), None)
                st["knee_file"] = knee
                r = {"name": name, "dir": str(d / "res"), "knee_file": knee,
                     "objectives": [o["name"] for o in front.get("objectives", [])]}
                rc2, _, se2 = prep_run(binary, ["export", "res", "--format", "html", "--out",
                                                str(d / "check.html")], d, env)
                if rc2 == 0:
                    ctx.results.append(r)
                    # Remove the check export's plots (they sit next to check.html, not in res).
                    if {"stiffness_min", "machine_size"} <= set(r["objectives"]):
                        ctx.compare_results.append(r)
                else:
                    ctx.seed_notes.append(f"export {name}: exit {rc2}: {se2.strip()}")
        else:
            ctx.seed_notes.append(f"run {name}: exit {rc} in {secs:.1f} s: {se.strip()[:200]}")
        ctx.studies.append(st)
    for c, ms in ctx.machines_for.items():
        if not ms:
            raise SystemExit(f"mutation_campaign: no seed machine passes `{c}` unmodified")
    if len(ctx.compare_results) < 3 or not ctx.results or not ctx.calibration_sets:
        raise SystemExit("mutation_campaign: the seed results or calibration sets are missing")
    stamp.write_text(json.dumps({"key": key, "ctx": ctx.__dict__}, indent=1))
    return ctx


# ----------------------------------------------------------------------------------------------
