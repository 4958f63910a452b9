"""Checks of a run: NaN in outputs, the exit-status contract, failures kept. (the mutation campaign: fuzz/campaign/main.py)."""

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

from .common import PYTHON, RUN_JOURNAL_FILES  # noqa: F401
from .values import BLOCK_KEY_RE, NAN_TOKENS, TEXT_KEYS, b2s, code_end, s2b  # noqa: F401
from .runner import materialize, read_capped, run_binary, snapshot  # noqa: F401
# ----------------------------------------------------------------------------------------------
# NaN checks
# ----------------------------------------------------------------------------------------------

TOKEN_NAN_RE = re.compile(r"(?<![\w.+\-])[-+]?\.?nan(?:\([^)]*\))?(?![\w.])", re.I)


def is_nan_cell(cell):
    return cell.strip().strip("\"").lower() in NAN_TOKENS


def nan_in_csv(text, passthrough):
    hits = []
    try:
        rows = list(csv.reader(io.StringIO(text)))
    except csv.Error:
        return nan_in_text(text)
    if not rows:
        return hits
    header = rows[0]
    for r, row in enumerate(rows[1:], start=2):
        for c, cell in enumerate(row):
            name = header[c] if c < len(header) else ""
            if name in passthrough:
                continue
            if is_nan_cell(cell):
                hits.append(f"row {r} column {c + 1} ({name}): {cell!r}")
                if len(hits) > 5:
                    return hits
    return hits


def nan_in_yaml(text):
    hits = []
    for i, line in enumerate(text.split("\n"), start=1):
        code = line[:code_end(line)]
        code = re.sub(r"\"(?:[^\"\\]|\\.)*\"|'(?:[^']|'')*'", "\"\"", code)
        m = BLOCK_KEY_RE.match(code)
        if m and m.group(3).split(".")[-1] in TEXT_KEYS:
            continue
        for t in TOKEN_NAN_RE.finditer(code):
            before = code[:t.start()].rstrip()
            key = re.findall(r"([A-Za-z_][\w\-]*)\s*:\s*$", before)
            if key and key[-1] in TEXT_KEYS:
                continue
            hits.append(f"line {i}: {line.strip()[:120]}")
            break
        if len(hits) > 5:
            break
    return hits


def nan_in_json(text):
    found = []

    def const(name):
        if "NaN" in name:
            found.append(name)
        return 0.0

    try:
        json.loads(text, parse_constant=const)
    except ValueError:
        # Not JSON: look for bare NaN tokens outside strings.
        stripped = re.sub(r"\"(?:[^\"\\]|\\.)*\"", "\"\"", text)
        return [f"(invalid JSON) {m.group(0)}" for m in TOKEN_NAN_RE.finditer(stripped)][:5]
    return [f"JSON value {v}" for v in found[:5]]


def nan_in_text(text):
    hits = []
    for i, line in enumerate(text.split("\n"), start=1):
        if TOKEN_NAN_RE.search(line):
            hits.append(f"line {i}: {line.strip()[:160]}")
            if len(hits) > 5:
                break
    return hits


