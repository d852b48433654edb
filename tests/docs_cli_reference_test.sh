#!/usr/bin/env bash
# docs/cli.md is the output of scripts/cli_reference.sh for this build's
# shellspace: a flag added, removed or reworded in tools/ without
# regenerating the page fails here, with the difference.
#   tests/docs_cli_reference_test.sh SOURCE_DIR SHELLSPACE_BINARY
set -uo pipefail
source_dir=$1
binary=$2
generated=$(mktemp)
trap 'rm -f "$generated"' EXIT
if ! "$source_dir/scripts/cli_reference.sh" "$binary" - > "$generated"; then
  echo "FAIL: scripts/cli_reference.sh did not run" >&2
  exit 1
fi
if ! grep -q '^## geodesic$' "$generated"; then
  echo "FAIL: the generated reference has no geodesic section" >&2
  exit 1
fi
if ! diff -u "$source_dir/docs/cli.md" "$generated"; then
  echo "FAIL: docs/cli.md is out of date; run scripts/cli_reference.sh $binary" >&2
  exit 1
fi
echo "docs/cli.md is current ($(wc -l < "$generated") lines)"
