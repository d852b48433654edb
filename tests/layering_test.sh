#!/usr/bin/env bash
# Usage: tests/layering_test.sh SOURCE_DIR ROOM_TABLE [--self-test]
#
# The rooms may include only what they link (docs/development.md, "The
# layering test"). ROOM_TABLE is written by CMake at configure time from
# the rooms' target_link_libraries (shellspace_write_room_table in
# cmake/rooms.cmake; build/room_links.txt), one line per room, bottom up:
#
#   <room> <source folder> <include prefix> : <rooms it links>
#
# A room may include the rooms it links, directly or through them (the
# closure of the link graph). Fails on
#   - an include of a room above it (one that links it): "upward";
#   - an include of a room it does not link: "not linked" (a missing link:
#     it compiles only because every room shares one include folder);
#   - an include of the front ends (tools/, tests/, python/, bench/,
#     examples/, fuzz/: included by their path from the checkout's top,
#     "tools/run/run_status.h") from a room: "upward";
#   - an include "shellspace/..." that names no room (anywhere);
#   - an include of a room without the shellspace/ prefix
#     ("geometry/mesh.h"), in any of the project's C++ folders;
#   - a link in the table to a room that is not below (a cycle);
#   - in the CLI, an include of tools/verbs/ from tools/run/ (the run's
#     infrastructure knows no verb);
#   - in the calculus, an include of geodesic.h from the parts the geodesic
#     solve is built of (shell_path, path_energy, path_newton,
#     geodesic_initial_path, vertex_relaxation, stiff_vertex_elimination;
#     .h and .cc): a back-arrow inside the room.
# With --self-test, first checks that a copy of the rooms passes and that
# each of ten injected faults (bad includes, wrong edges in the table)
# fails with its message.
set -uo pipefail
src="${1:?usage: $0 SOURCE_DIR ROOM_TABLE [--self-test]}"
table="${2:?usage: $0 SOURCE_DIR ROOM_TABLE [--self-test]}"
src="$(cd "$src" && pwd)"
table="$(cd "$(dirname "$table")" && pwd)/$(basename "$table")"

# The project's C++ folders besides the rooms (checked for bare includes).
others=(tools python bench tests examples fuzz)

