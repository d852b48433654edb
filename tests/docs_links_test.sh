#!/usr/bin/env bash
# Every relative link of README.md and docs/*.md, [text](target) with an
# optional #anchor, names a file or directory that exists (relative to the
# page that links it). Links with a scheme (https:, mailto:) are not
# checked. With --self-test, also checks that a page with a broken link is
# caught.
#   tests/docs_links_test.sh SOURCE_DIR [--self-test]
set -uo pipefail
source_dir=$1

broken_links() {  # prints "page: target" for each broken link of the pages
  local page dir target
  for page in "$@"; do
    dir=$(dirname "$page")
    # [text](target) outside code spans; an image ![..](..) alike.
    grep -oE '\]\([^)[:space:]]+\)' "$page" | sed -E 's/^\]\((.*)\)$/\1/' |
    while IFS= read -r target; do
      case "$target" in
        *://*|mailto:*|\#*) continue ;;
      esac
      target=${target%%#*}
      [[ -e "$dir/$target" ]] || echo "$page: $target"
    done
  done
}

status=0
if [[ "${2:-}" == "--self-test" ]]; then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  mkdir -p "$scratch/docs"
  printf '[ok](docs/a.md) [ok](docs/a.md#x) [web](https://example.org)\n' > "$scratch/README.md"
  printf '[up](../README.md) [bad](missing.md)\n' > "$scratch/docs/a.md"
  found=$(broken_links "$scratch/README.md" "$scratch/docs/a.md")
  if [[ "$found" != "$scratch/docs/a.md: missing.md" ]]; then
    echo "FAIL: self-test: expected exactly docs/a.md: missing.md, got: $found" >&2
    status=1
  fi
fi

pages=("$source_dir/README.md" "$source_dir"/docs/*.md)
found=$(broken_links "${pages[@]}")
if [[ -n "$found" ]]; then
  echo "FAIL: broken relative links:" >&2
  echo "$found" >&2
  status=1
fi
count=$(cat "${pages[@]}" | grep -oE '\]\([^)[:space:]]+\)' | grep -vcE '\]\(([a-z]+:|#)')
echo "${#pages[@]} pages, $count relative links checked"
exit $status
