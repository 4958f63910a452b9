#!/usr/bin/env bash
# Installs every Debian package pkmopt needs to build, test and benchmark.
# Idempotent: packages already present are skipped; apt is only touched when
# something is missing. Run as root on Debian 12 (bookworm).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git python3
  libeigen3-dev
  coinor-libipopt-dev
  libnlopt-cxx-dev
  libceres-dev
  libcgal-dev
  libyaml-cpp-dev
  libcli11-dev
  nlohmann-json3-dev
  libfmt-dev
  libspdlog-dev
  libopenmpi-dev openmpi-bin
  libgtest-dev libgmock-dev
  libbenchmark-dev
  libpagmo-dev
  libpng-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-yaml
  clang libclang-rt-dev libomp-dev
  ccache
  chromium python3-websocket
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
