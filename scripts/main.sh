#!/usr/bin/env bash
# The main job: builds pkmopt and analyses the sample hexapod (examples/hexapod.yaml) over a
# grid of TCP poses, writing results/analyze.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target pkmopt_cli
mkdir -p results
# Pose grid: x, y in [-0.15, 0.15] m, z in [0.75, 0.95] m, tilts of 0 and 15 degrees about x.
awk 'BEGIN {
  print "x,y,z,rx,ry,rz";
  for (i = 0; i < 7; i++) for (j = 0; j < 7; j++) for (k = 0; k < 5; k++) for (t = 0; t < 2; t++)
    printf "%.3f,%.3f,%.3f,%d,0,0\n", -0.15 + 0.05 * i, -0.15 + 0.05 * j, 0.75 + 0.05 * k, 15 * t;
}' > results/poses.csv
./build/bin/pkmopt analyze examples/hexapod.yaml --poses results/poses.csv \
  --wrench 0,0,-2000,0,0,0 --out results/analyze.csv
rows=$(($(wc -l < results/analyze.csv) - 1))
reachable=$(awk -F, 'NR > 1 && $7 == 1 { n++ } END { print n + 0 }' results/analyze.csv)
echo "pkmopt: analysed ${rows} poses of examples/hexapod.yaml (${reachable} reachable) -> results/analyze.csv"
