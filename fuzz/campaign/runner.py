"""Running one case: its files, limits, FIFO feeders, the binary. (the mutation campaign: fuzz/campaign/main.py)."""

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

from .values import s2b  # noqa: F401
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
