#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds and runs the whole test suite with CTest,
# runs the fast tests under ASan + UBSan (./build-sanitize), then fuzzes the
# mesh and mask readers: a separate clang build in
# ./build-fuzz (-DSHELLSPACE_BUILD_FUZZERS=ON, only the fuzz targets and the
# geometry and io rooms, with ASan + UBSan) and fuzz/run.sh with 20000
# inputs per target (about 3 minutes on 2 cores from a clean build dir).
# Needs ../shared/data next to the checkout (or SHELLSPACE_DATA). Exits non-zero on any failure
# or fuzz finding.
set -euo pipefail
cd "$(dirname "$0")/.."
# The options are forced, not taken from build/'s cache: scripts/demo.sh
# configures build/ with the tests and benchmarks off, and a cache with the
# tests off used to make CTest find none and this script pass.
scripts/setup.sh -DSHELLSPACE_BUILD_TESTS=ON -DSHELLSPACE_BUILD_BENCHMARKS=ON \
  -DSHELLSPACE_BUILD_EXAMPLES=ON -DSHELLSPACE_BUILD_PYTHON=ON \
  -DSHELLSPACE_SANITIZE=OFF -DSHELLSPACE_BUILD_FUZZERS=OFF
cd build
# CI runs the data tests too: without the data folder (SHELLSPACE_DATA) CTest
# would skip them (data_tests) and pass.
if ctest -N -R '^data_tests$' | grep -q 'Total Tests: 1'; then
  echo "scripts/test.sh: no data folder (SHELLSPACE_DATA, ../shared/data): the data tests cannot run" >&2
  exit 1
fi
# No test found is a failure, not a pass.
ctest --output-on-failure --no-tests=error -j"$(nproc)"
cd ..

# Sanitizer stage: the fast tests of tests/CMakeLists.txt
# (SHELLSPACE_SANITIZED_TESTS) and the sanitizer canary built with
# AddressSanitizer + UndefinedBehaviorSanitizer at -O1 in ./build-sanitize
# (only the rooms they need: geometry, io, cost_functions, solvers,
# calculus; about 15 minutes of the 2 cores), then run by
# scripts/run_sanitized_tests.sh: any report or failure fails the stage, and
# so does a canary defect that goes unreported.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DSHELLSPACE_SANITIZE=ON \
  -DSHELLSPACE_BUILD_TESTS=ON \
  -DSHELLSPACE_BUILD_BENCHMARKS=OFF -DSHELLSPACE_BUILD_PYTHON=OFF >/dev/null
cmake --build build-sanitize -j"$(nproc)" --target sanitized_tests
scripts/run_sanitized_tests.sh build-sanitize

# Fuzz stage (fuzz/CMakeLists.txt, fuzz/run.sh).
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  -DSHELLSPACE_BUILD_FUZZERS=ON -DSHELLSPACE_BUILD_TESTS=OFF \
  -DSHELLSPACE_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzzers
fuzz/run.sh build-fuzz 20000
