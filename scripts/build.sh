#!/usr/bin/env bash
# Installs the Debian packages (if missing), configures and builds pkmopt in ./build.
# Usage: scripts/build.sh [cmake --build extra arguments, e.g. --target pkmopt_cli]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
launcher=()
# ccache, when installed, makes rebuilds fast; CCACHE_BASEDIR makes paths inside the clone
# relative, so that a clone in another folder (CI's) reuses the cache too.
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPKMOPT_WERROR=ON "${launcher[@]}" >/dev/null
cmake --build build -j"$(nproc)" "$@"
