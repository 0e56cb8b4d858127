#!/usr/bin/env bash
# Set-up shared by the README's two commands: installs the Debian packages that are missing
# (idempotent: does nothing when all are present), then configures and builds.
#
#   scripts/setup.sh [--test-tools] [BUILD_DIR] [extra cmake arguments...]
#
# --test-tools (the README's test command, scripts/test.sh): also the packages only tests use,
# the Cortex-M cross toolchain and QEMU that run the exported C (docs/deploy.md); the demo
# command does not download them.
#
# Environment: SYSID_JOBS (parallel build jobs, default: number of cores).
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  g++ cmake make ccache                # toolchain
  libeigen3-dev libceres-dev           # linear algebra, nonlinear least squares
  libsundials-dev libnlopt-cxx-dev     # CVODE integrator, derivative-free optimisation
  catch2 libcli11-dev nlohmann-json3-dev libfmt-dev   # tests, CLI, JSON, formatting
  gnuplot-nox                          # plots in reports
  clang libclang-rt-dev                # libFuzzer + sanitizers for scripts/fuzz.sh (CI's fuzz step)
  libnanoflann-dev                     # k-d tree: the irreducible-error estimate (nn module)
  libboost-dev                         # Boost.Math (test cross-check of the smoothing derivative)
  libmatio-dev libhdf5-dev zlib1g-dev  # MATLAB MAT (v4, v5, v7.3) and HDF5 recordings
  libssl-dev                           # libcrypto: SHA-256 of a model in an export's provenance
  pkgconf                              # finds matio and the serial HDF5 (cmake/SysidDependencies.cmake)
  python3-numpy python3-scipy          # the Python peers that benchmarks run side by side
  pybind11-dev python3-pybind11        # the Python package sysid (python/)
  python3-pandas python3-dask python3-distributed python3-pytest python3-matplotlib
  python3-hypothesis                   # property-based tests of the Python bindings
)

# Only the tests need these: the exported C on an emulated Cortex-M4F.
TEST_PACKAGES=(gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm)
if [ "${1:-}" = --test-tools ]; then
  PACKAGES+=("${TEST_PACKAGES[@]}")
  shift
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing missing Debian packages: ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >&2
fi

BUILD_DIR="${1:-build}"
shift || true
# ccache keys on paths relative to this clone: another clone or build folder on the machine
# reuses its objects (a user's own CCACHE_BASEDIR wins).
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
jobs="${SYSID_JOBS:-$(nproc)}"
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@" >&2
cmake --build "$BUILD_DIR" -j "$jobs" >&2

# The sysid program (into /usr/local/bin, so the docs' bare `sysid` works) and the Python
# package (python/, built when pybind11 and NumPy are present; into Debian's python3
# site-packages, so `import sysid` works with no further step).
# A sanitizer build installs nothing (its program needs the sanitizers' run-time options).
components=()
grep -q '^SYSID_SANITIZE:BOOL=ON' "$BUILD_DIR/CMakeCache.txt" 2>/dev/null || components+=(cli)
if grep -q '^SYSID_PYTHON:BOOL=ON' "$BUILD_DIR/CMakeCache.txt" 2>/dev/null; then
  components+=(python)
fi
for component in ${components[@]+"${components[@]}"}; do
  if [ "$(id -u)" -eq 0 ]; then
    cmake --install "$BUILD_DIR" --component "$component" >&2
  elif sudo -n true 2>/dev/null; then
    sudo cmake --install "$BUILD_DIR" --component "$component" >&2
  else
    echo "setup: $component not installed (no root): the program is $BUILD_DIR/apps/sysid, the" \
      "Python package $BUILD_DIR/python (PYTHONPATH=$BUILD_DIR/python);" \
      "'sudo cmake --install $BUILD_DIR --component $component' installs it" >&2
  fi
done
