#!/usr/bin/env bash
# Usage: fuzz/run.sh BUILD_DIR EXECUTIONS
#
# Runs every fuzz target of BUILD_DIR (configured with
# -DSHELLSPACE_BUILD_FUZZERS=ON, target 'fuzzers' built) for EXECUTIONS
# inputs with libFuzzer's fixed seed 1, from a fresh seed corpus
# (fuzz/make_corpus.sh into BUILD_DIR/fuzz-work/corpus). Fails on the first
# finding (crash, sanitizer report, leak, timeout, an exception other than
# InputError); the input is kept as BUILD_DIR/fuzz-work/artifacts/<target>-*.
# Prints executions per second of each target. The PLY and OFF targets get
# a dictionary of their header keywords and limit counts (fuzz/*.dict).
# -use_cmp=0 -use_memmem=0: libFuzzer's comparison-operand dictionaries
# contain heap addresses (which vary from run to run), so without them a
# -seed=1 run is reproducible.
set -euo pipefail
build="${1:?usage: $0 BUILD_DIR EXECUTIONS}"
runs="${2:?usage: $0 BUILD_DIR EXECUTIONS}"
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "$build" && pwd)"
work="$build/fuzz-work"
rm -rf "$work"
mkdir -p "$work/corpus" "$work/artifacts" "$work/tmp"
"$here/make_corpus.sh" "$work/corpus" >/dev/null
targets=(ply_ascii_fuzzer ply_binary_fuzzer obj_fuzzer off_fuzzer mask_fuzzer)
status=0
for t in "${targets[@]}"; do
  exe="$build/fuzz/$t"
  [ -x "$exe" ] || { echo "fuzz: $exe missing (build target 'fuzzers')"; exit 2; }
  log="$work/$t.log"
  dict=()
  case "$t" in
    ply_*) dict=(-dict="$here/ply.dict") ;;
    off_*) dict=(-dict="$here/off.dict") ;;
  esac
  start=$(date +%s.%N)
  if TMPDIR="$work/tmp" "$exe" -runs="$runs" -seed=1 -use_cmp=0 -use_memmem=0 -max_len=8192 \
      -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "${dict[@]}" \
      -artifact_prefix="$work/artifacts/$t-" "$work/corpus/$t" >"$log" 2>&1; then
    end=$(date +%s.%N)
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    printf 'fuzz %-18s ok: %s executions, %s exec/s, %.1f s, corpus %s files\n' \
      "$t" "$execs" "$rate" "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" \
      "$(ls "$work/corpus/$t" | wc -l)"
  else
    echo "fuzz $t: FINDING (log $log)"
    grep -E "ERROR|fuzz finding|SUMMARY|Test unit written" "$log" | head -5 || true
    status=1
  fi
done
exit $status
