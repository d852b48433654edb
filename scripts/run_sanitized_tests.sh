#!/usr/bin/env bash
# Runs the sanitized test executables listed in BUILD/sanitized_tests.txt
# (a build configured with -DSHELLSPACE_SANITIZE=ON, target sanitized_tests),
# one line each: the executable and its gtest filter ("*"; "skip" for a data
# executable, *_data_test, when the build has no data folder).
# Any AddressSanitizer, LeakSanitizer or UndefinedBehaviorSanitizer report, or
# any test failure, fails the run; prints one line per executable.
# Usage: scripts/run_sanitized_tests.sh BUILD
set -uo pipefail
build=${1:?usage: run_sanitized_tests.sh BUILD}
list="$build/sanitized_tests.txt"
[ -f "$list" ] || { echo "run_sanitized_tests: $list not found" >&2; exit 1; }
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:exitcode=86
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:exitcode=87
failed=()
skipped=()
count=0
# The negative twin: the canary's deliberate heap-buffer-overflow and signed
# overflow must each fail with a sanitizer's report (the out-of-bounds read
# is caught by UBSan's object-size check before ASan sees it).
for mode in "heap:heap-buffer-overflow|insufficient space for an object" \
            "overflow:signed integer overflow"; do
  name=${mode%%:*}
  report=${mode#*:}
  log="$build/sanitized_canary_$name.log"
  if "$build/tests/sanitizer_canary" "$name" >"$log" 2>&1; then
    echo "sanitized: the canary's $name defect went unreported (log $log)" >&2
    exit 1
  fi
  if ! grep -Eq "$report" "$log"; then
    echo "sanitized: the canary's $name defect failed without '$report' (log $log):" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  echo "sanitized: canary $name reported ($report)"
done
while read -r name filter; do
  [ -n "$name" ] || continue
  if [ "${filter:-*}" = skip ]; then
    skipped+=("$name")
    continue
  fi
  count=$((count + 1))
  log="$build/sanitized_$name.log"
  start=$(date +%s)
  if "$build/tests/$name" --gtest_brief=1 --gtest_filter="${filter:-*}" \
      >"$log" 2>&1; then
    echo "sanitized: $name passed ($(( $(date +%s) - start )) s)"
  else
    rc=$?
    echo "sanitized: $name FAILED (exit $rc; log $log):"
    tail -n 40 "$log"
    failed+=("$name")
  fi
done <"$list"
if [ ${#skipped[@]} -gt 0 ]; then
  echo "sanitized: skipped ${#skipped[@]} executables whose every test reads the data folder: ${skipped[*]}"
fi
if [ "$count" -eq 0 ]; then
  echo "sanitized: $list lists no executable: nothing was tested" >&2
  exit 1
fi
if [ ${#failed[@]} -gt 0 ]; then
  echo "sanitized: ${#failed[@]} of $count executables failed: ${failed[*]}" >&2
  exit 1
fi
echo "sanitized: all $count executables passed with zero sanitizer reports"
