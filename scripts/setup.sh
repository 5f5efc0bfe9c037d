#!/usr/bin/env bash
# Sets conform up on a fresh Debian machine: installs the Debian packages it needs, configures and builds.
# Usage: scripts/setup.sh [--target T] [build-dir] [extra cmake args...]   (default build dir: build)
# --target T builds only T and what it needs (the README's first command builds only the `conform` program);
# without it everything is built, tests included. Idempotent: run it again after a pull to rebuild.
set -euo pipefail
cd "$(dirname "$0")/.."

target=()
if [ "${1:-}" = "--target" ]; then
  target=(--target "$2")
  shift 2
fi
build_dir=${1:-build}
shift || true

packages=(cmake ninja-build g++ pkg-config libeigen3-dev libpcl-dev libceres-dev libopencv-dev
          libgtest-dev libnanoflann-dev libcli11-dev nlohmann-json3-dev
          pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed  # python/ (docs/python.md)
          libjs-three  # three.js, compiled into the HTML reports (report/, docs/report.md)
          chromium  # the reports' browser test renders them headless (tests/apps/report_browser_test.cpp)
          # OpenCASCADE for STEP/IGES references (the cad plugin, LGPL-2.1 with exception, linked dynamically)
          libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}" >&2
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B "$build_dir" -G Ninja "$@"
cmake --build "$build_dir" -j "$(nproc)" "${target[@]}"
