#!/usr/bin/env bash
# Builds pkmopt with AddressSanitizer + UndefinedBehaviorSanitizer (clang) in ./build-asan and runs
# the test suite under them: every memory error, leak or undefined behaviour stops the program
# that has it, so the test fails. Clang builds the baseline kernel of the batched hexapod analysis
# (not its AVX2 variant, which is GCC-only). The Python package is left out (its tests would need the
# sanitizer runtime preloaded into the interpreter) and so are the benchmarks.
# On two cores: about 16 minutes to build from an empty ccache (2 with a warm one), then about 21
# minutes for the whole suite (the shipped_fronts and readme_commands tests take 10-13 minutes
# each under the sanitizers).
# Usage: scripts/sanitize.sh [ctest arguments, e.g. -R 'Cli|ErrorContract' for the CLI tests]
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
# -O1, as the sanitizers' authors advise: fast enough to run, much faster to build than -O2.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DCMAKE_CXX_COMPILER=clang++ \
  -DPKMOPT_SANITIZE=address,undefined \
  -DPKMOPT_BUILD_BENCH=OFF -DPKMOPT_BUILD_PYTHON=OFF "${launcher[@]}" >/dev/null
cmake --build build-asan -j"$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" --timeout 1800 "$@"
