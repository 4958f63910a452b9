#!/usr/bin/python3
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

REPO = Path(__file__).resolve().parent.parent
CAMPAIGN_VERSION = "1"

COMMANDS = [
    "describe", "analyze", "fk", "workspace", "trajectory", "calibration-poses",
    "simulate-measurements", "calibrate", "validate", "run", "export", "compare", "draw",
    "task-poses", "python",
]

# What a failed `run` may leave in its --out folder: the journal it resumes from (its results,
# study.resolved.yaml included, go into place together or not at all).
RUN_JOURNAL_FILES = {"journal.txt", "evaluations.csv", "run.lock", "journal.damaged.txt"}
PYTHON = "/usr/bin/python3"

# ----------------------------------------------------------------------------------------------
# Hostile values
# ----------------------------------------------------------------------------------------------

HOSTILE_NUMBERS = [
    "1e308", "-1e308", "1.7976931348623157e308", "1e309", "-1e309", "1e-320", "-1e-320",
    "4.9e-324", "2.2250738585072014e-308", "1e-30", "1e-300", "0", "-0", "0.0", "-0.0", "1e15",
    "1e16", "-1e15", "1e100", "-1e100",
    "2147483647", "2147483648", "-2147483648", "-2147483649", "4294967295", "4294967296",
    "9223372036854775807", "9223372036854775808", "-9223372036854775808",
    "-9223372036854775809", "18446744073709551615", "18446744073709551616",
    "nan", "NaN", "-nan", "+nan", ".nan", "NAN", "nan(0x1)",
    "inf", "-inf", "+inf", "Infinity", "-Infinity", ".inf", "-.inf", "INF",
    "1" * 400, "0." + "0" * 400 + "1", "1" * 30, "9" * 20 + ".5", "-" + "9" * 40,
    "1e99999", "-1e99999", "1e-99999", "0x1p-1074", "0x7fffffff", "0x10", "1e", "1e+", ".",
    "-", "+", "--1", "1.2.3", "1,5", "1_000", "1 000", " 1", "1 ", "\u0661", "\uff11", "1e3",
    "-1", "-1e-9", "3.5", "0.5", "1.0000000000000002", "0.49999999999999994", "01", "+1",
    "1d", "1f", "1.#INF", "1e-1.5",
]
# Values at the edges of what the readers accept (+-1e15, 1e-30, +-1e9 for loads, angles).
BOUNDARY_NUMBERS = [
    "1e15", "-1e15", "9.99e14", "1e-30", "-1e-30", "1.1e-30", "1e-29", "1e9", "-1e9", "1e-9",
    "1e12", "1e-12", "1e-15", "1e6", "-1e6", "1e-6", "89.99999", "90", "-90", "180", "-180",
    "360", "720", "0.9999999999999999", "1e-300", "0", "-0", "1", "-1", "2", "0.5", "1e3",
]
NON_NUMBERS = [
    "abc", "", "true", "null", "~", "[]", "{}", "a\nb", "1\n2", "\"1\"", "'1'", "%s%n%x",
    "\u00e9", "\ufeff1", "$(echo hi)", "-h", "--help", "x" * 5000, "\t", "\u202e1", "1\r",
]
HOSTILE_STRINGS = [
    "", "nope", "x" * 5000, "a\nb", "\u00e9\u00e8", "\ufeff", "\u202eabc", "%s%s%n",
    "../../etc/passwd", "/", " ", "CON", "a,b", "{}", "[]", "- x", "*alias", "&anchor",
]
YAML_VALUE_REPLACEMENTS = [
    "abc", "\"0.5\"", "'x'", "[1, 2]", "[]", "{}", "{a: 1}", "~", "null", "\"\"", "true",
    "no", "-", "!!binary aGVsbG8=", "!!str 1", "!!int 1.5", "!!float abc", "*undefined",
    "&a 1", "?", ":", "[", "{", "]", "}", "'", "\"", "@x", "`x", "%YAML", "|", ">",
    "0o17", "0b101", "1:20", "2001-12-14", "<<", "!custom 1", "!!map {}", "!<tag:x> 1",
    "\"a\\nb\"", "\"\\0\"", "\"\\x1b[31mred\"", "\"\\u202eabc\"", "\"a\\rb\"",
    "\"\\t\"", "'it''s'", "\"\\U0001F600\"", "\"\\xff\"", "\"\\e\"", "\"\\N\\L\\P\"",
]
BYTE_INSERTS = [
    b"\xff", b"\x00", b"\x01", b"\x1b[31m", b"\t", b"\r", b"\xc3\x28", b"\xef\xbb\xbf",
    b"\xe2\x80\xae", b"\xed\xa0\x80", b"\xf4\x90\x80\x80", b"\xc0\xaf", b"\x7f", b"\x0b\x0c",
    b"\x00" * 64, b"\xfe\xff", b"\r\n", b"\n", b"#", b":", b"- ", b"{", b"[", b"\"", b"'",
    b"&", b"*", b"!", b"|", b">", b"%", b"@", b"`", b",", b";",
]
NAN_TOKENS = {"nan", "-nan", "+nan", ".nan", "-.nan", "+.nan", "nan(ind)", "-nan(ind)",
              "nan(0x1)", "nanq", "nans"}

TEXT_KEYS = {"name", "description", "study", "model", "id", "machine_file", "catalog",
             "actuator", "drive", "type", "note", "machine", "measurements", "file", "format",
             "pkmopt_version", "message", "status", "knee", "algorithm", "benchmark", "unit",
             "sense", "kind", "metric", "shape", "spindle", "code", "frame", "loss", "gauge",
             "local_algorithm", "cost", "campaign", "axes", "failure", "reason"}


def fmt(x):
    return repr(float(x)) if isinstance(x, float) else str(x)


# ----------------------------------------------------------------------------------------------
# Text helpers (files are handled as latin-1 strings: every byte maps to one character)
# ----------------------------------------------------------------------------------------------

def b2s(b):
    return b.decode("latin-1")


def s2b(s):
    return s.encode("latin-1", "replace") if isinstance(s, str) else s


def u(s):
    """A str that may hold non-latin-1 characters, as latin-1 text of its UTF-8 bytes."""
    return s.encode("utf-8").decode("latin-1")


def code_end(line):
    """Index where a YAML comment starts in line (outside quotes), or len(line)."""
    q = None
    for i, c in enumerate(line):
        if q:
            if c == q:
                q = None
        elif c in "\"'" and (i == 0 or line[i - 1] in " \t[{,:"):
            q = c
        elif c == "#" and (i == 0 or line[i - 1] in " \t"):
            return i
    return len(line)


NUM_RE = re.compile(r"(?<![\w.\-+])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")
BLOCK_KEY_RE = re.compile(r"^(\s*)(-\s+)?([A-Za-z_][\w.\-]*)\s*:(?=\s|$)")
FLOW_KEY_RE = re.compile(r"(?<=[{,])\s*([A-Za-z_][\w\-]*)\s*:\s")
FLOW_LIST_RE = re.compile(r"\[[^\[\]{}]*\]")


