#!/usr/bin/env bash
# Installs the Debian packages (if missing), configures and builds pkmopt in ./build.
# Usage: scripts/build.sh [cmake --build extra arguments, e.g. --target pkmopt_cli]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
launcher=()
# ccache, when installed, makes rebuilds after small changes fast (not required).
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPKMOPT_WERROR=ON "${launcher[@]}" >/dev/null
cmake --build build -j"$(nproc)" "$@"
