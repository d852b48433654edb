#!/usr/bin/env bash
# Builds a configured build directory on all cores, one line per step:
# "building n/N: what" (Ninja's progress; Make's "[ p%]" lines pass as they
# are, and so do the compiler's messages).
#   scripts/build.sh BUILD_DIR [TARGET...]
set -euo pipefail
dir=${1:?usage: scripts/build.sh BUILD_DIR [TARGET...]}
shift
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" -j"$(nproc)" "${targets[@]}" |
  sed -u -E 's/^\[([0-9]+)\/([0-9]+)\] [A-Z][a-z]+ [A-Za-z+]+ [a-z ]*(object|library|executable|module) /building \1\/\2: /'
