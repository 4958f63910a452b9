#!/usr/bin/env bash
# Builds everything (tests, benchmarks, CLI) and runs the whole test suite with CTest: GoogleTest,
# pytest, the command-line and study checks, and a replay of every fuzz seed and regression input
# through the file readers. Fuzzing itself (scripts/fuzz.sh) and the sanitizer suite
# (scripts/sanitize.sh) take much longer and are run on their own.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 900
