#!/usr/bin/env bash
# Sets conform up on a fresh Debian machine: installs the Debian packages it needs, configures and builds.
# Usage: scripts/setup.sh [--target T] [build-dir] [extra cmake args...]   (default build dir: build)
# --target T builds only T and what it needs, with the packages the program needs and the tests and the Python package
# configured out unless the extra cmake args turn them on (the README's first command builds only the `conform`
# program); without it everything is built, tests and the Python package included. Idempotent: run it again after a
# pull to rebuild.
set -euo pipefail
cd "$(dirname "$0")/.."

target=()
if [ "${1:-}" = "--target" ]; then
  target=(--target "$2")
  shift 2
fi
build_dir=${1:-build}
shift || true

# What the `conform` program needs (the README's first command installs only these)...
packages=(cmake ninja-build g++ pkg-config libeigen3-dev libpcl-dev libceres-dev libopencv-dev
          libnanoflann-dev libcli11-dev nlohmann-json3-dev
          libjs-three  # three.js, compiled into the HTML reports (report/, docs/report.md)
          # OpenCASCADE for STEP/IGES references (the cad plugin, LGPL-2.1 with exception, linked dynamically)
          libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev)
# ...and what the whole build adds: the test suite, the Python package, the reports' browser test.
full_packages=(libgtest-dev
               pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed  # python/ (docs/python.md)
               chromium)  # the reports' browser test renders them headless (tests/apps/report_browser_test.cpp)
# A target build leaves the tests and the Python package out of the configuration (so their packages are not
# needed); a full build turns them on again (the options are cached, so both are always stated).
if ((${#target[@]})); then
  configure=(-DCONFORM_BUILD_TESTS=OFF -DCONFORM_BUILD_PYTHON=OFF)
else
  packages+=("${full_packages[@]}")
  configure=(-DCONFORM_BUILD_TESTS=ON -DCONFORM_BUILD_PYTHON=ON)
fi
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

# Unity builds (CMake batches of 8 sources per compile) parse the heavy PCL, Eigen and Ceres headers once per batch
# instead of once per source (the README gives the first command's measured time). Pass
# -DCMAKE_UNITY_BUILD=OFF for a development build where one edited file should recompile alone.
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_UNITY_BUILD=ON "${configure[@]}" "$@"
cmake --build "$build_dir" -j "$(nproc)" "${target[@]}"
