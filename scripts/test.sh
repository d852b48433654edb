#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds and runs the whole test suite with CTest.
# Needs ../shared/data next to the checkout. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh -DSHELLSPACE_BUILD_BENCHMARKS=ON
cd build
ctest --output-on-failure -j"$(nproc)"
