#!/usr/bin/env bash
# Sets up (scripts/setup.sh --profile test), builds and runs the whole test
# suite with CTest, runs the fast tests under ASan + UBSan
# (./build-sanitize), then fuzzes the mesh and mask readers: a separate clang
# build in ./build-fuzz (-DSHELLSPACE_BUILD_FUZZERS=ON, only the fuzz targets
# and the geometry and io rooms, with ASan + UBSan) and fuzz/run.sh with
# 20000 inputs per target. Exits non-zero on any failure or fuzz finding.
#
# The data tests read the meshes of SHELLSPACE_DATA (default ../shared/data
# next to the checkout). Without that folder they are skipped, with one line
# saying how many; with SHELLSPACE_REQUIRE_DATA=1 (set by .ci/run) a missing
# data folder fails the run before anything is built.
# Each phase prints "test: <phase>" and, when it ends, its time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
phase_start=$start
phase() {  # ends the phase before (with its time) and names the next
  local now
  now=$(date +%s)
  [ -z "${current:-}" ] || echo "test: $current took $((now - phase_start)) s"
  current=$1
  phase_start=$now
  [ -z "$current" ] || echo "test: $current"
}

# The options are forced, not taken from build/'s cache: scripts/demo.sh
# configures build/ with the tests and benchmarks off, and a cache with the
# tests off used to make CTest find none and this script pass.
phase "set-up and configure"
scripts/setup.sh --profile test --no-build \
  -DSHELLSPACE_BUILD_TESTS=ON -DSHELLSPACE_BUILD_BENCHMARKS=ON \
  -DSHELLSPACE_BUILD_EXAMPLES=ON -DSHELLSPACE_BUILD_PYTHON=ON \
  -DSHELLSPACE_SANITIZE=OFF -DSHELLSPACE_BUILD_FUZZERS=OFF
data_dir=$(sed -n 's/^SHELLSPACE_DATA:PATH=//p' build/CMakeCache.txt)
# Configured without the data folder: tests/CMakeLists.txt adds the
# placeholder data_tests and registers the data tests disabled.
no_data=0
if (cd build && ctest -N -R '^data_tests$' | grep -q 'Total Tests: 1'); then
  no_data=1
  if [ "${SHELLSPACE_REQUIRE_DATA:-0}" = 1 ]; then
    echo "scripts/test.sh: no data folder $data_dir (SHELLSPACE_DATA) and SHELLSPACE_REQUIRE_DATA=1: the data tests cannot run" >&2
    exit 1
  fi
fi

phase "building build/ (everything, tests included)"
scripts/build.sh build

phase "ctest"
cd build
if [ "$no_data" = 1 ]; then
  # The placeholder and the disabled data tests are left out of the run.
  skipped=$(ctest -N -L data | sed -n 's/^Total Tests: //p')
  skipped=$((skipped - 1))
  # No test found is a failure, not a pass.
  ctest --output-on-failure --no-tests=error -j"$(nproc)" -LE data
  echo "test: skipped $skipped data tests: no data folder $data_dir (set SHELLSPACE_DATA to the meshes' folder to run them)"
else
  ctest --output-on-failure --no-tests=error -j"$(nproc)"
fi
cd ..

# Sanitizer stage: the fast tests of tests/CMakeLists.txt
# (SHELLSPACE_SANITIZED_TESTS) and the sanitizer canary built with
# AddressSanitizer + UndefinedBehaviorSanitizer at -O1 in ./build-sanitize
# (only the rooms they need: geometry, io, cost_functions, solvers,
# calculus), then run by scripts/run_sanitized_tests.sh: any report or
# failure fails the stage, and so does a canary defect that goes unreported.
phase "sanitizer stage (build-sanitize/)"
generator=()
[ -f build-sanitize/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build-sanitize "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DSHELLSPACE_SANITIZE=ON -DSHELLSPACE_BUILD_TESTS=ON \
  -DSHELLSPACE_BUILD_BENCHMARKS=OFF -DSHELLSPACE_BUILD_PYTHON=OFF >/dev/null
scripts/build.sh build-sanitize sanitized_tests
scripts/run_sanitized_tests.sh build-sanitize

# Fuzz stage (fuzz/CMakeLists.txt, fuzz/run.sh).
phase "fuzz stage (build-fuzz/)"
generator=()
[ -f build-fuzz/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build-fuzz "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER=clang++ -DSHELLSPACE_BUILD_FUZZERS=ON \
  -DSHELLSPACE_BUILD_TESTS=OFF -DSHELLSPACE_BUILD_BENCHMARKS=OFF >/dev/null
scripts/build.sh build-fuzz fuzzers
fuzz/run.sh build-fuzz 20000
phase ""
echo "test: passed in $(( $(date +%s) - start )) s"
