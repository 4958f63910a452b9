#!/usr/bin/env bash
# The hexapod-vs-5axis study, every step (README.md explains each): the hexapod the default milling
# study proposes (hexapod-knee.yaml) against a 5-axis machining centre with a tilting table,
# coordinate code 641236 (examples/serial_641236.yaml), on one milling task. Usage:
#   studies/hexapod-vs-5axis/run.sh [OUT_DIR] [RESOLUTION_M] [HELIX_SAMPLES]
# defaults: results/hexapod-vs-5axis, 0.02 m, 721. PKMOPT selects the binary (default: pkmopt on
# the PATH, else the repository's build/bin/pkmopt). The reduced form the tests run: OUT 0.05 61.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
examples="$here/../../examples"
pkmopt=${PKMOPT:-$(command -v pkmopt || echo "$here/../../build/bin/pkmopt")}
out=${1:-results/hexapod-vs-5axis}
resolution=${2:-0.02}
samples=${3:-721}
hexapod="$here/hexapod-knee.yaml"
serial="$examples/serial_641236.yaml"
# The task: a 300 x 300 x 200 mm block, each machine in its own frame (z up, the tool coming
# from above): where the default study put it for this hexapod, centred at (0, 0, 1.0645) m
# above its base, and on the 5-axis table with its centre 0.1 m above the point where the C axis
# meets the A axis.
centre_hexapod="0,0,1.0645"
centre_serial="0,0,0.1"
# The milling load of studies/library/hexapod-milling.yaml (63 mm face mill in C45, Kienzle
# specific cutting force, design factor 1.8), at the TCP in base axes (N, N*m).
wrench="-2454.45,981.782,1227.23,0,0,-77.3153"
mkdir -p "$out"

# 1. Structure: degrees of freedom, drives and the class by drive coupling (P0З6 against P5З0).
"$pkmopt" describe "$hexapod" >"$out/describe-hexapod.txt"
"$pkmopt" describe "$serial" >"$out/describe-5axis.txt"

# 2. The task poses: the block's 8 corners and its centre, each with the tool vertical and tilted
#    by 20 deg towards 8 directions (81 poses; R = Rz Ry Rx with rz = 0: the tool axis
#    (sin t cos p, sin t sin p, cos t) has rx = -asin(a_y), ry = atan2(a_x, a_z)).
task_poses() {
  awk -v c="$1" 'BEGIN {
    split(c, o, ",");
    print "x,y,z,rx,ry,rz";
    pi = atan2(0, -1);
    for (k = 0; k <= 8; ++k) {
      if (k < 8) { px = (k % 2 ? 0.15 : -0.15); py = (int(k / 2) % 2 ? 0.15 : -0.15);
                   pz = (k >= 4 ? 0.1 : -0.1) } else { px = 0; py = 0; pz = 0 }
      for (d = -1; d < 8; ++d) {
        t = (d < 0 ? 0 : 20 * pi / 180); p = d * pi / 4;
        ax = sin(t) * cos(p); ay = sin(t) * sin(p); az = cos(t);
        rx = -atan2(ay, sqrt(1 - ay * ay)) * 180 / pi; ry = atan2(ax, az) * 180 / pi;
        printf "%.4f,%.4f,%.4f,%.10g,%.10g,0\n", o[1] + px, o[2] + py, o[3] + pz, rx, ry;
      }
    }
  }'
}
task_poses "$centre_hexapod" >"$out/task-hexapod.csv"
task_poses "$centre_serial" >"$out/task-5axis.csv"

# 3. Stiffness and deflection under the milling load at every task pose.
"$pkmopt" analyze "$hexapod" --poses "$out/task-hexapod.csv" --wrench "$wrench" \
  --out "$out/analyze-hexapod.csv" >/dev/null
"$pkmopt" analyze "$serial" --poses "$out/task-5axis.csv" --wrench "$wrench" \
  --out "$out/analyze-5axis.csv" >/dev/null

# 4. Workspaces: the tool vertical, and every orientation of the 20 deg tilt cone.
for machine in hexapod 5axis; do
  file=$hexapod
  [ "$machine" = 5axis ] && file=$serial
  "$pkmopt" workspace "$file" --resolution "$resolution" \
    --out "$out/workspace-$machine-level" >/dev/null
  "$pkmopt" workspace "$file" --resolution "$resolution" --tilt 20 --orientation-step 10 \
    --out "$out/workspace-$machine-tilt20" >/dev/null
done

# 5. The helical test path with the tool on a 20 deg cone around the vertical, and one whose tool
#    axis passes 0.1 deg from the vertical (the tilting table's singular pose).
"$pkmopt" trajectory "$hexapod" --helix --helix-centre 0,0,1.0445 --helix-angles 20,20,0 \
  --samples "$samples" --out "$out/helix-hexapod.csv" >"$out/helix-hexapod.txt"
"$pkmopt" trajectory "$serial" --helix --helix-centre 0,0,0.08 --helix-angles 20,20,0 \
  --samples "$samples" --out "$out/helix-5axis.csv" >"$out/helix-5axis.txt"
"$pkmopt" trajectory "$hexapod" --helix --helix-centre 0,0,1.0445 --helix-angles 3,3,0 \
  --helix-orientation 2.9,0,0 --samples "$samples" --out "$out/near-vertical-hexapod.csv" \
  >"$out/near-vertical-hexapod.txt"
"$pkmopt" trajectory "$serial" --helix --helix-centre 0,0,0.08 --helix-angles 3,3,0 \
  --helix-orientation 2.9,0,0 --samples "$samples" --out "$out/near-vertical-5axis.csv" \
  >"$out/near-vertical-5axis.txt"

# 6. One table: per machine, the task poses reached, the weakest stiffness and largest
#    deflection over them, the smallest singularity margin, the workspace volumes, and the
#    fastest drive on each helix.
summarise_task() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    { n++; r += $col["reachable"];
      if (n == 1 || $col["stiffness_min"] < k) k = $col["stiffness_min"];
      if ($col["tcp_deflection"] > d) d = $col["tcp_deflection"];
      if (n == 1 || $col["singularity_margin"] < s) s = $col["singularity_margin"] }
    END { printf "%d/%d,%.4g,%.4g,%.4g", r, n, k / 1e6, d * 1e6, s }' "$1"
}
volume() { sed -n 's/^  "volume": \(.*\),$/\1/p' "$1/summary.json"; }
fastest() {
  # The largest max |q_dot| per unit kind in a trajectory summary: "mm/s;deg/s".
  awk '/^  q_[0-9]+:/ { for (i = 1; i <= NF; ++i) if ($i == "|q_dot|") { v = $(i + 1); u = $(i + 2);
         if (u == "mm/s" && v > mm) mm = v; if (u == "deg/s" && v > dg) dg = v } }
       END { printf "%g;%g", mm, dg }' "$1"
}
{
  echo "machine,task_reached,stiffness_min_N_per_um,tcp_deflection_max_um,singularity_margin_min,workspace_level_m3,workspace_tilt20_m3,helix_fastest_mm_s_deg_s,near_vertical_fastest_mm_s_deg_s"
  for machine in hexapod 5axis; do
    echo "$machine,$(summarise_task "$out/analyze-$machine.csv"),$(volume "$out/workspace-$machine-level"),$(volume "$out/workspace-$machine-tilt20"),$(fastest "$out/helix-$machine.txt"),$(fastest "$out/near-vertical-$machine.txt")"
  done
} >"$out/comparison.csv"
cat "$out/comparison.csv"
echo "hexapod-vs-5axis: results in $out"
