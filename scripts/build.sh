#!/usr/bin/env bash
# Installs the Debian packages (if missing), configures and builds pkmopt in ./build.
# Usage: scripts/build.sh [cmake --build extra arguments, e.g. --target pkmopt_cli]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPKMOPT_WERROR=ON >/dev/null
cmake --build build -j"$(nproc)" "$@"
