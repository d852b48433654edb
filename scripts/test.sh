#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds and runs the whole test suite with CTest,
# then fuzzes the mesh and mask readers: a separate clang build in
# ./build-fuzz (-DSHELLSPACE_BUILD_FUZZERS=ON, only the fuzz targets and the
# geometry and io rooms, with ASan + UBSan) and fuzz/run.sh with 20000
# inputs per target (about 3 minutes on 2 cores from a clean build dir).
# Needs ../shared/data next to the checkout. Exits non-zero on any failure
# or fuzz finding.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh -DSHELLSPACE_BUILD_BENCHMARKS=ON
cd build
ctest --output-on-failure -j"$(nproc)"
cd ..

# Fuzz stage (fuzz/CMakeLists.txt, fuzz/run.sh).
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  -DSHELLSPACE_BUILD_FUZZERS=ON -DSHELLSPACE_BUILD_TESTS=OFF \
  -DSHELLSPACE_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzzers
fuzz/run.sh build-fuzz 20000