class YamlDoc:
    def __init__(self, text):
        self.lines = text.split("\n")

    def text(self):
        return "\n".join(self.lines)

    def numbers(self):
        out = []
        for i, line in enumerate(self.lines):
            code = line[:code_end(line)]
            for m in NUM_RE.finditer(code):
                out.append((i, m.start(), m.end()))
        return out

    def block_keys(self):
        out = []
        for i, line in enumerate(self.lines):
            m = BLOCK_KEY_RE.match(line)
            if m:
                out.append((i, m.start(3), m.end(3)))
        return out

    def flow_keys(self):
        out = []
        for i, line in enumerate(self.lines):
            code = line[:code_end(line)]
            for m in FLOW_KEY_RE.finditer(code):
                out.append((i, m.start(1), m.end(1)))
        return out

    def scalar_values(self):
        """Spans of scalar values: after a block key, after a flow key, flow list items."""
        out = []
        for i, line in enumerate(self.lines):
            ce = code_end(line)
            code = line[:ce]
            m = BLOCK_KEY_RE.match(code)
            if m:
                rest_start = m.end()
                rest = code[rest_start:]
                v = rest.strip()
                if v and v[0] not in "[{|>":
                    s = rest_start + (len(rest) - len(rest.lstrip()))
                    out.append((i, s, s + len(v)))
            for fm in re.finditer(r"(?<=[{,])\s*[A-Za-z_][\w\-]*\s*:\s*([^,{}\[\]]+?)\s*(?=[,}])",
                                  code):
                out.append((i, fm.start(1), fm.end(1)))
            for lm in FLOW_LIST_RE.finditer(code):
                inner_start = lm.start() + 1
                pos = inner_start
                for item in code[lm.start() + 1:lm.end() - 1].split(","):
                    st = item.strip()
                    if st:
                        off = item.index(st)
                        out.append((i, pos + off, pos + off + len(st)))
                    pos += len(item) + 1
            sm = re.match(r"^(\s*)-\s+([^\[{#][^#]*?)\s*$", code)
            if sm and ":" not in sm.group(2):
                out.append((i, sm.start(2), sm.end(2)))
        return out

    def block_end(self, i):
        """Index after the block of line i (the line and its more-indented children)."""
        ind = len(self.lines[i]) - len(self.lines[i].lstrip())
        if self.lines[i].lstrip().startswith("- "):
            ind += 1
        j = i + 1
        while j < len(self.lines):
            ln = self.lines[j]
            if ln.strip() and not ln.lstrip().startswith("#"):
                if len(ln) - len(ln.lstrip()) <= ind:
                    break
            j += 1
        return j

    def replace(self, i, a, b, new):
        self.lines[i] = self.lines[i][:a] + new + self.lines[i][b:]


def parse_doc_fields():
    """The documented keys of every file format (the `<!-- fields: NAME -->` tables)."""
    prefixes = {
        "machine hexapod": "machine.", "task.region box": "task.region.",
        "task.region cylinder": "task.region.", "task.orientations": "task.orientations.",
        "task.workspace": "task.workspace.", "output": "output.",
        "turning": "task.wrench.turning.", "milling": "task.wrench.milling.",
        "nsga2": "optimizer.", "hybrid@optimizer": "optimizer.",
        "epsilon_constraint": "optimizer.", "nbi": "optimizer.", "ipopt": "optimizer.",
        "nlopt": "optimizer.", "problem": "problem.",
    }
    groups = {"machine": set(), "study": set(), "calibration": set(), "catalog": set()}
    files = [REPO / "README.md"] + sorted((REPO / "docs").glob("*.md"))
    for f in files:
        try:
            text = f.read_text(encoding="utf-8")
        except OSError:
            continue
        for m in re.finditer(r"<!-- fields: ([^>]*?) -->(.*?)<!-- /fields -->", text, re.S):
            name, body = m.group(1).strip(), m.group(2)
            keys = re.findall(r"^\| `([^`]+)` \|", body, re.M)
            keys = [k for k in keys if "[" not in k and " " not in k]
            if name == "hybrid" and f.name == "optimizer.md":
                name = "hybrid@optimizer"
            if name.startswith("machine.parameters"):
                groups["study"].update("machine.parameters." + k for k in keys)
            elif name in prefixes:
                groups["study"].update(prefixes[name] + k for k in keys)
            elif name == "calibration":
                groups["calibration"].update(keys)
            elif name == "actuator_catalog":
                groups["catalog"].update(keys)
            else:
                groups["machine"].update(keys)
    return {k: sorted(v) for k, v in groups.items()}


# ----------------------------------------------------------------------------------------------
# Mutators
# ----------------------------------------------------------------------------------------------

def hostile_number(rng):
    r = rng.random()
    if r < 0.35:
        return rng.choice(BOUNDARY_NUMBERS)
    return u(rng.choice(HOSTILE_NUMBERS if r < 0.88 else NON_NUMBERS))


def mild_number(rng, text):
    try:
        v = float(text)
    except ValueError:
        return text
    if re.fullmatch(r"[-+]?\d+", text.strip()):
        if len(text.strip()) > 18:  # an earlier mutation's huge integer: left as it is
            return text
        return str(int(text.strip()) + rng.choice([-1, 1, 2]))
    f = rng.choice([0.5, 0.9, 0.99, 1.01, 1.1, 2.0, -1.0])
    return repr(v * f)


def bytes_mutation(text, rng):
    """Byte-level damage: truncate, insert/overwrite bytes, BOM, CRLF, empty."""
    op = rng.choice(["truncate", "insert", "insert", "overwrite", "bom", "crlf", "empty",
                     "nul_tail", "repeat"])
    n = len(text)
    if op == "truncate":
        p = rng.randrange(0, max(1, n))
        return text[:p], f"truncate at byte {p} of {n}"
    if op in ("insert", "overwrite"):
        ins = b2s(rng.choice(BYTE_INSERTS)) if rng.random() < 0.7 else \
            b2s(bytes(rng.randrange(256) for _ in range(rng.randint(1, 8))))
        p = rng.randrange(0, n + 1)
        if op == "insert":
            return text[:p] + ins + text[p:], f"insert bytes {s2b(ins)!r} at {p}"
        return text[:p] + ins + text[p + len(ins):], f"overwrite bytes {s2b(ins)!r} at {p}"
    if op == "bom":
        return "\xef\xbb\xbf" + text, "prepend UTF-8 BOM"
    if op == "crlf":
        return text.replace("\n", "\r\n"), "CRLF line ends"
    if op == "empty":
        e = rng.choice(["", "\n", " ", "\n\n\n", "\x00", "# only a comment\n", "\xef\xbb\xbf"])
        return e, f"replace the file by {s2b(e)!r}"
    if op == "nul_tail":
        return text + "\x00" * rng.choice([1, 10, 1000]), "append NUL bytes"
    return text * rng.choice([2, 3]), "repeat the whole file"


