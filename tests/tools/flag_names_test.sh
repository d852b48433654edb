#!/usr/bin/env bash
# Usage: tests/tools/flag_names_test.sh SOURCE_DIR
#
# CLI flag names appear only in tools/: fails on a string literal in a
# library room (anywhere under shellspace/)
# that contains "--" followed by a letter (a flag name like --steps).
set -euo pipefail
src="${1:?usage: $0 SOURCE_DIR}"
cd "$src"
hits="$(grep -rnE --include='*.h' --include='*.cc' '"[^"]*--[a-z][^"]*"' \
  shellspace |
  grep -vE '^[^:]+:[0-9]+:\s*//' || true)"
if [[ -n "$hits" ]]; then
  echo "flag names outside tools/:"
  echo "$hits"
  exit 1
fi
echo "flag names: none outside tools/"
