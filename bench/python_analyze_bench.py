#!/usr/bin/python3
"""Throughput of pkmopt's Python `Machine.analyze` against the C++ batch path.

Times `m.analyze(poses, wrench, threads=T)` on 10^6 poses of the docs/conventions.md hexapod
(examples/hexapod.yaml) — the very poses of the C++ benchmark (bench/hexapod_poses.hpp: the
splitmix64 stream seeded 12345, x, y in [-0.15, 0.15] m, z in [0.75, 0.95] m, rx, ry in
[-15, 15] deg, rz in [-20, 20] deg) —, best of --repetitions, and runs pkmopt_bench's
BM_HexapodAnalyzeBatch with the same poses, thread count and wrench; prints both
throughputs and their ratio (goal: Python >= 90 % of C++).

Usage (after scripts/build.sh):
  PYTHONPATH=build/python /usr/bin/python3 bench/python_analyze_bench.py [--threads 1]
"""

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def bench_poses(n, seed=12345):
    """bench/hexapod_poses.hpp's poses: draw k = lo + (hi - lo) * (splitmix64 word k >> 11) 2^-53."""
    k = np.arange(1, 6 * n + 1, dtype=np.uint64)
    with np.errstate(over="ignore"):
        z = np.uint64(seed) + k * np.uint64(0x9E3779B97F4A7C15)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        z = z ^ (z >> np.uint64(31))
    u = (z >> np.uint64(11)).astype(np.float64) * 2.0**-53
    u = u.reshape(n, 6)
    lo = np.array([-0.15, -0.15, 0.75, -15, -15, -20])
    hi = np.array([0.15, 0.15, 0.95, 15, 15, 20])
    return lo + (hi - lo) * u


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repetitions", type=int, default=5)
    parser.add_argument("--bench", default=os.path.join(ROOT, "build", "bin", "pkmopt_bench"))
    args = parser.parse_args()

    import pkmopt

    machine = pkmopt.load_machine(os.path.join(ROOT, "examples", "hexapod.yaml"))
    n = args.poses
    poses = bench_poses(n)
    wrench = [100, -200, -1500, 10, 20, 5]
    # Rounds alternate the three measurements, so that a drift of the machine's speed hits all
    # of them alike; each keeps its best round. "new arrays": fresh output arrays on every call
    # (the first touch of ~200 MB of new pages is part of the cost); "out=": the arrays of the
    # previous call reused, as the C++ benchmark's metrics are allocated once outside its timed
    # loop.
    name = f"BM_HexapodAnalyzeBatch/{n}/{args.threads}/0/0/real_time"
    fresh = reused = float("inf")
    cpp_rate = 0.0
    result = machine.analyze(poses, wrench=wrench, threads=args.threads)
    for _ in range(args.repetitions):
        start = time.perf_counter()
        result = machine.analyze(poses, wrench=wrench, threads=args.threads)
        fresh = min(fresh, time.perf_counter() - start)
        start = time.perf_counter()
        machine.analyze(poses, wrench=wrench, threads=args.threads, out=result)
        reused = min(reused, time.perf_counter() - start)
        out = subprocess.run(
            [args.bench, f"--benchmark_filter=^{name}$", "--benchmark_format=json"],
            check=True, capture_output=True, text=True).stdout
        runs = [r for r in json.loads(out)["benchmarks"] if r.get("run_type") == "iteration"]
        cpp_rate = max([cpp_rate] + [r["items_per_second"] for r in runs])
    fresh_rate, reused_rate = n / fresh, n / reused
    reachable = float(np.mean(result["reachable"]))

    print(f"poses {n}, threads {args.threads}, reachable {100 * reachable:.1f} %")
    print(f"python Machine.analyze, new arrays : {fresh_rate / 1e6:.3f} M poses/s "
          f"({fresh * 1e3:.1f} ms, best of {args.repetitions})")
    print(f"python Machine.analyze, out=       : {reused_rate / 1e6:.3f} M poses/s "
          f"({reused * 1e3:.1f} ms, best of {args.repetitions})")
    print(f"C++ {name.split('/real_time')[0]} : {cpp_rate / 1e6:.3f} M poses/s "
          f"(best of {args.repetitions} runs)")
    print(f"ratio python / C++ : {reused_rate / cpp_rate:.3f} with out=, "
          f"{fresh_rate / cpp_rate:.3f} with new arrays")
    return 0


if __name__ == "__main__":
    sys.exit(main())
