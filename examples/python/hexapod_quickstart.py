#!/usr/bin/python3
"""pkmopt from Python: the sample hexapod's stiffness over a plane, and a design study's front.

1. Loads the docs/conventions.md hexapod (examples/hexapod.yaml) and maps its worst-direction
   TCP stiffness `stiffness_min` (N/m) over the plane z = 0.90 m, platform level, under a
   3 kN downward cutting force: 40,401 poses in one `analyze` call.
2. Runs the `hexapod-quick` study (studies/library/hexapod-quick.yaml: stiffness over a
   300 x 300 x 200 mm milling box with 20 deg tilt against machine size) and plots its Pareto
   front with the knee design marked.

Run from the repository root after scripts/build.sh:
    PYTHONPATH=build/python /usr/bin/python3 examples/python/hexapod_quickstart.py
Pictures go to --out (default results/python-quickstart): stiffness_map.png and front.png
(with Debian's python3-matplotlib; without it the numbers are printed only).
"""

import argparse
import os
import sys

import numpy as np

import pkmopt

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def pyplot():
    """matplotlib.pyplot on the file-only Agg backend, or None without Debian's python3-matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    return plt


def stiffness_map(out):
    machine = pkmopt.load_machine(os.path.join(ROOT, "examples", "hexapod.yaml"))
    print(machine.describe(), end="")
    xs = np.linspace(-0.20, 0.20, 201)
    ys = np.linspace(-0.20, 0.20, 201)
    X, Y = np.meshgrid(xs, ys)
    poses = np.column_stack([X.ravel(), Y.ravel(), np.full(X.size, 0.90)])
    r = machine.analyze(poses, wrench=[0, 0, -3000, 0, 0, 0])
    k = np.where(r["reachable"], r["stiffness_min"], np.nan).reshape(X.shape)
    reachable = r["reachable"].mean()
    print(f"plane z = 0.90 m: {100 * reachable:.1f} % of {len(poses)} poses reachable, "
          f"stiffness_min {np.nanmin(k) / 1e6:.2f} .. {np.nanmax(k) / 1e6:.2f} N/um, "
          f"largest leg force {np.max(np.abs(r['tau'][r['reachable']])):.0f} N")
    plt = pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6, 5))
    image = ax.pcolormesh(X * 1e3, Y * 1e3, k / 1e6, shading="auto", cmap="viridis")
    fig.colorbar(image, ax=ax, label="stiffness_min [N/um]")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_aspect("equal")
    ax.set_title("Sample hexapod, z = 0.90 m, platform level")
    fig.savefig(os.path.join(out, "stiffness_map.png"), dpi=120, bbox_inches="tight")
    plt.close(fig)


def study_front(out):
    front = pkmopt.run_study(os.path.join(ROOT, "studies", "library", "hexapod-quick.yaml"),
                             out=os.path.join(out, "hexapod-quick"), force=True)
    run = front["run"]
    print(f"{run['name']}: {run['designs']} designs from {run['evaluations']} evaluations "
          f"in {run['wall_seconds']:.2f} s, status {run['status']}, knee {front['knee']}")
    f = front["objectives"]
    info = front["objective_info"]
    knee = front["ids"].index(front["knee"])
    print(f"knee: {info[0]['name']} = {f[knee, 0]:.4g} {info[0]['unit']}, "
          f"{info[1]['name']} = {f[knee, 1]:.4g} {info[1]['unit']}")
    plt = pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(f[:, 1], f[:, 0] / 1e6, "o", label="Pareto front")
    ax.plot(f[knee, 1], f[knee, 0] / 1e6, "r*", markersize=14, label=f"knee {front['knee']}")
    ax.set_xlabel(f"{info[1]['name']} [{info[1]['unit']}] (minimised)")
    ax.set_ylabel(f"{info[0]['name']} [N/um] (maximised)")
    ax.legend()
    ax.set_title(front["study"])
    fig.savefig(os.path.join(out, "front.png"), dpi=120, bbox_inches="tight")
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join("results", "python-quickstart"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    stiffness_map(args.out)
    study_front(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
