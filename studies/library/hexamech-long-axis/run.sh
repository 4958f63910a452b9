#!/usr/bin/env bash
# The hexamech-long-axis study, every step (README.md explains each): a hexapod alone against
# the same hexapod carried by a 2 m X axis (examples/hybrid_long_axis_hexapod.yaml). Usage:
#   studies/library/hexamech-long-axis/run.sh [OUT_DIR] [RESOLUTION_M] [HELIX_SAMPLES]
# defaults: results/hexamech-long-axis, 0.02 m, 721. PKMOPT selects the binary (default: pkmopt
# on the PATH, else the repository's build/bin/pkmopt). The reduced form the tests run: OUT 0.04 61.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
examples="$here/../../../examples"
pkmopt=${PKMOPT:-$(command -v pkmopt || echo "$here/../../../build/bin/pkmopt")}
out=${1:-results/hexamech-long-axis}
resolution=${2:-0.02}
samples=${3:-721}
hexapod="$examples/hexapod.yaml"
hybrid="$examples/hybrid_long_axis_hexapod.yaml"
mkdir -p "$out"

# 1. Structure: degrees of freedom, drives and the class by drive coupling (P0З6 against P1З6).
"$pkmopt" describe "$hexapod" >"$out/describe-hexapod.txt"
"$pkmopt" describe "$hybrid" >"$out/describe-hybrid.txt"

# 2. Workspaces at constant orientation and for a 15 deg tilt cone, hexapod and hybrid.
for machine in hexapod hybrid; do
  file=$hexapod
  [ "$machine" = hybrid ] && file=$hybrid
  "$pkmopt" workspace "$file" --resolution "$resolution" --slice-axis y --slice-at 0 \
    --out "$out/workspace-$machine-level" >/dev/null
  "$pkmopt" workspace "$file" --resolution "$resolution" --tilt 15 --orientation-step 15 \
    --out "$out/workspace-$machine-tilt15" >/dev/null
done
{
  echo "case,volume,x_min,x_max"
  for dir in "$out"/workspace-*; do
    name=${dir##*/workspace-}
    volume=$(sed -n 's/^  "volume": \(.*\),$/\1/p' "$dir/summary.json")
    box=$(awk '/"bounding_box": \{/ { inside = 1; next }
               inside && /^ *-?[0-9]/ { gsub(/[ ,]/, ""); v[++n] = $0; if (n == 6) exit }
               END { if (n == 6) printf "%.4f,%.4f", v[1], v[4]; else printf "," }' \
      "$dir/summary.json")
    echo "$name,$volume,$box"
  done
} >"$out/workspaces.csv"

# 3. Along the bed: x from -1.4 to 1.4 m at y = 0, z = 0.9 m under a milling-like load
#    (1000, 0, -2000) N; the X axis follows until its +-1 m travel ends.
{
  echo "x,y,z,rx,ry,rz"
  for i in $(seq -14 14); do
    awk -v i="$i" 'BEGIN { printf "%.2f,0,0.9,0,0,0\n", i / 10 }'
  done
} >"$out/line.csv"
"$pkmopt" analyze "$hybrid" --poses "$out/line.csv" --wrench 1000,0,-2000,0,0,0 \
  --out "$out/line-hybrid.csv" >/dev/null
"$pkmopt" analyze "$hexapod" --poses "$out/line.csv" --wrench 1000,0,-2000,0,0,0 \
  --out "$out/line-hexapod.csv" >/dev/null

# 4. The helical test path (5 deg harmonic angles) at x = 0.8 m, out of the bare hexapod's reach:
#    the X axis carries it there and the legs repeat the helix at the hexapod's home.
"$pkmopt" trajectory "$hybrid" --helix --helix-centre 0.8,0,0.88 --helix-angles 5,5,5 \
  --samples "$samples" --out "$out/helix-hybrid.csv" >"$out/helix-hybrid.txt"
"$pkmopt" trajectory "$hexapod" --helix --helix-centre 0,0,0.88 --helix-angles 5,5,5 \
  --samples "$samples" --out "$out/helix-hexapod.csv" >"$out/helix-hexapod.txt"
echo "hexamech-long-axis: results in $out"