def yaml_mutation(text, rng, doc_keys=(), mild=False):
    """One mutation of a YAML text; returns (text, description)."""
    d = YamlDoc(text)
    hostile_ops = [
        ("num_hostile", 14), ("delete_key", 6), ("duplicate_key", 5), ("misspell_key", 5),
        ("change_type", 8), ("list_count", 5), ("bytes", 8), ("second_doc", 2), ("deep", 3),
        ("long", 3), ("empty", 1), ("alias", 2), ("tab", 1), ("add_doc_key", 6),
        ("unknown_key", 2), ("reindent", 2), ("swap_lines", 1), ("anchor_merge", 1),
        ("multiline", 1),
    ]
    mild_ops = [("num_mild", 10), ("num_copy", 4), ("comment", 2), ("crlf", 1),
                ("add_doc_key_mild", 3), ("quote", 2), ("flow_space", 1)]
    ops = mild_ops if mild else hostile_ops
    op = rng.choices([o for o, _ in ops], [w for _, w in ops])[0]
    if op in ("num_hostile", "num_mild", "num_copy"):
        nums = d.numbers()
        if nums:
            i, a, b = rng.choice(nums)
            old = d.lines[i][a:b]
            if op == "num_hostile":
                new = hostile_number(rng)
            elif op == "num_copy":
                j, c, e = rng.choice(nums)
                new = d.lines[j][c:e]
            else:
                new = mild_number(rng, old)
            d.replace(i, a, b, new)
            return d.text(), f"line {i + 1}: number {old} -> {s2b(new)!r}"
        op = "change_type"
    if op == "delete_key":
        bk, fk = d.block_keys(), d.flow_keys()
        if fk and (not bk or rng.random() < 0.4):
            i, a, b = rng.choice(fk)
            line = d.lines[i]
            m = re.compile(r"\s*[A-Za-z_][\w\-]*\s*:\s*(\{[^{}]*\}|\[[^\[\]]*\]|[^,{}\[\]]*)\s*,?")
            mm = m.match(line, a - (len(line[:a]) - len(line[:a].rstrip())))
            if mm:
                d.lines[i] = line[:mm.start()] + line[mm.end():]
                return d.text(), f"line {i + 1}: delete flow key {line[a:b]}"
        if bk:
            i, a, b = rng.choice(bk)
            key = d.lines[i][a:b]
            j = d.block_end(i)
            del d.lines[i:j]
            return d.text(), f"line {i + 1}: delete key {key} ({j - i} lines)"
        op = "bytes"
    if op == "duplicate_key":
        bk, fk = d.block_keys(), d.flow_keys()
        if fk and (not bk or rng.random() < 0.4):
            i, a, b = rng.choice(fk)
            line = d.lines[i]
            mm = re.compile(r"[A-Za-z_][\w\-]*\s*:\s*[^,{}\[\]]*").match(line, a)
            if mm:
                entry = mm.group(0).rstrip()
                d.lines[i] = line[:a] + entry + ", " + line[a:]
                return d.text(), f"line {i + 1}: duplicate flow key {line[a:b]}"
        if bk:
            i, a, b = rng.choice(bk)
            j = d.block_end(i)
            block = d.lines[i:j]
            if rng.random() < 0.5:
                block = [re.sub(NUM_RE, lambda m: mild_number(rng, m.group(0)), block[0], 1)] \
                    + block[1:]
            d.lines[j:j] = block
            return d.text(), f"line {i + 1}: duplicate key {d.lines[i][a:b]}"
        op = "bytes"
    if op == "misspell_key":
        keys = d.block_keys() + d.flow_keys()
        if keys:
            i, a, b = rng.choice(keys)
            k = d.lines[i][a:b]
            how = rng.choice(["swap", "drop", "add", "upper", "underscore", "unicode", "space"])
            if how == "swap" and len(k) > 1:
                p = rng.randrange(len(k) - 1)
                nk = k[:p] + k[p + 1] + k[p] + k[p + 2:]
            elif how == "drop" and len(k) > 1:
                p = rng.randrange(len(k))
                nk = k[:p] + k[p + 1:]
            elif how == "upper":
                nk = k.upper()
            elif how == "underscore":
                nk = k + "_"
            elif how == "unicode":
                nk = k[:-1] + u("\u0435")
            elif how == "space":
                nk = k + " x"
            else:
                nk = k + rng.choice("abcxyz_0")
            d.replace(i, a, b, nk)
            return d.text(), f"line {i + 1}: key {k} -> {s2b(nk)!r}"
        op = "bytes"
    if op in ("change_type", "quote"):
        vals = d.scalar_values()
        if vals:
            i, a, b = rng.choice(vals)
            old = d.lines[i][a:b]
            if op == "quote":
                new = "\"" + old.strip("\"'") + "\""
            else:
                new = u(rng.choice(YAML_VALUE_REPLACEMENTS + HOSTILE_STRINGS[:6]))
            d.replace(i, a, b, new)
            return d.text(), f"line {i + 1}: value {old!r} -> {s2b(new)!r}"
        op = "bytes"
    if op == "list_count":
        lists = [(i, m) for i, line in enumerate(d.lines)
                 for m in FLOW_LIST_RE.finditer(line[:code_end(line)])]
        if lists:
            i, m = rng.choice(lists)
            items = [x.strip() for x in m.group(0)[1:-1].split(",") if x.strip()]
            how = rng.choice(["drop", "add", "empty", "double", "nest", "hostile_item"])
            if how == "drop" and items:
                items = items[:-1]
            elif how == "add":
                items = items + [items[-1] if items and rng.random() < 0.5
                                 else hostile_number(rng)]
            elif how == "empty":
                items = []
            elif how == "double":
                items = items * 2
            elif how == "nest":
                items = ["[" + ", ".join(items) + "]"]
            elif items:
                p = rng.randrange(len(items))
                items[p] = hostile_number(rng)
            new = "[" + ", ".join(items) + "]"
            d.replace(i, m.start(), m.end(), new)
            return d.text(), f"line {i + 1}: list {m.group(0)} -> {s2b(new)[:80]!r} ({how})"
        op = "bytes"
    if op == "second_doc":
        how = rng.choice(["copy", "small", "start", "end"])
        if how == "copy":
            return text + "\n---\n" + text, "append a second document (a copy)"
        if how == "small":
            return text + "\n---\na: 1\n", "append a second document"
        if how == "start":
            return "---\n" + text + "\n...\n", "explicit document start and end"
        return text + "\n...\ngarbage: [\n", "text after the document end"
    if op in ("deep", "long", "multiline"):
        vals = d.scalar_values()
        if op == "deep":
            depth = rng.choice([50, 500, 5000, 50000, 200000])
            kind = rng.choice(["list", "map", "block"])
            if kind == "list":
                new = "[" * depth + "1" + "]" * depth
            elif kind == "map":
                new = "{a: " * depth + "1" + "}" * depth
            else:
                depth = min(depth, 20000)
                new = "\n" + "\n".join(" " * (2 + i) + "- " for i in range(depth)) + "1"
            desc = f"value -> nesting of depth {depth} ({kind})"
        elif op == "long":
            n = rng.choice([1000, 100000, 1000000])
            new = rng.choice(["x" * n, "1" * n, "0." + "0" * n + "1", "\"" + "y" * n + "\"",
                              "[" + ", ".join(["1"] * (n // 10)) + "]"])
            desc = f"value -> long text of {len(new)} characters"
        else:
            new = "|\n" + "\n".join("  line %d" % i for i in range(3))
            desc = "value -> block scalar"
        if vals and rng.random() < 0.85:
            i, a, b = rng.choice(vals)
            d.replace(i, a, b, new)
            return d.text(), f"line {i + 1}: {desc}"
        keys = d.block_keys()
        if keys and op == "long":
            i, a, b = rng.choice(keys)
            d.replace(i, a, b, "k" * rng.choice([1000, 100000]))
            return d.text(), f"line {i + 1}: key -> very long key"
        return text + "\nzz: " + new + "\n", "append key with " + desc
    if op == "empty":
        e = rng.choice(["", "\n", "# comment only\n", "   \n", "---\n", "~\n", "[]\n", "{}\n",
                        "- a\n- b\n", "just a scalar\n", "...\n", "\"\"\n", "null\n"])
        return e, f"replace the file by {e!r}"
    if op == "alias":
        how = rng.choice(["bomb", "undefined", "self"])
        if how == "bomb":
            bomb = ["lol0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
            for lv in range(1, 9):
                bomb.append(f"lol{lv}: &a{lv} [" + ", ".join([f"*a{lv - 1}"] * 10) + "]")
            return "\n".join(bomb) + "\n" + text, "prepend an alias bomb (10^9 leaves)"
        vals = d.scalar_values()
        if vals:
            i, a, b = rng.choice(vals)
            d.replace(i, a, b, "*nope" if how == "undefined" else "&x *x")
            return d.text(), f"line {i + 1}: value -> alias ({how})"
        op = "bytes"
    if op == "anchor_merge":
        keys = [k for k in d.block_keys() if d.lines[k[0]].startswith(d.lines[k[0]][:k[1]])]
        if keys:
            i, a, b = rng.choice(keys)
            ind = d.lines[i][:a]
            d.lines.insert(i, ind + "<<: {extra: 1}")
            return d.text(), f"line {i + 1}: insert a merge key"
        op = "bytes"
    if op == "tab":
        cand = [i for i, ln in enumerate(d.lines) if ln.startswith(" ")]
        if cand:
            i = rng.choice(cand)
            d.lines[i] = "\t" + d.lines[i].lstrip(" ")
            return d.text(), f"line {i + 1}: tab indentation"
        op = "bytes"
    if op == "reindent":
        cand = [i for i, ln in enumerate(d.lines) if ln.strip() and not ln.lstrip().startswith("#")]
        if cand:
            i = rng.choice(cand)
            delta = rng.choice([-2, -1, 1, 3])
            ln = d.lines[i]
            d.lines[i] = (" " * delta + ln) if delta > 0 else ln[min(-delta, len(ln) - len(ln.lstrip())):]
            return d.text(), f"line {i + 1}: indentation {delta:+d}"
        op = "bytes"
    if op == "swap_lines":
        cand = [i for i, ln in enumerate(d.lines) if ln.strip()]
        if len(cand) > 1:
            i, j = rng.sample(cand, 2)
            d.lines[i], d.lines[j] = d.lines[j], d.lines[i]
            return d.text(), f"swap lines {i + 1} and {j + 1}"
        op = "bytes"
    if op in ("add_doc_key", "add_doc_key_mild", "unknown_key"):
        if op == "unknown_key" or not doc_keys:
            key = rng.choice(["bogus", "extra.key", "legs.bogus", "nan", "0", "\"\"", "-",
                              "optimizer.bogus", "task.bogus", "x" * 300])
        else:
            key = rng.choice(list(doc_keys))
        if op == "add_doc_key_mild":
            value = rng.choice(["0.1", "1", "0.5", "[0, 0, 0]", "true", "10", "0.01", "45",
                                "[0.1, 0.2]", "2"])
        else:
            value = rng.choice([hostile_number(rng), rng.choice(YAML_VALUE_REPLACEMENTS),
                                "0.1", "1", "[0, 0, 0]", "[1, 2, 3, 4, 5, 6]", "-1", "0"])
        return insert_yaml_key(d, key, value), f"add key {key}: {s2b(value)[:60]!r}"
    if op == "comment":
        i = rng.randrange(len(d.lines) + 1)
        d.lines.insert(i, "# a comment \u00e9".encode("utf-8").decode("latin-1"))
        return d.text(), f"insert a comment line at {i + 1}"
    if op == "crlf":
        return text.replace("\n", "\r\n"), "CRLF line ends"
    if op == "flow_space":
        return re.sub(r",(?=\S)", ", ", text), "spaces after commas"
    return bytes_mutation(text, rng)


def insert_yaml_key(d, dotted, value):
    parts = dotted.split(".")
    # Find the deepest existing top-level block to insert into.
    top = parts[0]
    for i, line in enumerate(d.lines):
        m = BLOCK_KEY_RE.match(line)
        if m and m.group(1) == "" and not m.group(2) and m.group(3) == top and len(parts) > 1:
            rest = line[m.end():line.__len__()]
            code = rest[:code_end(rest)].strip()
            sub = parts[1:]
            flow = value
            for p in reversed(sub[1:]):
                flow = "{" + p + ": " + flow + "}"
            if code.startswith("{"):
                pos = line.index("{", m.end())
                d.lines[i] = line[:pos + 1] + sub[0] + ": " + flow + ", " + line[pos + 1:]
            elif code == "":
                d.lines.insert(i + 1, "  " + sub[0] + ": " + flow)
            else:
                break
            return d.text()
    flow = value
    for p in reversed(parts[1:]):
        flow = "{" + p + ": " + flow + "}"
    return d.text().rstrip("\n") + "\n" + parts[0] + ": " + flow + "\n"


def csv_mutation(text, rng, mild=False):
    """One mutation of a CSV text; returns (text, description)."""
    nl = "\r\n" if "\r\n" in text else "\n"
    body = text[:-len(nl)] if text.endswith(nl) else text
    rows = body.split(nl)
    if not rows or not rows[0]:
        return bytes_mutation(text, rng)
    cells = [r.split(",") for r in rows]
    header = cells[0]
    hostile_ops = [("cell_hostile", 14), ("cell_text", 4), ("header_rename", 4),
                   ("header_drop", 3), ("header_dup", 3), ("header_empty", 2),
                   ("row_short", 4), ("row_long", 4), ("quoted_newline", 3), ("quote", 2),
                   ("bom", 2), ("bytes", 6), ("header_only", 2), ("blank_lines", 2),
                   ("many_rows", 2), ("many_cols", 1), ("separator", 2), ("delete_col", 3),
                   ("spaces", 2), ("unbalanced_quote", 2), ("long_cell", 2)]
    mild_ops = [("cell_mild", 10), ("crlf", 2), ("reorder_cols", 3), ("extra_col", 3),
                ("dup_row", 2), ("drop_row", 2), ("quote_mild", 1), ("trailing_newlines", 1)]
    ops = mild_ops if mild else hostile_ops
    op = rng.choices([o for o, _ in ops], [w for _, w in ops])[0]
    data_idx = list(range(1, len(cells)))

    def join(cs):
        return nl.join(",".join(r) for r in cs) + nl

    if op in ("cell_hostile", "cell_mild", "cell_text", "long_cell", "quote", "quote_mild",
              "quoted_newline") and data_idx:
        r = rng.choice(data_idx)
        if not cells[r]:
            return bytes_mutation(text, rng)
        c = rng.randrange(len(cells[r]))
        old = cells[r][c]
        if op == "cell_hostile":
            new = hostile_number(rng)
            if "," in new or "\n" in new:
                new = "\"" + new + "\"" if rng.random() < 0.5 else new
        elif op == "cell_mild":
            new = mild_number(rng, old)
        elif op == "cell_text":
            new = u(rng.choice(HOSTILE_STRINGS + ["zero", "1e", "", " "]))
        elif op == "long_cell":
            new = rng.choice(["1" * 100000, "x" * 100000, "0." + "0" * 5000 + "1"])
        elif op in ("quote", "quote_mild"):
            new = "\"" + old + "\""
        else:
            new = "\"" + old + "\n" + old + "\""
        cells[r][c] = new
        return join(cells), f"row {r + 1} column {c + 1}: {old!r} -> {s2b(new)[:60]!r}"
    if op == "header_rename":
        c = rng.randrange(len(header))
        old = header[c]
        new = rng.choice([old.upper(), old + " ", " " + old, old + "_", old[:-1] or "q",
                          "\"" + old + "\"", u(old + "\u00e9"), "nan", old + "\x00"])
        header[c] = new
        return join(cells), f"header {old!r} -> {s2b(new)!r}"
    if op == "header_drop":
        c = rng.randrange(len(header))
        old = header.pop(c)
        return join(cells), f"header column {old!r} removed (rows keep their cells)"
    if op == "header_dup":
        c = rng.randrange(len(header))
        header.append(header[c])
        for r in cells[1:]:
            if r:
                r.append(r[c] if c < len(r) else "0")
        return join(cells), f"duplicate column {header[c]!r}"
    if op == "header_empty":
        c = rng.randrange(len(header))
        header[c] = ""
        return join(cells), f"header column {c + 1} name emptied"
    if op == "delete_col":
        c = rng.randrange(len(header))
        name = header[c]
        for r in cells:
            if c < len(r):
                r.pop(c)
        return join(cells), f"column {name!r} deleted"
    if op in ("row_short", "row_long") and data_idx:
        r = rng.choice(data_idx)
        if op == "row_short" and cells[r]:
            cells[r] = cells[r][:rng.randrange(len(cells[r]))]
        else:
            cells[r] = cells[r] + ["1"] * rng.randint(1, 3)
        return join(cells), f"row {r + 1} with {len(cells[r])} cells"
    if op == "bom":
        return "\xef\xbb\xbf" + text, "UTF-8 BOM"
    if op == "header_only":
        return join(cells[:1]), "no data rows"
    if op == "blank_lines":
        p = rng.randint(1, len(cells))
        rows2 = [",".join(r) for r in cells]
        rows2.insert(p, rng.choice(["", " ", ",,,", "\t"]))
        return nl.join(rows2) + nl, f"blank line at {p + 1}"
    if op == "many_rows" and data_idx:
        n = rng.choice([1000, 20000])
        out = cells[:1] + [cells[data_idx[i % len(data_idx)]] for i in range(n)]
        return join(out), f"{n} data rows"
    if op == "many_cols":
        n = rng.choice([100, 5000])
        cells = [r + [("c%d" % i if j == 0 else "0") for i in range(n)] for j, r in enumerate(cells)]
        return join(cells), f"{n} extra columns"
    if op == "separator":
        sep = rng.choice([";", "\t", ", ", " "])
        return nl.join(sep.join(r) for r in cells) + nl, f"separator {sep!r}"
    if op == "spaces" and data_idx:
        r = rng.choice(data_idx)
        cells[r] = [" " + x + " " for x in cells[r]]
        return join(cells), f"row {r + 1}: spaces around cells"
    if op == "unbalanced_quote":
        r = rng.randrange(len(cells))
        if cells[r]:
            cells[r][0] = "\"" + cells[r][0]
        return join(cells), f"row {r + 1}: unbalanced quote"
    if op == "crlf":
        return text.replace("\r\n", "\n").replace("\n", "\r\n"), "CRLF line ends"
    if op == "reorder_cols":
        perm = list(range(len(header)))
        rng.shuffle(perm)
        cells = [[r[p] if p < len(r) else "" for p in perm] for r in cells]
        return join(cells), "columns reordered"
    if op == "extra_col":
        name = rng.choice(["label", "note", "extra", "w"])
        cells = [r + [name if j == 0 else str(j)] for j, r in enumerate(cells)]
        return join(cells), f"extra column {name}"
    if op == "dup_row" and data_idx:
        r = rng.choice(data_idx)
        cells.insert(r, list(cells[r]))
        return join(cells), f"row {r + 1} duplicated"
    if op == "drop_row" and len(data_idx) > 1:
        r = rng.choice(data_idx)
        del cells[r]
        return join(cells), f"row {r + 1} removed"
    if op == "trailing_newlines":
        return text + nl * 2, "trailing blank lines"
    return bytes_mutation(text, rng)


class _Raw:
    def __init__(self, text):
        self.text = text


def json_paths(node, path=()):
    out = [(path, node)]
    if isinstance(node, dict):
        for k, v in node.items():
            out.extend(json_paths(v, path + (k,)))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.extend(json_paths(v, path + (i,)))
    return out


def json_set(root, path, value):
    if not path:
        return value
    node = root
    for p in path[:-1]:
        node = node[p]
    node[path[-1]] = value
    return root


def json_dump_raw(obj):
    raws = []

    def conv(n):
        if isinstance(n, _Raw):
            raws.append(n.text)
            return "\x00RAW%d\x00" % (len(raws) - 1)
        if isinstance(n, dict):
            return {k: conv(v) for k, v in n.items()}
        if isinstance(n, list):
            return [conv(v) for v in n]
        return n

    s = json.dumps(conv(obj), indent=2, ensure_ascii=False)
    for i, r in enumerate(raws):
        s = s.replace(json.dumps("\x00RAW%d\x00" % i), r)
    return s


def json_mutation(text, rng, mild=False):
    try:
        obj = json.loads(s2b(text).decode("utf-8"))
    except (ValueError, UnicodeDecodeError, RecursionError):
        return bytes_mutation(text, rng)
    paths = json_paths(obj)
    nums = [(p, v) for p, v in paths if isinstance(v, (int, float)) and not isinstance(v, bool)]
    strs = [(p, v) for p, v in paths if isinstance(v, str)]
    keyed = [(p, v) for p, v in paths if p and isinstance(p[-1], str)]
    lists = [(p, v) for p, v in paths if isinstance(v, list)]
    if mild:
        op = rng.choice(["num_mild", "num_mild", "reorder", "compact", "extra_key"])
    else:
        op = rng.choices(["num_raw", "type", "delete", "rename", "list", "str", "text", "dup_key",
                          "deep", "null"], [12, 8, 7, 4, 5, 5, 7, 2, 2, 4])[0]
    if op == "num_mild" and nums:
        p, v = rng.choice(nums)
        nv = v + 1 if isinstance(v, int) else v * rng.choice([0.5, 1.01, 2.0, -1.0])
        obj = json_set(obj, p, nv)
        return u(json_dump_raw(obj)), f"{_jp(p)}: {v} -> {nv}"
    if op == "reorder" and isinstance(obj, dict):
        items = list(obj.items())
        rng.shuffle(items)
        return u(json_dump_raw(dict(items))), "top-level keys reordered"
    if op == "compact":
        return u(json.dumps(obj, separators=(",", ":"))), "compact JSON"
    if op == "extra_key" and isinstance(obj, dict):
        obj["x_extra"] = {"a": [1, 2]}
        return u(json_dump_raw(obj)), "extra top-level key"
    if op == "num_raw" and nums:
        p, v = rng.choice(nums)
        design_nums = [(q, w) for q, w in nums if q and q[0] == "designs"]
        if design_nums and rng.random() < 0.5:
            # Finite extremes in the values a report plots and sums (objectives first).
            objs = [(q, w) for q, w in design_nums if "objectives" in q]
            p, v = rng.choice(objs if objs and rng.random() < 0.7 else design_nums)
            raw = rng.choice(["1.7976931348623157e308", "-1.7976931348623157e308", "1e308",
                              "-1e308", "1e300", "-1e300", "1e200", "4.9e-324", "1e-320",
                              "2.2250738585072014e-308", "1e15", "-1e15", "0", "-0"])
            obj = json_set(obj, p, _Raw(raw))
            return u(json_dump_raw(obj)), f"{_jp(p)}: {v} -> {raw}"
        raw = rng.choice(["NaN", "-NaN", "Infinity", "-Infinity", "1e400", "-1e400", "1e-400",
                          "-0", "123456789012345678901234567890", "0x10", "1.", ".5", "01",
                          "+1", "1e", "nan", "inf", "\"1\"", "\"nan\"", "9" * 400,
                          "9223372036854775808", "-9223372036854775809", "4.9e-324",
                          "1.7976931348623157e308", "2147483648"])
        obj = json_set(obj, p, _Raw(raw))
        return u(json_dump_raw(obj)), f"{_jp(p)}: {v} -> {raw}"
    if op == "type" and paths:
        p, v = rng.choice(paths[1:] or paths)
        nv = rng.choice(["abc", "", 1, 0, -1, 1.5, [], {}, [1, 2], {"a": 1}, None, True, False,
                         [[1]], "d0000"])
        obj = json_set(obj, p, nv)
        return u(json_dump_raw(obj)), f"{_jp(p)}: {type(v).__name__} -> {json.dumps(nv)}"
    if op == "null" and paths:
        p, v = rng.choice(paths[1:] or paths)
        obj = json_set(obj, p, None)
        return u(json_dump_raw(obj)), f"{_jp(p)}: -> null"
    if op == "delete" and keyed:
        p, v = rng.choice(keyed)
        node = obj
        for q in p[:-1]:
            node = node[q]
        del node[p[-1]]
        return u(json_dump_raw(obj)), f"{_jp(p)}: deleted"
    if op == "rename" and keyed:
        p, v = rng.choice(keyed)
        node = obj
        for q in p[:-1]:
            node = node[q]
        nk = rng.choice([p[-1].upper(), p[-1] + "_", p[-1][:-1], "", " " + p[-1], "nan"])
        node[nk] = node.pop(p[-1])
        return u(json_dump_raw(obj)), f"{_jp(p)}: key renamed to {nk!r}"
    if op == "list" and lists:
        p, v = rng.choice(lists)
        how = rng.choice(["empty", "dup", "drop", "add", "many"])
        if how == "empty":
            nv = []
        elif how == "dup" and v:
            nv = v + [v[rng.randrange(len(v))]]
        elif how == "drop" and v:
            nv = v[:-1]
        elif how == "many" and v:
            nv = v * rng.choice([100, 2000])
        else:
            nv = v + [rng.choice([1, "x", None, {}, []])]
        obj = json_set(obj, p, nv)
        return u(json_dump_raw(obj)), f"{_jp(p)}: list {how} ({len(v)} -> {len(nv)} items)"
    if op == "str" and strs:
        p, v = rng.choice(strs)
        nv = rng.choice(HOSTILE_STRINGS + ["d0000", "d9999", "designs/missing.yaml", "/dev/null",
                                           "designs", "designs/../../x.yaml", "maximize",
                                           "minimize", "max", "pkmopt-pareto-2", "\u0000x",
                                           "designs/d0000.yaml"])
        obj = json_set(obj, p, nv)
        return u(json_dump_raw(obj)), f"{_jp(p)}: {v!r} -> {nv[:60]!r}"
    if op == "dup_key":
        m = list(re.finditer(r"\n(\s*)(\"[^\"]+\": [^\n{\[]+?),?\n", text))
        if m:
            mm = rng.choice(m)
            ins = "\n" + mm.group(1) + mm.group(2).rstrip(",") + ","
            return text[:mm.start()] + ins + text[mm.start():], "duplicate key " + mm.group(2)[:40]
    if op == "deep" and paths:
        p, v = rng.choice(paths[1:] or paths)
        depth = rng.choice([100, 10000, 100000])
        obj = json_set(obj, p, _Raw("[" * depth + "1" + "]" * depth))
        return u(json_dump_raw(obj)), f"{_jp(p)}: nesting depth {depth}"
    return bytes_mutation(text, rng)


def _jp(p):
    return "".join(f"[{x}]" if isinstance(x, int) else f".{x}" for x in p) or "(root)"


def text_mutation(text, rng, mild=False):
    """Line/token mutations for line-based files (journal.txt, run.lock)."""
    lines = text.split("\n")
    op = rng.choice(["token", "token", "delete_line", "dup_line", "swap", "truncate_lines",
                     "bytes", "header"]) if not mild else rng.choice(["truncate_lines",
                                                                       "delete_line"])
    if op == "token":
        toks = [(i, m) for i, ln in enumerate(lines) for m in re.finditer(r"\S+", ln)]
        if toks:
            i, m = rng.choice(toks)
            new = rng.choice(["nan", "-nan", "inf", "0x1p+1024", "0x1.fffffffffffffp+1023",
                              "0x0.0000000000001p-1022", "zz", "", "0x", "1e999", "-0x0p+0",
                              "99999999999999999999", "0x1.8p+1 0x1.8p+1"] + HOSTILE_NUMBERS[:20])
            lines[i] = lines[i][:m.start()] + u(new) + lines[i][m.end():]
            return "\n".join(lines), f"line {i + 1}: token {m.group(0)[:30]!r} -> {new[:30]!r}"
    if op == "delete_line" and len(lines) > 1:
        i = rng.randrange(len(lines))
        del lines[i]
        return "\n".join(lines), f"line {i + 1} deleted"
    if op == "dup_line" and lines:
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
        return "\n".join(lines), f"line {i + 1} duplicated"
    if op == "swap" and len(lines) > 2:
        i, j = rng.sample(range(len(lines)), 2)
        lines[i], lines[j] = lines[j], lines[i]
        return "\n".join(lines), f"lines {i + 1} and {j + 1} swapped"
    if op == "truncate_lines" and len(lines) > 2:
        n = rng.randrange(1, len(lines))
        return "\n".join(lines[:n]) + "\n", f"kept the first {n} of {len(lines)} lines"
    if op == "header" and lines:
        new = rng.choice(["pkmopt-journal 3", "pkmopt-journal 99999999999999999999", "",
                          "pkmopt-journal", "journal 2", lines[0] + " extra"])
        lines[0] = new
        return "\n".join(lines), f"first line -> {new!r}"
    return bytes_mutation(text, rng)


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


# ----------------------------------------------------------------------------------------------
# Option mutations
# ----------------------------------------------------------------------------------------------

def hostile_list(rng, n, base=None):
    items = base.split(",") if base else ["0.1"] * n
    how = rng.choice(["fewer", "more", "empty", "one", "hostile_item", "hostile_item",
                      "empty_item", "spaces", "brackets", "semicolons", "many", "trailing"])
    if how == "fewer":
        items = items[:max(0, len(items) - rng.randint(1, max(1, len(items))))]
        return ",".join(items), how
    if how == "more":
        return ",".join(items + ["0"] * rng.randint(1, 3)), how
    if how == "empty":
        return "", how
    if how == "one":
        return items[0] if items else "1", how
    if how == "hostile_item":
        p = rng.randrange(max(1, len(items)))
        items = items or ["0"]
        items[p] = hostile_number(rng).replace(",", ";")
        return ",".join(items), how
    if how == "empty_item":
        p = rng.randrange(max(1, len(items)))
        items = items or ["0"]
        items[p] = ""
        return ",".join(items), how
    if how == "spaces":
        return ", ".join(items), how
    if how == "brackets":
        return "[" + ",".join(items) + "]", how
    if how == "semicolons":
        return ";".join(items), how
    if how == "many":
        return ",".join(["1"] * rng.choice([100, 10000])), how
    return ",".join(items) + ",", how


def hostile_in_path(case, rng, src_rel, want_dir=False):
    """A hostile value for an input file (or folder) option."""
    how = rng.choice(["dir", "devnull", "missing", "fifo", "fifo_empty", "empty", "junk",
                      "symlink_loop", "emptystr", "long", "dotdir", "file_as_dir", "binary"])
    if how == "dir":
        case.files["adir"] = ("dir",)
        return "adir", how
    if how == "devnull":
        return "/dev/null", how
    if how == "missing":
        return "missing" + (".yaml" if not want_dir else ""), how
    if how == "fifo":
        entry = case.files.get(src_rel, ("file", "x: 1\n"))
        feed = entry[1] if len(entry) > 1 else ""  # a folder or a removed file feeds nothing
        case.files["fifo_in"] = ("fifo", feed if isinstance(feed, str) else "")
        return "fifo_in", how
    if how == "fifo_empty":
        case.files["fifo_in"] = ("fifo", "")
        return "fifo_in", how
    if how == "empty":
        if want_dir:
            case.files["emptydir"] = ("dir",)
            return "emptydir", how
        case.add_file("empty.txt", "")
        return "empty.txt", how
    if how == "junk":
        case.add_file("junk.bin", b2s(bytes(range(256)) * 4))
        return "junk.bin", how
    if how == "binary":
        case.add_file("binary.png", "\x89PNG\r\n\x1a\n" + "\x00" * 100)
        return "binary.png", how
    if how == "symlink_loop":
        case.files["loop"] = ("symlink", "loop")
        return "loop", how
    if how == "emptystr":
        return "", how
    if how == "long":
        return "a" * 300 + ".yaml", how
    if how == "dotdir":
        return ".", how
    return (src_rel or "machine.yaml") + "/x", how


def hostile_out_path(case, rng, is_dir):
    how = rng.choice(["existing_dir", "missing_parent", "devnull", "fifo", "input_file",
                      "emptystr", "dot", "long", "through_file", "trailing_slash", "existing_file",
                      "nested_ok"])
    if how == "existing_dir":
        case.files["odir"] = ("dir",)
        return "odir", how
    if how == "missing_parent":
        return "no/such/dir/" + ("out" if is_dir else "out.csv"), how
    if how == "devnull":
        case.files["devnull"] = ("symlink", "/dev/null")
        return "devnull", how
    if how == "fifo":
        case.files["fifo_out"] = ("fifo_out",)
        return "fifo_out", how
    if how == "input_file":
        ins = [r for r, f in case.files.items() if f[0] == "file"]
        return (rng.choice(ins) if ins else "x"), how
    if how == "emptystr":
        return "", how
    if how == "dot":
        return ".", how
    if how == "long":
        return "o" * 300, how
    if how == "through_file":
        ins = [r for r, f in case.files.items() if f[0] == "file"]
        return (rng.choice(ins) if ins else "x") + "/out", how
    if how == "trailing_slash":
        return ("newdir/" if is_dir else "out.csv/"), how
    if how == "existing_file":
        case.add_file("existing.txt", "old\n")
        return "existing.txt", how
    return ("sub/dir/out" if is_dir else "sub_ok.csv"), how


def mutate_options(case, rng, ctx):
    ops = ["value", "value", "value", "value", "drop", "dup", "unknown", "flag_value",
           "eq_form", "positional", "extra_positional"]
    op = rng.choice(ops)
    opts = [it for it in case.items if it[0] == "opt" and it[1] not in case.fixed]
    if op == "value" and case.spec:
        name = rng.choice(sorted(case.spec))
        kind = case.spec[name]
        cur = case.opt_value(name)
        if kind == "flag":
            op = "flag_value"
        else:
            if kind in ("float", "int", "uint"):
                r = rng.random()
                if r < 0.25 and cur is not None:
                    val = mild_number(rng, cur)
                elif kind in ("int", "uint") and r < 0.35:
                    val = rng.choice(["1.5", "1e3", "0x10", "-1", "0", "+3", "3 ", "2e0"])
                elif kind in ("int", "uint") and r < 0.5:
                    # Counts that fit an int but ask for far too much work.
                    val = rng.choice(["2147483647", "1000000000", "100000000", "10000000"])
                else:
                    val = hostile_number(rng)
                    val = s2b(val).decode("utf-8", "replace")
                desc = f"{name} {val[:60]!r}"
            elif kind == "threads":
                val = rng.choice(["-1", "2147483648", "abc", "", "1.5", "9223372036854775807",
                                  "-2147483649", "1e3", "0x1", "0", "2", "-0", " 1"])
                desc = f"{name} {val!r}"
            elif kind.startswith("list"):
                n = int(kind[4:])
                val, how = hostile_list(rng, n, cur)
                val = s2b(u(val)).decode("utf-8", "replace")
                desc = f"{name} {val[:60]!r} ({how})"
            elif kind.startswith("enum:"):
                vals = kind[5:].split(",")
                base = cur or vals[0]
                val = rng.choice([base.upper(), base + "x", "", base[:-1], " " + base,
                                  rng.choice(vals), rng.choice(vals), "a\nb", base + ",",
                                  rng.choice(HOSTILE_STRINGS[:8])])
                desc = f"{name} {val[:60]!r}"
            elif kind in ("text", "text_obj"):
                pool = HOSTILE_STRINGS + ["stiffness_min", "machine_size", "workspace_volume",
                                          "Stiffness_min", "nan", "CMS50S/70", "cheapest"]
                val = s2b(u(rng.choice(pool))).decode("utf-8", "replace")
                desc = f"{name} {val[:60]!r}"
            elif kind == "in_file":
                src = cur if cur in case.files else None
                val, how = hostile_in_path(case, rng, src)
                desc = f"{name} {val[:60]!r} ({how})"
            elif kind in ("out_file", "out_dir"):
                val, how = hostile_out_path(case, rng, kind == "out_dir")
                desc = f"{name} {val[:60]!r} ({how})"
            else:
                val, desc = "x", name + " x"
            if cur is None:
                case.opt(name, val)
                case.mutations.append("option added: " + desc)
            else:
                for it in case.items:
                    if it[0] == "opt" and it[1] == name:
                        it[2] = val
                case.mutations.append("option value: " + desc)
            return
    if op == "flag_value":
        flags = [n for n, k in case.spec.items() if k == "flag"]
        if flags:
            f = rng.choice(flags)
            how = rng.choice(["value", "twice", "add"])
            if how == "value":
                case.items.append(["opt", f, rng.choice(["1", "0", "true", "yes"]), "eq"])
            elif how == "twice":
                case.opt(f)
                case.opt(f)
            else:
                case.opt(f)
            case.mutations.append(f"flag {f} ({how})")
            return
        op = "unknown"
    if op == "drop" and (opts or case.items):
        pool = opts or [it for it in case.items]
        it = rng.choice(pool)
        case.items.remove(it)
        case.mutations.append(f"dropped {it[1]}")
        return
    if op == "dup" and opts:
        it = rng.choice(opts)
        new = list(it)
        if new[2] is not None and rng.random() < 0.5:
            new[2] = mild_number(rng, new[2]) if re.fullmatch(r"[-+0-9.e]+", new[2]) else new[2]
        case.items.append(new)
        case.mutations.append(f"duplicated {it[1]}")
        return
    if op == "eq_form" and opts:
        it = rng.choice([o for o in opts if o[2] is not None] or opts)
        if it[2] is not None:
            it[3] = "eq"
            case.mutations.append(f"{it[1]}=VALUE form")
            return
    if op in ("positional", "extra_positional"):
        pos = [i for i, it in enumerate(case.items) if it[0] == "pos"]
        kinds = case.meta.get("pos_kinds", ["in_file"])
        if op == "positional" and pos:
            i = rng.choice(pos)
            idx = pos.index(i)
            src = case.items[i][1]
            val, how = hostile_in_path(case, rng, src, kinds[min(idx, len(kinds) - 1)] == "in_dir")
            case.items[i][1] = val
            case.mutations.append(f"positional {src!r} -> {val[:60]!r} ({how})")
            return
        extra = rng.choice(["extra.yaml", "-", "--", "--=", "-x", "", case.items[pos[0]][1]
                            if pos else "a"])
        case.items.append(["pos", extra])
        case.mutations.append(f"extra argument {extra!r}")
        return
    bogus = rng.choice(["--bogus", "-x", "--", "---", "-", "--out-", "--OUT", "--help=1",
                        "--version", "--q=", "-h"])
    case.items.insert(rng.randrange(len(case.items) + 1), ["pos", bogus])
    case.mutations.append(f"unknown argument {bogus!r}")


def mutate_case(case, rng, ctx):
    if case.cmd == "python":
        case.mutated = bool(case.mutations)
        files = sorted(k for k in case.kinds if k != "case.py")
        if not files or rng.random() < 0.5:
            return
        case.mutated = True
        rel = rng.choice(files)
        kind = case.kinds[rel]
        text = case.files[rel][1]
        if kind.startswith("yaml"):
            group = kind.split(":", 1)[1] if ":" in kind else ""
            new, desc = yaml_mutation(text, rng, ctx.doc_keys.get(group, ()),
                                      rng.random() < 0.35)
        elif kind == "csv":
            new, desc = csv_mutation(text, rng, rng.random() < 0.35)
        elif kind == "json":
            new, desc = json_mutation(text, rng, rng.random() < 0.35)
        else:
            new, desc = text_mutation(text, rng)
        case.files[rel] = ("file", new)
        case.mutations.append(f"{rel}: {desc}")
        return
    r = rng.random()
    if r < 0.04:
        return  # unmutated baseline run
    n = 1 if r < 0.68 else (2 if r < 0.88 else 3)
    case.mutated = True
    for _ in range(n):
        targets = sorted(case.kinds)
        # Files named by the command line are mutated more often than the options.
        w_files = 0.7 if targets else 0.0
        if rng.random() < w_files:
            rel = rng.choice(targets)
            f = case.files.get(rel)
            if not f or f[0] != "file":
                continue
            kind = case.kinds[rel]
            refs = list(PATH_KEY_RE.finditer(f[1])) if kind.startswith("yaml") else []
            if refs and rng.random() < 0.25:
                m = rng.choice(refs)
                if rng.random() < 0.25:
                    val, how = rel, "the file itself"
                else:
                    val, how = hostile_in_path(case, rng, None)
                    val = val or "''"
                case.files[rel] = ("file", f[1][:m.start(2)] + val + f[1][m.end(2):])
                case.mutations.append(f"{rel}: {m.group(1)}: {m.group(2)!r} -> {val[:60]!r} "
                                      f"({how})")
                continue
            mild = rng.random() < 0.35
            text = f[1]
            if kind.startswith("yaml"):
                group = kind.split(":", 1)[1] if ":" in kind else ""
                new, desc = yaml_mutation(text, rng, ctx.doc_keys.get(group, ()), mild)
            elif kind == "csv":
                new, desc = csv_mutation(text, rng, mild)
            elif kind == "json":
                new, desc = json_mutation(text, rng, mild)
            else:
                new, desc = text_mutation(text, rng, mild)
            case.files[rel] = ("file", new)
            case.mutations.append(f"{rel}: {'(mild) ' if mild else ''}{desc}")
        else:
            mutate_options(case, rng, ctx)


PATH_KEY_RE = re.compile(r"(?m)(?:^\s*|[{,]\s*)(file|machine|measurements|catalog):[ \t]*"
                         r"(\"[^\"\n]*\"|[^\s,{}#]+)")


def make_case(seed, k, ctx):
    rng = random.Random(f"pkmopt-campaign:{seed}:{k}")
    cmd = COMMANDS[k % len(COMMANDS)]
    case = Case(k, cmd)
    GENERATORS[cmd](case, rng, ctx)
    mutate_case(case, rng, ctx)
    return case


# ----------------------------------------------------------------------------------------------
# Running one case
# ----------------------------------------------------------------------------------------------

def materialize(case, root):
    root.mkdir(parents=True, exist_ok=True)
    for rel, src in case.trees:
        shutil.copytree(src, root / rel, symlinks=True)
    for rel, f in case.files.items():
        p = root / rel
        if f[0] == "gone":
            if p.exists():
                p.unlink()
            continue
        p.parent.mkdir(parents=True, exist_ok=True)
        if p.is_symlink() or p.exists():
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()
        if f[0] == "file":
            p.write_bytes(s2b(f[1]))
        elif f[0] == "dir":
            p.mkdir()
        elif f[0] in ("fifo", "fifo_out"):
            os.mkfifo(p)
        elif f[0] == "symlink":
            os.symlink(f[1], p)


def snapshot(root):
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for name in filenames + dirnames:
            p = os.path.join(dirpath, name)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            rel = os.path.relpath(p, root)
            out[rel] = (stat.S_IFMT(st.st_mode), st.st_size, st.st_mtime_ns, st.st_ino)
    return out


class FifoFeeder(threading.Thread):
    """Feeds an input FIFO (each time it is opened) or drains an output FIFO until stopped."""

    def __init__(self, path, data, reader):
        super().__init__(daemon=True)
        self.path, self.data, self.reader = path, data, reader
        self.stop = threading.Event()
        self.drained = bytearray()

    def run(self):
        if self.reader:
            try:
                fd = os.open(self.path, os.O_RDONLY | os.O_NONBLOCK)
            except OSError:
                return
            try:
                while not self.stop.is_set():
                    try:
                        chunk = os.read(fd, 65536)
                    except BlockingIOError:
                        chunk = None
                    except OSError:
                        break
                    if chunk:
                        if len(self.drained) < 64 << 20:
                            self.drained.extend(chunk)
                    else:
                        time.sleep(0.005)
            finally:
                os.close(fd)
            return
        while not self.stop.is_set():
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_NONBLOCK)
            except OSError as e:
                if e.errno in (errno.ENXIO, errno.EAGAIN, errno.EINTR):
                    time.sleep(0.005)
                    continue
                return
            try:
                os.set_blocking(fd, True)
                view = memoryview(self.data)
                while view and not self.stop.is_set():
                    n = os.write(fd, view[:65536])
                    view = view[n:]
            except OSError:
                pass
            finally:
                os.close(fd)
            time.sleep(0.02)


def limits():
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
    resource.setrlimit(resource.RLIMIT_FSIZE, (512 << 20, 512 << 20))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def run_binary(binary, argv, cwd, timeout, out_dir, env, fifos=()):
    """Runs binary; returns (returncode or None on timeout, stdout bytes, stderr bytes, secs)."""
    so_path, se_path = out_dir / "stdout.bin", out_dir / "stderr.bin"
    feeders = []
    for path, data, reader in fifos:
        fd = FifoFeeder(str(path), data, reader)
        fd.start()
        feeders.append(fd)
    t0 = time.monotonic()
    with open(so_path, "wb") as so, open(se_path, "wb") as se:
        proc = subprocess.Popen([binary] + argv, cwd=cwd, stdin=subprocess.DEVNULL, stdout=so,
                                stderr=se, env=env, start_new_session=True, preexec_fn=limits)
        try:
            rc = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait()
            rc = None
    secs = time.monotonic() - t0
    for fd in feeders:
        fd.stop.set()
    for fd in feeders:
        fd.join(timeout=2)
    return rc, read_capped(so_path), read_capped(se_path), secs, feeders


def read_capped(p, cap=64 << 20):
    with open(p, "rb") as f:
        return f.read(cap)


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