def nan_in_stl(data):
    if len(data) < 84 or data[:5] == b"solid" and b"facet" in data[:1000]:
        return nan_in_text(data.decode("utf-8", "replace"))
    n = struct.unpack_from("<I", data, 80)[0]
    for t in range(min(n, (len(data) - 84) // 50)):
        vals = struct.unpack_from("<12f", data, 84 + 50 * t)
        if any(v != v for v in vals):
            return [f"triangle {t}: {vals}"]
    return []


def looks_csv(text):
    lines = [ln for ln in text.split("\n")[:6] if ln]
    return len(lines) >= 2 and "," in lines[0] and \
        all(ln.count(",") == lines[0].count(",") for ln in lines[1:])


def nan_check(name, data, passthrough):
    """NaN findings in one output (file name used for the format)."""
    low = name.lower()
    if low.endswith(".png"):
        return [], False
    if low.endswith(".stl"):
        return nan_in_stl(data), False
    if b"\x00" in data[:4096] and not low.endswith((".csv", ".json", ".yaml", ".txt")):
        return [], False
    text = data.decode("utf-8", "replace")
    if low.endswith(".json"):
        return nan_in_json(text), False
    if low.endswith((".yaml", ".yml")):
        return nan_in_yaml(text), False
    if low.endswith(".csv") or (low.startswith("<std") and looks_csv(text)):
        return nan_in_csv(text, passthrough), False
    if low.endswith((".html", ".svg")):
        # The embedded JSON of the html report and the attribute values of the SVG.
        hits = []
        for m in re.finditer(r"<script type=\"application/json\"[^>]*>(.*?)</script>", text, re.S):
            hits += nan_in_json(m.group(1))
        body = re.sub(r"<script.*?</script>", "", text, flags=re.S)
        for m in re.finditer(r"=\"\s*([^\"]*)\"", body):
            if any(TOKEN_NAN_RE.fullmatch(t) for t in re.split(r"[\s,;()]+", m.group(1)) if t):
                hits.append(f"attribute {m.group(0)[:100]}")
                break
        for m in re.finditer(r">([^<>]*)<", body):
            if TOKEN_NAN_RE.search(m.group(1)):
                hits.append(f"text {m.group(1).strip()[:100]!r}")
                break
        return hits, True
    return nan_in_text(text), True


# ----------------------------------------------------------------------------------------------
# Checking one run
# ----------------------------------------------------------------------------------------------

def input_nan_words(case):
    """Whether a nan-like token appears in the case's inputs (text outputs may echo it)."""
    blobs = [f[1] for f in case.files.values() if f[0] in ("file", "fifo") and f[1]]
    blobs += case.argv()
    return any(TOKEN_NAN_RE.search(b if isinstance(b, str) else b2s(b)) for b in blobs)


def csv_passthrough(case):
    cols = set()
    for rel, f in case.files.items():
        if f[0] == "file" and rel.endswith(".csv") and f[1]:
            first = f[1].split("\n", 1)[0].replace("\r", "")
            cols.update(c.strip().lstrip("\ufeff\xef\xbb\xbf") for c in first.split(","))
    return cols - {"x", "y", "z", "rx", "ry", "rz", "t", ""}


def check_run(case, rc, stdout, stderr, before, after, feeders, timeout):
    findings = []
    argv = case.argv()
    if rc is None:
        findings.append(("hang", f"no exit within {timeout} s"))
    elif rc < 0:
        try:
            sig = signal.Signals(-rc).name
        except ValueError:
            sig = str(-rc)
        findings.append(("crash", f"killed by signal {sig}"))
    elif rc == 1:
        findings.append(("exit1_mutated" if case.mutated else "exit1_unmutated",
                         "exit status 1 (internal fault)"))
    elif rc not in (0, 2, 3):
        findings.append(("bad_exit_status", f"exit status {rc}"))
    if not case.mutated and rc is not None and rc > 1 and rc not in (0, case.meta.get("ok_status", 0)):
        findings.append(("baseline_failed", f"unmutated input gave exit status {rc}"))
    err_lines = stderr.split(b"\n")
    if err_lines and err_lines[-1] == b"":
        err_lines.pop()
    if rc == 2:
        if len(err_lines) != 1 or not err_lines[0].startswith(b"pkmopt: error: "):
            findings.append(("exit2_message", f"stderr has {len(err_lines)} line(s): "
                             f"{stderr[:300]!r}"))
        new_files = []
        out_dir = case.opt_value("--out") if case.cmd == "run" else None
        for rel, info in after.items():
            if stat.S_ISDIR(info[0]):
                continue
            if rel in before and before[rel][0] == info[0]:
                continue
            if out_dir is not None:
                parent = os.path.normpath(os.path.dirname(rel))
                if parent == os.path.normpath(out_dir or ".") and \
                        os.path.basename(rel) in RUN_JOURNAL_FILES:
                    continue
            new_files.append(rel)
        if new_files:
            findings.append(("exit2_leftover", "new files after exit 2: " +
                             ", ".join(sorted(new_files)[:10])))
        new_dirs = [rel for rel, info in after.items() if stat.S_ISDIR(info[0]) and
                    rel not in before]
        if new_dirs:
            case.meta["exit2_new_dirs"] = sorted(new_dirs)[:10]
    if rc == 3 and not any(ln.startswith(b"pkmopt: warning:") for ln in err_lines):
        findings.append(("exit3_no_warning", "exit 3 without a 'pkmopt: warning:' line"))
    # NaN in outputs: stdout and every file written or changed.
    passthrough = csv_passthrough(case) if case.cmd == "analyze" else set()
    echo_possible = input_nan_words(case)
    outputs = [("<stdout>", stdout)]
    for rel, info in sorted(after.items()):
        if not stat.S_ISREG(info[0]):
            continue
        if rel in before and before[rel] == info:
            continue
        outputs.append((rel, None))
    for fd in feeders:
        if fd.reader and fd.drained:
            outputs.append(("fifo_out.csv", bytes(fd.drained)))
    nan_hits = []
    for name, data in outputs:
        if data is None:
            try:
                data = read_capped(case.meta["work"] / name)
            except OSError:
                continue
        hits, textual = nan_check(name, data, passthrough)
        if hits and textual and echo_possible:
            case.meta.setdefault("nan_echo_notes", []).append(f"{name}: {hits[0]}")
            continue
        for h in hits:
            nan_hits.append(f"{name}: {h}")
    if nan_hits:
        findings.append(("nan_output", "; ".join(nan_hits[:6])))
    return findings


def check_python_run(case, rc, stdout, stderr, before, after, timeout):
    """The Python module's contract: no crash or hang, only pkmopt.InputError or TypeError
    raised (with a one-line message), no NaN returned, nothing left behind by an InputError."""
    findings = []
    if rc is None:
        return [("hang", f"no exit within {timeout} s")]
    if rc < 0:
        try:
            sig = signal.Signals(-rc).name
        except ValueError:
            sig = str(-rc)
        return [("crash", f"the interpreter was killed by signal {sig}")]
    lines = [ln for ln in stdout.split(b"\n") if ln.startswith(b"{")]
    if rc != 0 or not lines:
        return [("crash", f"the interpreter exited {rc}: {stderr[-300:]!r}")]
    try:
        res = json.loads(lines[-1])
    except ValueError:
        return [("harness_error", f"unreadable result line {lines[-1][:200]!r}")]
    case.meta["py_status"] = res.get("status")
    if res["status"] == "foreign" and res.get("message") == "user fitness failed":
        pass  # the user's own exception from fitness, passed on unchanged (docs/python.md)
    elif res["status"] == "foreign":
        findings.append(("python_foreign_exception",
                         f"{res['type']}: {res.get('message', '')[:200]}"))
    elif res["status"] == "raised":
        # pkmopt's own messages are one line; pybind11's TypeError for arguments of the wrong
        # type lists the signatures, as Python's own argument errors do.
        if res["type"] == "InputError" and res.get("lines", 1) != 1:
            findings.append(("python_multiline_message", res.get("message", "")[:200]))
        if res["type"] == "InputError":
            out_dir = case.meta.get("py_out_dir")
            new_files = [rel for rel, info in after.items() if not stat.S_ISDIR(info[0]) and
                         rel not in before and not rel.startswith("__pycache__") and
                         not (out_dir and os.path.dirname(rel) == out_dir and
                              os.path.basename(rel) in RUN_JOURNAL_FILES)]
            if new_files:
                findings.append(("exit2_leftover", "new files after InputError: " +
                                 ", ".join(sorted(new_files)[:10])))
    elif res["status"] == "ok" and res.get("nan"):
        findings.append(("nan_output", "; ".join(res["nan"][:6])))
    return findings


def execute(case, binary, scratch, timeout, env, keep_root):
    root = scratch / f"{case.k:06d}"
    if root.exists():
        shutil.rmtree(root)
    inp, work = root / "input", root / "work"
    materialize(case, inp)
    materialize(case, work)
    case.meta["work"] = work
    fifos = []
    for rel, f in case.files.items():
        if f[0] == "fifo":
            fifos.append((work / rel, s2b(f[1] or ""), False))
        elif f[0] == "fifo_out":
            fifos.append((work / rel, b"", True))
    before = snapshot(work)
    argv = case.argv()
    if case.cmd == "python":
        py_env = dict(env)
        py_env["PYTHONPATH"] = str(Path(binary).resolve().parent.parent / "python")
        py_env["PYTHONDONTWRITEBYTECODE"] = "1"
        rc, so, se, secs, feeders = run_binary(PYTHON, argv, work, timeout, root, py_env, fifos)
        after = snapshot(work)
        findings = check_python_run(case, rc, so, se, before, after, timeout)
    else:
        rc, so, se, secs, feeders = run_binary(binary, argv, work, timeout, root, env, fifos)
        after = snapshot(work)
        findings = check_run(case, rc, so, se, before, after, feeders, timeout)
    result = {"k": case.k, "cmd": case.cmd, "rc": rc, "secs": round(secs, 4),
              "mutated": case.mutated, "mutations": case.mutations,
              "findings": [list(f) for f in findings], "argv": argv,
              "nan_echo_notes": case.meta.get("nan_echo_notes", []),
              "exit2_new_dirs": case.meta.get("exit2_new_dirs", [])}
    if findings:
        keep = keep_root / f"{case.k:04d}"
        if keep.exists():
            shutil.rmtree(keep)
        keep.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(str(root), str(keep))
        write_failure(keep, case, binary, rc, so, se, findings)
        result["kept"] = str(keep)
    else:
        shutil.rmtree(root, ignore_errors=True)
    result["stderr_head"] = se[:400].decode("utf-8", "replace")
    return result


def write_failure(keep, case, binary, rc, so, se, findings):
    argv = case.argv()
    cmdline = " ".join(shlex.quote(a) for a in [binary] + argv)
    (keep / "cmdline.txt").write_text(cmdline + "\n")
    (keep / "stdout.txt").write_bytes(so)
    (keep / "stderr.txt").write_bytes(se)
    (keep / "exit_status.txt").write_text(("timeout" if rc is None else str(rc)) + "\n")
    (keep / "mutations.txt").write_text("\n".join(case.mutations) + "\n")
    (keep / "findings.json").write_text(json.dumps(findings, indent=2) + "\n")
    feeds = []
    for rel, f in case.files.items():
        if f[0] == "fifo":
            (keep / ("fifo_feed_" + rel.replace("/", "_"))).write_bytes(s2b(f[1] or ""))
            feeds.append(f"(cat \"$HERE/fifo_feed_{rel.replace('/', '_')}\" > "
                         f"{shlex.quote(rel)} &) 2>/dev/null")
        elif f[0] == "fifo_out":
            feeds.append(f"(cat {shlex.quote(rel)} > /dev/null &) 2>/dev/null")
    script = [
        "#!/bin/sh",
        f"# Repeats campaign run {case.k} ({case.cmd}) in a fresh copy of input/.",
        "# Mutations:",
        *[f"#   {m[:200]}" for m in case.mutations],
        'HERE=$(cd "$(dirname "$0")" && pwd)',
        'D=$(mktemp -d /tmp/pkmopt-repro.XXXXXX)',
        'cp -a "$HERE/input/." "$D/"',
        'cd "$D" || exit 99',
        *feeds,
        f"timeout 60 {cmdline}",
        'rc=$?',
        'echo "exit status $rc (folder $D)" >&2',
        'exit $rc',
    ]
    p = keep / "repro.sh"
    p.write_text("\n".join(script) + "\n")
    p.chmod(0o755)


# ----------------------------------------------------------------------------------------------
