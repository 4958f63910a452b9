#!/usr/bin/env bash
# The main job: builds pkmopt and runs the default study, studies/library/hexapod-milling.yaml (a
# hexapod for milling steel: stiffness, workspace, singularity margin and leg force over a
# 300 x 300 x 200 mm box with 20 deg tilt), then writes its HTML report.
# Results: results/hexapod-milling/ (pareto.csv, pareto.json, evaluations.csv, summary.json,
# designs/<id>.yaml, report.html, pareto.png/svg, knee_slice.png/svg).
# The run keeps a journal: if it is killed, running this script again resumes it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target pkmopt_cli
out=results/hexapod-milling
mkdir -p results
./build/bin/pkmopt run studies/library/hexapod-milling.yaml --out "$out" --resume
./build/bin/pkmopt export "$out" --format html
echo "pkmopt: default study done -> $out/report.html (front: $out/pareto.csv)"
