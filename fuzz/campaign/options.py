"""Option mutations, and making the mutated case of a run. (the mutation campaign: fuzz/campaign/main.py)."""

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

from .common import COMMANDS  # noqa: F401
from .values import HOSTILE_STRINGS, b2s, s2b, u  # noqa: F401
from .mutators import csv_mutation, hostile_number, json_mutation, mild_number, text_mutation, yaml_mutation  # noqa: F401
from .cases import Case, GENERATORS  # noqa: F401
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
