#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer) in
# ./build-fuzz and runs each for a bounded time from its seed corpus (CTest label `fuzz`).
# Usage: scripts/fuzz.sh [SECONDS per target, default 30]
# A finding (crash, sanitizer report, uncaught non-input exception, timeout, out of memory) fails
# the run; its input is in build-fuzz/fuzz/findings/<target>/ and replays with
#   build-fuzz/fuzz/fuzz_<target> build-fuzz/fuzz/findings/<target>/<file>
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
bash scripts/install-deps.sh
launcher=()
# ccache, when installed, makes rebuilds fast; CCACHE_BASEDIR makes paths inside the clone
# relative, so that a clone in another folder (CI's) reuses the cache too.
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD"
fi
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DPKMOPT_FUZZ=ON -DPKMOPT_SANITIZE=address,undefined -DPKMOPT_FUZZ_SECONDS="$seconds" \
  -DPKMOPT_BUILD_TESTS=OFF -DPKMOPT_BUILD_BENCH=OFF -DPKMOPT_BUILD_PYTHON=OFF \
  "${launcher[@]}" >/dev/null
targets=(fuzz_machine_file fuzz_study_file fuzz_csv fuzz_pareto_json fuzz_calibration_file)
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}"
ctest --test-dir build-fuzz -L fuzz --output-on-failure -j"$(nproc)"
