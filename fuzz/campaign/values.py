"""Hostile and boundary values, and text helpers (files as latin-1 strings). (the mutation campaign: fuzz/campaign/main.py)."""

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

from .common import REPO  # noqa: F401
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
