#!/usr/bin/env bash
# Usage: tests/docs_blocks_test.sh SOURCE_DIR BUILD_DIR [--self-test]
#
# Runs every command and code block of README.md, docs/tutorial.md and
# docs/python.md, page by page and in order, in one empty temporary folder
# that holds only `build` (a link to BUILD_DIR): what a reader of a bare
# clone has after the two commands. Shell blocks (indented by four spaces,
# or fenced as sh/bash/console) run in bash with -e; ```python blocks run in
# $PYTHON (default python3; CTest passes the one the module is built for)
# with PYTHONPATH=build/python. The two set-up commands
# (scripts/demo.sh, scripts/test.sh) are what made BUILD_DIR and are not run
# again. Any failing block fails the test, naming its page and line.
# --self-test first checks that a page with a failing block fails.
set -euo pipefail
source_dir=$(cd "${1:?usage: $0 SOURCE_DIR BUILD_DIR}" && pwd)
build_dir=$(cd "${2:?usage: $0 SOURCE_DIR BUILD_DIR}" && pwd)
pages=(README.md docs/tutorial.md docs/python.md)

# Splits PAGE into blocks: DIR/NNN.sh or DIR/NNN.py, each starting with a
# comment naming the page and line.
extract() {
  python3 - "$1" "$2" <<'PY'
import os, re, sys
page, out = sys.argv[1], sys.argv[2]
lines = open(page).read().split("\n")
blocks, i, fence = [], 0, None
while i < len(lines):
    line = lines[i]
    m = re.match(r"^```(\w*)\s*$", line)
    if m:
        kind, start, body = m.group(1), i + 1, []
        i += 1
        while i < len(lines) and not lines[i].startswith("```"):
            body.append(lines[i]); i += 1
        if kind == "python":
            blocks.append(("py", start, body))
        elif kind in ("sh", "bash", "console"):
            blocks.append(("sh", start, body))
    elif line.startswith("    ") and (i == 0 or lines[i - 1].strip() == ""):
        start, body = i + 1, []
        while i < len(lines) and (lines[i].startswith("    ") or
                                  (lines[i].strip() == "" and i + 1 < len(lines)
                                   and lines[i + 1].startswith("    "))):
            body.append(lines[i][4:]); i += 1
        blocks.append(("sh", start, body))
        continue
    i += 1
for n, (kind, start, body) in enumerate(blocks):
    text = "\n".join(body).strip("\n")
    if kind == "sh":
        # The set-up commands made build/; they are not run again.
        text = "\n".join(l for l in text.split("\n")
                         if not re.match(r"^scripts/(demo|test)\.sh\b", l))
        if not text.strip():
            continue
    with open(os.path.join(out, f"{n:03d}.{kind}"), "w") as f:
        f.write(f"# {os.path.basename(page)}:{start}\n{text}\n")
PY
}

# Runs the blocks of the pages $@ (paths) in folder $work; returns non-zero
# at the first failing block.
run_pages() {
  local work=$1; shift
  for page in "$@"; do
    local blocks
    blocks=$(mktemp -d)
    extract "$page" "$blocks"
    for block in "$blocks"/*; do
      [ -e "$block" ] || continue
      local where
      where=$(head -1 "$block" | cut -c3-)
      local start=$SECONDS
      if [[ "$block" == *.py ]]; then
        (cd "$work" && PYTHONPATH=build/python "${PYTHON:-python3}" "$block") >"$blocks/log" 2>&1
      else
        (cd "$work" && bash -e "$block") >"$blocks/log" 2>&1
      fi || {
        echo "docs_blocks: the block at $where failed:"
        tail -n 30 "$blocks/log"
        rm -rf "$blocks"
        return 1
      }
      echo "docs_blocks: $where ran ($((SECONDS - start)) s)"
    done
    rm -rf "$blocks"
  done
}

fresh_folder() {
  local work
  work=$(mktemp -d)
  ln -s "$build_dir" "$work/build"
  echo "$work"
}

if [ "${3:-}" = --self-test ]; then
  work=$(fresh_folder)
  printf 'Text.\n\n    build/shellspace example finger --output finger\n\nMore.\n\n    test -f finger/no_such_file.ply\n' >"$work/broken.md"
  if run_pages "$work" "$work/broken.md" >/dev/null; then
    echo "docs_blocks: self-test: a page with a failing block passed"
    exit 1
  fi
  rm -rf "$work"
  echo "docs_blocks: self-test: a failing block fails the page"
fi
work=$(fresh_folder)
trap 'rm -rf "$work"' EXIT
for page in "${pages[@]}"; do
  run_pages "$work" "$source_dir/$page"
done
echo "docs_blocks: every block of ${pages[*]} ran"
