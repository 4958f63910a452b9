"""Mutators of YAML, CSV, JSON, text and bytes. (the mutation campaign: fuzz/campaign/main.py)."""

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

from .values import BLOCK_KEY_RE, BOUNDARY_NUMBERS, BYTE_INSERTS, FLOW_LIST_RE, HOSTILE_NUMBERS, HOSTILE_STRINGS, NON_NUMBERS, NUM_RE, YAML_VALUE_REPLACEMENTS, YamlDoc, b2s, code_end, s2b, u  # noqa: F401
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
