#!/usr/bin/env python3
"""Every command block of every study page runs as written.

Collects the command blocks of studies/library/README.md, studies/library/*.md and
studies/library/*/README.md (fenced blocks and blocks indented by four spaces whose lines are
commands; a drawing or a table of numbers is not a command block) and runs each page's blocks in
order, as a user would from the repository root after the README's two commands with build/bin
on the PATH, each page in a fresh folder that holds the repository's studies/ and examples/ and
build/bin/pkmopt.

A reduced form where a command is long: the study files are copies with at most 12 NSGA-II
generations; a line `# reduced form ...: COMMAND` in a block replaces the command before it;
QUICK=1 is set for the scripts that know it. Everything else (paths, options, outputs) is as
written.

Usage: readme_commands_test.py PKMOPT_BINARY SOURCE_DIR SCRATCH_DIR
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

COMMAND = re.compile(r"^(pkmopt |PKMOPT=|QUICK=|studies/|export |bash |\./build/bin/pkmopt |"
                     r"PYTHONPATH=|/usr/bin/python3 |column |cat |ls |printf |echo |mkdir |cp |"
                     r"sed |awk |head |tail )")


def blocks(markdown):
    """The command blocks of a page: lists of lines."""
    found, fenced, current = [], False, []
    lines = markdown.splitlines()
    for k, line in enumerate(lines):
        if line.startswith("```"):
            if fenced:
                found.append(current)
            fenced, current = not fenced, []
            continue
        if fenced:
            current.append(line)
    # Indented blocks: four spaces after a blank line, outside fences.
    fenced, k = False, 0
    while k < len(lines):
        if lines[k].startswith("```"):
            fenced = not fenced
        elif (not fenced and lines[k].startswith("    ") and (k == 0 or not lines[k - 1].strip())
              and not lines[k].lstrip().startswith(("-", "*", "|"))):
            block = []
            while k < len(lines) and (lines[k].startswith("    ") or not lines[k].strip()):
                block.append(lines[k][4:])
                k += 1
            found.append(block)
            continue
        k += 1
    return [b for b in found if is_command_block(b)]


def is_command_block(block):
    lines = [ln.strip() for ln in block if ln.strip()]
    return bool(lines) and all(COMMAND.match(ln) or ln.startswith("#") for ln in lines) and any(
        COMMAND.match(ln) for ln in lines)


def commands(block):
    """The commands of a block, a `# reduced form ...: CMD` line replacing the command before."""
    result = []
    for line in block:
        text = line.strip()
        reduced = re.match(r"^#\s*reduced form[^:]*:\s*(.+)$", text)
        if reduced and result:
            result[-1] = reduced.group(1).replace("DIR", "results/reduced")
            continue
        if not text or text.startswith("#"):
            continue
        result.append(text)
    return result


def reduce_budgets(library):
    for f in list(library.glob("*.yaml")) + list(library.glob("*/*.yaml")):
        text = f.read_text()
        text = re.sub(r"generations: *(\d+)",
                      lambda m: f"generations: {min(int(m.group(1)), 12)}", text)
        f.write_text(text)


def main():
    binary, source, scratch = (pathlib.Path(a).resolve() for a in sys.argv[1:4])
    if scratch.exists():
        shutil.rmtree(scratch)
    tree = scratch / "tree"
    shutil.copytree(source / "studies", tree / "studies")
    reduce_budgets(tree / "studies" / "library")
    pages = [source / "studies/library/README.md"]
    pages += sorted((source / "studies/library").glob("*.md"))
    pages += sorted((source / "studies/library").glob("*/README.md"))
    pages = list(dict.fromkeys(pages))
    failures = ran = 0
    for page in pages:
        page_blocks = blocks(page.read_text())
        if not page_blocks:
            continue
        name = str(page.relative_to(source))
        work = scratch / "pages" / name.replace("/", "_")
        work.mkdir(parents=True)
        (work / "studies").symlink_to(tree / "studies")
        (work / "examples").symlink_to(source / "examples")
        (work / "build" / "bin").mkdir(parents=True)
        (work / "build" / "bin" / "pkmopt").symlink_to(binary)
        env = dict(os.environ, QUICK="1", PATH=f"{work / 'build' / 'bin'}:{os.environ['PATH']}")
        env.pop("PKMOPT", None)
        for block in page_blocks:
            script = "set -e\n" + "\n".join(commands(block)) + "\n"
            r = subprocess.run(["bash", "-c", script], cwd=work, env=env, capture_output=True,
                               text=True, timeout=900)
            ran += 1
            if r.returncode != 0:
                failures += 1
                print(f"FAIL {name}: exit {r.returncode}\n{script}{r.stderr[-2000:]}")
            else:
                print(f"ok   {name}: {len(commands(block))} commands")
    print(f"{ran} command blocks, {failures} failed")
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