# check SOURCE TABLE: prints one line per violation and a count; exit 1 if any.
check() {
  local root=$1 rooms=$2 folders=() f
  while read -r f; do [[ -d "$root/$f" ]] && folders+=("$f"); done < <(
    awk '!/^#/ && NF { print $2 }' "$rooms")
  for f in "${others[@]}"; do [[ -d "$root/$f" ]] && folders+=("$f"); done
  (cd "$root" && grep -rHE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"]+"' \
      --include='*.h' --include='*.cc' "${folders[@]}" || true) |
  awk -v table="$rooms" '
    function fail(text) { print "layering: " text; violations++ }
    # The room whose folder (or include prefix, kind "prefix") holds path;
    # the longest match, "" if none.
    function room_of(path, kind,   r, best, len) {
      best = ""; len = 0
      for (r in order) {
        p = (kind == "prefix") ? prefix[r] : folder[r]
        if (index(path, p "/") == 1 && length(p) > len) { best = r; len = length(p) }
      }
      return best
    }
    BEGIN {
      n = 0
      while ((getline line < table) > 0) {
        if (line ~ /^#/ || line !~ /[^[:space:]]/) continue
        split(line, halves, ":")
        split(halves[1], f, " ")
        name = f[1]; folder[name] = f[2]; prefix[name] = f[3]
        order[name] = ++n
        links[name] = halves[2]
        top = prefix[name]; sub(/^shellspace\//, "", top); sub(/\/.*/, "", top)
        bare[top] = 1
      }
      split("tools tests python bench examples fuzz", f, " ")
      for (i in f) front[f[i]] = 1
      for (a in order) {
        k = split(links[a], l, " ")
        for (i = 1; i <= k; i++) {
          b = l[i]
          if (!(b in order)) fail("room " a " links " b ", which is not in the table")
          else if (order[b] >= order[a]) fail("room " a " links " b ", which is not below it (a cycle)")
          reach[a, b] = 1
        }
      }
      do {  # the closure of the link graph (a few dozen rooms at most)
        grown = 0
        for (a in order) for (b in order) if ((a, b) in reach)
          for (c in order) if (((b, c) in reach) && !((a, c) in reach)) { reach[a, c] = 1; grown = 1 }
      } while (grown)
    }
    {
      file = $0; sub(/:.*/, "", file)
      include = $0; sub(/^[^:]*:[^"]*"/, "", include); sub(/".*/, "", include)
      checked++
      top = include; sub(/\/.*/, "", top)
      if (include !~ /^shellspace\// && include ~ /\// && (top in bare)) {
        fail(file " includes \"" include "\" without the shellspace/ prefix")
        next
      }
      if (include ~ /^shellspace\// && room_of(include, "prefix") == "") {
        fail(file " includes " include ", which names no room")
        next
      }
      if (file ~ /^tools\/run\// && include ~ /^tools\/verbs\//) {
        fail(file " (tools/run) includes " include ": the run infrastructure knows no verb")
        next
      }
      if (file ~ /\/(shell_path|path_energy|path_newton|geodesic_initial_path|vertex_relaxation|stiff_vertex_elimination)\.(h|cc)$/ &&
          include ~ /\/calculus\/geodesic\.h$/) {
        fail(file " includes " include ": the geodesic solve is built of it")
        next
      }
      room = room_of(file, "folder")
      if (room == "") next
      if (include ~ /\// && (top in front)) {
        fail(file " (" room ") includes " include ": upward, " top "/ is above every room")
        next
      }
      if (include !~ /^shellspace\//) next
      target = room_of(include, "prefix")
      if (target == room || ((room, target) in reach)) next
      if ((target, room) in reach)
        fail(file " (" room ") includes " include " (" target "): upward, " target " links " room)
      else
        fail(file " (" room ") includes " include " (" target "): not linked, " room " does not link " target)
    }
    END {
      printf "layering: %d rooms, %d includes checked, %d violations\n", n, checked, violations
      exit violations > 0
    }'
}

status=0
if [[ "${3:-}" == "--self-test" ]]; then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  copy="$scratch/src"
  mkdir -p "$copy"
  while read -r f; do
    (cd "$src" && cp -r --parents "$f" "$copy/")
  done < <(awk '!/^#/ && NF { print $2 }' "$table")
  folder_of() { awk -v r="$1" '$1 == r { print $2 }' "$table"; }
  prefix_of() { awk -v r="$1" '$1 == r { print $3 }' "$table"; }
  # expect NAME PATTERN [TABLE]: the copy fails the check with a line matching PATTERN.
  expect() {
    local out
    if out=$(check "$copy" "${3:-$table}"); then
      echo "FAIL: self-test '$1': the check passed" >&2; status=1
    elif ! grep -qE "$2" <<<"$out"; then
      echo "FAIL: self-test '$1': no line matching '$2' in:" >&2; echo "$out" >&2; status=1
    else
      echo "self-test '$1': caught: $(grep -E "$2" <<<"$out" | head -1)"
    fi
  }
  if ! out=$(check "$copy" "$table"); then
    echo "FAIL: self-test: the untouched copy of the rooms fails:" >&2; echo "$out" >&2; status=1
  fi
  geometry=$(folder_of geometry)
  probe="$copy/$geometry/layering_probe.h"
  echo "#include \"$(prefix_of calculus)/geodesic.h\"" > "$probe"
  expect "upward include" "$geometry/layering_probe.h \(geometry\) includes .*: upward, calculus links geometry"
  echo "#include \"shellspace/tools/verbs/verb.h\"" > "$probe"
  expect "include of no room" "$geometry/layering_probe.h includes shellspace/tools/verbs/verb.h, which names no room"
  echo "#include \"tools/run/run_status.h\"" > "$probe"
  expect "room includes the CLI" "$geometry/layering_probe.h \(geometry\) includes tools/run/run_status.h: upward, tools/ is above every room"
  echo "#include \"geometry/mesh.h\"" > "$probe"
  expect "bare include" "$geometry/layering_probe.h includes \"geometry/mesh.h\" without the shellspace/ prefix"
  rm "$probe"
  io=$(folder_of io)
  echo "#include \"$(prefix_of solvers)/linear_solver.h\"" > "$copy/$io/layering_probe.cc"
  expect "missing link" "$io/layering_probe.cc \(io\) includes .*: not linked, io does not link solvers"
  rm "$copy/$io/layering_probe.cc"
  mkdir -p "$copy/tools/run"
  echo "#include \"tools/verbs/verb.h\"" > "$copy/tools/run/layering_probe.cc"
  expect "run includes a verb" "tools/run/layering_probe.cc \(tools/run\) includes tools/verbs/verb.h"
  rm -r "$copy/tools"
  calculus=$(folder_of calculus)
  cp "$copy/$calculus/path_newton.cc" "$scratch/path_newton.cc"
  echo "#include \"$(prefix_of calculus)/geodesic.h\"" >> "$copy/$calculus/path_newton.cc"
  expect "back-arrow in the calculus" "$calculus/path_newton.cc includes .*geodesic.h: the geodesic solve is built of it"
  cp "$scratch/path_newton.cc" "$copy/$calculus/path_newton.cc"
  cp "$copy/$calculus/vertex_relaxation.h" "$scratch/vertex_relaxation.h"
  echo "#include \"$(prefix_of calculus)/geodesic.h\"" >> "$copy/$calculus/vertex_relaxation.h"
  expect "back-arrow from a stage of the solve" "$calculus/vertex_relaxation.h includes .*geodesic.h: the geodesic solve is built of it"
  cp "$scratch/vertex_relaxation.h" "$copy/$calculus/vertex_relaxation.h"
  # Wrong edges in the table: render without its link to the branching
  # model it draws, and geometry linking the calculus (a back edge).
  awk '$1 == "render" { sub(/ branching_model/, "") } { print }' "$table" > "$scratch/no_edge.txt"
  expect "edge removed from the table" "\(render\) includes .*\(branching_model\): not linked, render does not link branching_model" "$scratch/no_edge.txt"
  awk '$1 == "geometry" { $0 = $0 " calculus" } { print }' "$table" > "$scratch/back_edge.txt"
  expect "back edge in the table" "room geometry links calculus, which is not below it" "$scratch/back_edge.txt"
fi

check "$src" "$table" || status=1
exit $status
