#!/usr/bin/env bash
# Python package benchmarks (bench/bench_python.py): binding overhead vs C++, batch threads and
# Dask workers, NumPy peer. Needs a build with SYSID_PYTHON=ON and bench_dominance.
#   bench/run_python.sh [BUILD_DIR] [N] [ROWS]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
N="${2:-1000}"
ROWS="${3:-5000}"
uptime
PYTHONPATH="$BUILD/python" /usr/bin/python3 bench/bench_python.py --build "$BUILD" -n "$N" \
  --rows "$ROWS"
uptime
