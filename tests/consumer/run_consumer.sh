#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, builds tests/consumer against it with
# find_package(pkmopt) and runs it on the sample hexapod and a small study; imports the
# installed Python package (when it was built).
# The consumer is built with the compiler of the build tree (a sanitizer build's libraries need
# that compiler's sanitizer runtime).
# Usage: tests/consumer/run_consumer.sh SOURCE_DIR BUILD_DIR SCRATCH_DIR [CXX_COMPILER]
set -euo pipefail
src=$1 build=$2 scratch=$3 cxx=${4:-c++}
rm -rf "$scratch"
mkdir -p "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
# The public surface: no detail header or kernel is installed, and no installed header needs one.
include="$scratch/prefix/include/pkmopt"
private=$(find "$include" -name '*_detail.hpp' -o -name '*.inc')
if [[ -n $private ]]; then echo "installed private headers: $private" >&2; exit 1; fi
if grep -rlE '#include "[a-z_/]+(_detail\.hpp|\.inc)"' "$include"; then
  echo "installed headers include private ones (above)" >&2
  exit 1
fi
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$src/tests/consumer" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_CXX_COMPILER="$cxx" "${launcher[@]}" >/dev/null
cmake --build "$scratch/build" -j2 >/dev/null
sed 's/population: 60, generations: 80/population: 40, generations: 5/' \
  "$src/studies/library/hexapod-quick.yaml" >"$scratch/study.yaml"
"$scratch/build/consumer" "$src/examples/hexapod.yaml" "$scratch/study.yaml" "$scratch/out"
test -s "$scratch/out/pareto.csv"
# The Python package is installed beside the libraries (PKMOPT_PYTHON_INSTALL_DIR, relative to
# the prefix) and imports from there alone (no build tree on the path).
site=$(find "$scratch/prefix" -path '*/dist-packages/pkmopt/__init__.py' -printf '%h\n' | head -1)
if [[ -n $site ]]; then
  (cd "$scratch" && PYTHONPATH="$(dirname "$site")" /usr/bin/python3 -c \
    "import pkmopt, sys; assert pkmopt.__file__.startswith('$scratch'), pkmopt.__file__; \
m = pkmopt.load_machine(sys.argv[1]); print('python:', m.model, pkmopt.__version__)" \
    "$src/examples/hexapod.yaml")
fi
echo "consumer_project: built against $scratch/prefix and ran"
