#!/usr/bin/env bash
# Runs the sanitized test executables listed in BUILD/sanitized_tests.txt
# (a build configured with -DSHELLSPACE_SANITIZE=ON, target sanitized_tests).
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
count=0
while read -r name; do
  [ -n "$name" ] || continue
  count=$((count + 1))
  log="$build/sanitized_$name.log"
  start=$(date +%s)
  if "$build/tests/$name" --gtest_brief=1 >"$log" 2>&1; then
    echo "sanitized: $name passed ($(( $(date +%s) - start )) s)"
  else
    rc=$?
    echo "sanitized: $name FAILED (exit $rc; log $log):"
    tail -n 40 "$log"
    failed+=("$name")
  fi
done <"$list"
if [ ${#failed[@]} -gt 0 ]; then
  echo "sanitized: ${#failed[@]} of $count executables failed: ${failed[*]}" >&2
  exit 1
fi
echo "sanitized: all $count executables passed with zero sanitizer reports"
