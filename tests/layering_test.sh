#!/usr/bin/env bash
# Usage: tests/layering_test.sh SOURCE_DIR
#
# The rooms of the library may include only the rooms below them (docs/development.md,
# "Layout"). Lists every project include of every room's sources and fails
# on one that reaches a room it may not use (a back-edge or a cycle).
set -euo pipefail
src="${1:?usage: $0 SOURCE_DIR}"
cd "$src"

# room folder -> rooms it may include (itself always).
declare -A allowed=(
  [runtime]=""
  [geometry]=""
  [models/branching]="geometry"
  [cost_functions]="geometry runtime models/branching"
  [solvers]="geometry runtime"
  [io]="geometry"
  [problems/calculus]="runtime geometry cost_functions solvers models/branching"
  [problems/splines]="runtime geometry cost_functions solvers problems/calculus models/branching"
  [problems/statistics]="runtime geometry cost_functions solvers problems/calculus models/branching"
  [problems/branching]="runtime geometry cost_functions solvers models/branching"
  # models/branching: the data it draws (constructions, relaxed fields).
  [render]="geometry io models/branching"
  # The verbs' summaries (CLI --json and the Python module's dicts).
  [reports]="runtime geometry cost_functions solvers io problems/calculus problems/splines problems/statistics problems/branching models/branching"
)

# The room of an include path "shellspace/<room>/...".
room_of() {
  local path="${1#shellspace/}"
  case "$path" in
    problems/* | models/*) echo "$path" | cut -d/ -f1-2 ;;
    *) echo "${path%%/*}" ;;
  esac
}

violations=0
checked=0
for room in "${!allowed[@]}"; do
  while IFS= read -r line; do
    file="${line%%:*}"
    include="$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"${line#*:}")"
    target="$(room_of "$include")"
    checked=$((checked + 1))
    [[ "$target" == "$room" ]] && continue
    ok=0
    for a in ${allowed[$room]}; do [[ "$a" == "$target" ]] && ok=1; done
    if [[ $ok -eq 0 ]]; then
      echo "layering: $file ($room) includes $include ($target)"
      violations=$((violations + 1))
    fi
  done < <(grep -rHE '^\s*#include "shellspace/' "$room" --include='*.h' --include='*.cc' || true)
done
# Every project include is "shellspace/<room>/...": a bare "geometry/mesh.h"
# would only resolve through an include path that collides with users' files.
while IFS= read -r line; do
  echo "layering: include without the shellspace/ prefix: $line"
  violations=$((violations + 1))
done < <(grep -rnE '^\s*#include "(runtime|geometry|models|cost_functions|solvers|problems|io|render|reports|tools|python)/' \
           runtime geometry models cost_functions solvers problems io render reports tools python bench tests --include='*.h' --include='*.cc' || true)
echo "layering: ${checked} includes checked, ${violations} violations"
[[ $violations -eq 0 ]]
