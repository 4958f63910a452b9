#!/bin/sh
# Runs every step of the 16K20F3 lathe-conversion study into one folder (README.md explains each).
#   studies/library/lathe-16k20f3/run.sh [OUT]            # OUT defaults to lathe-16k20f3-out
# Environment: PKMOPT = the pkmopt binary (default: pkmopt on the PATH, else the repository's
#              build/bin/pkmopt);
#              QUICK=1  = the reduced form CI runs (coarser workspace, small NSGA-II run).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-lathe-16k20f3-out}
PKMOPT=${PKMOPT:-$(command -v pkmopt || echo "$HERE/../../../build/bin/pkmopt")}
QUICK=${QUICK:-0}
mkdir -p "$OUT"
# The conversion study's turning load at the optimal approach angle arccot 2 (problems/design/cutting_load.hpp):
# 1186.63 N along x, 6633.45 N along z on the tool, in the lathe frame.
WRENCH=1186.63,0,6633.45,0,0,0

# 1. The conversion study's strut-length formula, L = sqrt(X_K^2 + (Y_D + D/2 + Y_xx - Y_I)^2 + (Z_D + D/2 + Z_xx - Z_I)^2)
#    with its own definitions (README, step 1): Y_D, Z_D = -0.10, 0.175 (the part axis from the hinge
#    line), Y_I, Z_I = -(0.16 (2, 1)/sqrt(5) + (0.15, -0.10)) (the tool tip from the strut joint),
#    X_K = L cos 70 deg (the hinge limit), so L = sqrt(dy^2 + dz^2) / sin 70 deg; the 400 mm cross
#    travel in place of D/2 + Y_xx in y.
awk 'BEGIN { pi = atan2(0, -1); s = sin(70 * pi / 180);
             yi = -(0.16 * 2 / sqrt(5) + 0.15); zi = -(0.16 / sqrt(5) - 0.10);
             dz = 0.175 + 0.16 + 0.02 - zi;
             printf "seeds_strut_length_m,%.6f\n", sqrt((-0.10 + 0.16 + 0.02 - yi)^2 + dz^2) / s;
             printf "seeds_strut_length_400mm_m,%.6f\n", sqrt((-0.10 + 0.40 - yi)^2 + dz^2) / s }' \
  > "$OUT/strut_length.csv"

# 2. The minimal strut length that reaches the whole task (task.csv: tool tip over x -0.5..0.5,
#    y 0..0.4, z 0..0.18, 75 poses): bisection on strut_length with `pkmopt analyze`.
reaches() {  # $1 = strut length (m); exit 0 when every task pose is reachable
  sed "s/^strut_length: .*/strut_length: $1/" "$HERE/lathe.yaml" > "$OUT/bisect.yaml"
  "$PKMOPT" analyze "$OUT/bisect.yaml" --poses "$HERE/task.csv" --out "$OUT/bisect.csv"
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "reachable") c = i; next }
           $c != 1 { bad = 1 } END { exit bad }' "$OUT/bisect.csv"
}
LOW=0.40
HIGH=0.80
reaches "$HIGH" || { echo "run.sh: the task is not reachable with $HIGH m struts" >&2; exit 1; }
while [ "$(awk -v l="$LOW" -v h="$HIGH" 'BEGIN { print (h - l > 1e-4) }')" = 1 ]; do
  MID=$(awk -v l="$LOW" -v h="$HIGH" 'BEGIN { printf "%.6f", (l + h) / 2 }')
  if reaches "$MID"; then HIGH=$MID; else LOW=$MID; fi
done
echo "minimal_strut_length_m,$HIGH" >> "$OUT/strut_length.csv"
rm -f "$OUT/bisect.yaml" "$OUT/bisect.csv"

# 3. Leg forces under the turning load over the task (design lathe.yaml, struts 0.73 m);
#    tau_1, tau_2 = carriage drives, tau_3, tau_4 = the electro-cylinders.
"$PKMOPT" analyze "$HERE/lathe.yaml" --poses "$HERE/task.csv" --wrench "$WRENCH" \
  --out "$OUT/forces.csv"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  { for (k = 1; k <= 4; ++k) { t = $col["tau_" k]; if (t < 0) t = -t; if (t > f[k]) f[k] = t }
    for (k = 3; k <= 4; ++k) { q = $col["q_" k]; if (!(k in lo) || q < lo[k]) lo[k] = q; if (!(k in hi) || q > hi[k]) hi[k] = q }
    if (!("k" in m) || $col["stiffness_min"] < m["k"]) m["k"] = $col["stiffness_min"] }
  END { printf "carriage_force_max_N,%.1f\ncylinder_force_max_N,%.1f\ncylinder_length_range_m,%.4f,%.4f\nstiffness_min_N_per_m,%.6g\n",
               (f[1] > f[2] ? f[1] : f[2]), (f[3] > f[4] ? f[3] : f[4]),
               (lo[3] < lo[4] ? lo[3] : lo[4]), (hi[3] > hi[4] ? hi[3] : hi[4]), m["k"] }' \
  "$OUT/forces.csv" > "$OUT/forces_summary.csv"

# 4. Workspaces (constant orientation, approach angle arccot 2): the turret centre and the tool tip.
RES=0.02
[ "$QUICK" = 1 ] && RES=0.05
"$PKMOPT" workspace "$HERE/turret-centre.yaml" --resolution "$RES" --slice-axis x --slice-at 0 \
  --out "$OUT/workspace-turret-centre"
"$PKMOPT" workspace "$HERE/lathe.yaml" --resolution "$RES" --slice-axis x --slice-at 0 \
  --out "$OUT/workspace-tool-tip"

# 5. The Pareto front of strut length against stiffness.
if [ "$QUICK" = 1 ]; then
  # The reduced run in OUT: the catalog by its path from the study's own folder.
  sed -e 's/population: 80, generations: 100/population: 12, generations: 3/' \
    -e "s|catalog: \.\./catalogs/|catalog: $HERE/../catalogs/|" "$HERE/pareto.yaml" \
    > "$OUT/pareto-quick.yaml"
  "$PKMOPT" run "$OUT/pareto-quick.yaml" --out "$OUT/pareto" --force --no-progress
else
  "$PKMOPT" run "$HERE/pareto.yaml" --out "$OUT/pareto" --force --no-progress
fi
echo "run.sh: done -> $OUT"
