#!/usr/bin/env bash
# Installs what the command-line tool needs (scripts/setup.sh --profile cli),
# builds only `shellspace` and the libraries it links, and runs the built-in
# demo: PLY frames, a JSON summary, a PNG film strip and a page to look at the
# path in a browser (viewer.html) in ./demo-output/. Prints each phase
# (installing, configuring, building n/N, running) with its time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
scripts/setup.sh --profile cli --target shellspace_cli \
  -DSHELLSPACE_BUILD_TESTS=OFF -DSHELLSPACE_BUILD_BENCHMARKS=OFF \
  -DSHELLSPACE_BUILD_EXAMPLES=OFF
built=$(date +%s)
echo "demo: set up in $((built - start)) s; running"
build/shellspace demo --output demo-output "$@" >/dev/null
echo "demo: ran in $(( $(date +%s) - built )) s; frames in demo-output/frames/," \
  "strip demo-output/film_strip.png, summary demo-output/summary.json," \
  "viewer demo-output/viewer.html"
