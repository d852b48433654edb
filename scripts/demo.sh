#!/usr/bin/env bash
# Sets up (scripts/setup.sh) and runs the built-in demo: writes PLY frames, a
# JSON summary and a PNG film strip into ./demo-output/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh -DSHELLSPACE_BUILD_TESTS=OFF -DSHELLSPACE_BUILD_BENCHMARKS=OFF
build/shellspace demo --output demo-output "$@"
echo "demo: frames in demo-output/frames/, strip demo-output/film_strip.png, summary demo-output/summary.json"
