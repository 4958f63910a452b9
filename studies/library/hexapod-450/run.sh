#!/usr/bin/env bash
# The hexapod-450 study, every step (README.md explains each). Usage:
#   studies/library/hexapod-450/run.sh [OUT_DIR] [RESOLUTION_M] [HELIX_SAMPLES]
# defaults: results/hexapod-450, 0.01 m, 721. PKMOPT selects the binary (default: pkmopt on the PATH, else
# the repository's build/bin/pkmopt).
# The reduced form the tests run: OUT 0.02 61.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
pkmopt=${PKMOPT:-$(command -v pkmopt || echo "$here/../../../build/bin/pkmopt")}
out=${1:-results/hexapod-450}
resolution=${2:-0.01}
samples=${3:-721}
machine="$here/hexapod-450.yaml"
mkdir -p "$out"

# Joint-limit variants of the same machine, to see what shrinks the tilted workspace.
sed 's/platform_max_angle_deg: 60/platform_max_angle_deg: 45/' "$machine" >"$out/joints-45-45.yaml"
sed 's/base_max_angle_deg: 45, platform_max_angle_deg: 60/base_max_angle_deg: 89, platform_max_angle_deg: 89/' \
  "$machine" >"$out/joints-89-89.yaml"

# 1. Workspaces: level (R = I) and at a constant 40 deg tilt about y and about x, with the
#    study's joints, with 45 deg joints everywhere, and with joints free up to 89 deg (about the
#    leg lengths alone; 89 rather than unlimited keeps out the mirror image below the base).
#    Slices: the x-z plane through y = 0 (where the tilt about y shifts the workspace).
run_workspace() {  # name machine orientation
  "$pkmopt" workspace "$2" --orientation "$3" --resolution "$resolution" \
    --slice-axis y --slice-at 0 --out "$out/workspace-$1"
}
run_workspace level "$machine" 0,0,0
run_workspace tilt-y40 "$machine" 0,40,0
run_workspace tilt-x40 "$machine" 40,0,0
run_workspace joints-45-45-level "$out/joints-45-45.yaml" 0,0,0
run_workspace joints-45-45-tilt-y40 "$out/joints-45-45.yaml" 0,40,0
run_workspace joints-89-89-level "$out/joints-89-89.yaml" 0,0,0
run_workspace joints-89-89-tilt-y40 "$out/joints-89-89.yaml" 0,40,0

# Volume, extents (the box of the boundary mesh, whose vertices lie on the true boundary) and
# centroid (the mean of the inside grid nodes) of every workspace.
{
  echo "case,volume,x_min,x_max,y_min,y_max,z_min,z_max,centroid_x,centroid_y,centroid_z"
  for dir in "$out"/workspace-*; do
    name=${dir##*/workspace-}
    volume=$(sed -n 's/^  "volume": \(.*\),$/\1/p' "$dir/summary.json")
    box=$(awk '/"bounding_box": \{/ { inside = 1; next }
               inside && /^ *-?[0-9]/ { gsub(/[ ,]/, ""); v[++n] = $0; if (n == 6) exit }
               END { if (n == 6) printf "%.4f,%.4f,%.4f,%.4f,%.4f,%.4f", v[1], v[4], v[2], v[5],
                                        v[3], v[6]; else printf ",,,,," }' "$dir/summary.json")
    centroid=$(awk -F, 'NR > 1 { n++; for (k = 1; k <= 3; k++) s[k] += $k }
                        END { if (n > 0) printf "%.4f,%.4f,%.4f", s[1]/n, s[2]/n, s[3]/n;
                              else printf ",," }' "$dir/points.csv")
    echo "$name,$volume,$box,$centroid"
  done
} >"$out/workspaces.csv"

# 2. The helical test path at level: leg lengths, rates (from J and from the IK), J, singular poses.
"$pkmopt" trajectory "$machine" --helix --helix-centre 0,0,0.70 --helix-angles 5,5,5 \
  --samples "$samples" --jacobian --out "$out/helix-level.csv" \
  --singular-out "$out/helix-level-singular.csv" | tee "$out/helix-level.txt"

# 3. The same helix tilted 40 deg about y, centred on the tilted workspace's centroid.
"$pkmopt" trajectory "$machine" --helix --helix-centre 0.18,0,0.70 --helix-angles 5,5,5 \
  --helix-orientation 0,40,0 --samples "$samples" --jacobian --out "$out/helix-tilt-y40.csv" \
  --singular-out "$out/helix-tilt-y40-singular.csv" | tee "$out/helix-tilt-y40.txt"

column -s, -t <"$out/workspaces.csv" 2>/dev/null || cat "$out/workspaces.csv"
