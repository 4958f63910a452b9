#!/usr/bin/env bash
# Builds everything (tests, benchmarks, CLI) and runs the whole test suite with CTest, then the
# libFuzzer targets (clang, ASan + UBSan) for 30 s each (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 900
bash scripts/fuzz.sh 30
