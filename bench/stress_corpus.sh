#!/usr/bin/env bash
# The stress corpus: single-pose public meshes (../shared/data/cgal) and the
# cactus, each with a second pose made by bench/stress_pose (a bend along
# the longest axis, a twist about it, a local pull, each followed by a
# random rigid motion of 30 degrees, or a rigid motion alone), run through
# the CLI with default settings as a new user would:
#   geodesic  START -> POSE, K = 8
#   shoot     the geodesic's frames 0 and 1 extrapolated K = 8 steps
#   transport a local pull of START (0.02 of the diagonal) along the geodesic
#   mean      of START and POSE
# Each run under /usr/bin/time -v; prints a Markdown table: converged
# (the verb's own criterion, exit 0), exit code, iterations, wall, CPU
# (user + sys), peak RSS, and the geodesic's initial path and
# multiresolution start, and the stages that ran (L: LM, N: exact Newton,
# P: projected Newton, R: vertex relaxation, each with its iterations);
# then per verb the runs, how many converged and their CPU seconds.
#
# Usage: bench/stress_corpus.sh [BUILD_DIR] [OUT_DIR]
# Environment:
#   SHELLSPACE_DATA      the meshes' folder (default ../shared/data beside
#                        the checkout)
#   CORPUS_MESHES        mesh files (default: every cgal mesh and
#                        cactus/cactus0.ply)
#   CORPUS_DEFORMATIONS  KIND:STRENGTH list (default: bend:75 bend:120
#                        twist:60 twist:180 pull:0.15)
#   CORPUS_VERBS         default "geodesic shoot transport mean"
#   CORPUS_CAP           --time_limit of each run in seconds (default 600)
#   CORPUS_SEED          the first pose's seed (default 1); each further
#                        pose takes the next. A table's rows of one mesh
#                        are remade alone by listing only that mesh and
#                        starting at the seed it had there (its position,
#                        counted in poses)
set -uo pipefail

build="${1:-build}"
cli="${build}/shellspace"
pose="${build}/bench/stress_pose"
out="${2:-$(mktemp -d "${TMPDIR:-/tmp}/shellspace-corpus.XXXXXX")}"
data="${SHELLSPACE_DATA:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../../shared/data" && pwd)}"
cap="${CORPUS_CAP:-600}"
verbs="${CORPUS_VERBS:-geodesic shoot transport mean}"
deformations="${CORPUS_DEFORMATIONS:-bend:75 bend:120 twist:60 twist:180 pull:0.15}"
if [[ -n "${CORPUS_MESHES:-}" ]]; then
  read -r -a meshes <<<"${CORPUS_MESHES}"
else
  meshes=("${data}"/cgal/*.off "${data}/cactus/cactus0.ply")
fi
for tool in "${cli}" "${pose}"; do
  [[ -x "${tool}" ]] || { echo "$0: ${tool} not found (build first)" >&2; exit 2; }
done
mkdir -p "${out}"

echo "| mesh | vertices | pose | verb | converged | exit | iterations | wall s | CPU s | peak RSS MB | start |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"

# json_field FILE KEY: the first value of "KEY": in a JSON file ("" if
# none); KEY "stages" gives the geodesic's stages as "L12 N4 P20 N3"
# (method letter, iterations).
json_field() {
  python3 -c 'import json,sys
try:
    d = json.load(open(sys.argv[1]))
except Exception:
    print(""); sys.exit()
if sys.argv[2] == "stages":
    letters = {"levenberg-marquardt": "L", "newton": "N", "projected-newton": "P",
               "vertex-relaxation": "R"}
    print(" ".join(letters.get(s.get("method"), "?") + str(s.get("iterations", ""))
                   for s in d.get("stages") or [] if isinstance(s, dict)))
    sys.exit()
v = d
for k in sys.argv[2].split("."):
    v = v.get(k, "") if isinstance(v, dict) else ""
print(v)' "$1" "$2"
}

# run NAME VERTICES POSE VERB JSON ARGS...: one CLI run, one table row.
run() {
  local name="$1" vertices="$2" posename="$3" verb="$4" json="$5"
  shift 5
  local log="${out}/${name}.${posename}.${verb}.log"
  /usr/bin/time -v "${cli}" "${verb}" "$@" --json --time_limit "${cap}" \
    >"${json}" 2>"${log}"
  local code=$?
  local wall cpu rss
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":");
    s = 0; for (i = 1; i <= n; ++i) s = s * 60 + t[i]; printf "%.1f", s}' "${log}")
  cpu=$(awk -F': ' '/User time|System time/ {s += $2} END {printf "%.1f", s}' "${log}")
  rss=$(awk -F': ' '/Maximum resident/ {printf "%.0f", $2 / 1024}' "${log}")
  local converged iterations start=""
  converged=$(json_field "${json}" converged)
  iterations=$(json_field "${json}" iterations)
  if [[ "${verb}" == geodesic ]]; then
    start="$(json_field "${json}" init.used) [$(json_field "${json}" stages)]"
    local prolongated
    prolongated=$(json_field "${json}" prolongation.used)
    [[ "$(json_field "${json}" prolongation.checked)" == True ]] &&
      start+="; prolongation $([[ ${prolongated} == True ]] && echo used || echo rejected)"
  fi
  [[ ${code} -ne 0 ]] && start+=" — $(grep -v '^\s' "${log}" | grep -v "^warning" | grep -v "^Command exited" | tail -n 1 | cut -c1-120)"
  start="${start//|/\\|}"  # a Markdown cell: "|grad|" in a message escaped
  echo "| ${name} | ${vertices} | ${posename} | ${verb} | ${converged:-no} | ${code} | ${iterations:-} | ${wall} | ${cpu} | ${rss} | ${start} |"
  runs[${verb}]=$(( ${runs[${verb}]:-0} + 1 ))
  cpu_total[${verb}]=$(awk -v a="${cpu_total[${verb}]:-0}" -v b="${cpu:-0}" 'BEGIN {printf "%.1f", a + b}')
  [[ ${code} -eq 0 && "${converged}" == True ]] &&
    met[${verb}]=$(( ${met[${verb}]:-0} + 1 ))
}
# Per verb: runs, runs that met the criterion (exit 0), CPU seconds.
declare -A runs met cpu_total

seed="${CORPUS_SEED:-1}"
[[ "${seed}" =~ ^[0-9]+$ ]] || { echo "$0: CORPUS_SEED must be a number" >&2; exit 2; }
for mesh in "${meshes[@]}"; do
  name="$(basename "${mesh%.*}")"
  if [[ "${mesh}" == *.ply ]]; then
    vertices=$(awk '/^element vertex/ {print $3; exit}' "${mesh}")
  else
    vertices=$(awk 'NR == 1 && /OFF/ && NF > 1 {print $2; exit}
                    NR == 1 {next} !/^#/ && NF {print $1; exit}' "${mesh}")
  fi
  for deformation in ${deformations}; do
    kind="${deformation%%:*}"
    strength="${deformation#*:}"
    posename="${kind}${strength}"
    dir="${out}/${name}/${posename}"
    mkdir -p "${dir}"
    start="${dir}/start.ply"
    end="${dir}/pose.ply"
    "${pose}" "${mesh}" none 0 0 "${start}" norigid >/dev/null 2>&1 || {
      echo "| ${name} | ${vertices} | ${posename} | (pose) | no | 1 | | | | | unreadable mesh |"
      continue
    }
    "${pose}" "${mesh}" "${kind}" "${strength}" "${seed}" "${end}"
    seed=$((seed + 1))
    for verb in ${verbs}; do
      case "${verb}" in
        geodesic)
          rm -rf "${dir}/geodesic"
          run "${name}" "${vertices}" "${posename}" geodesic "${dir}/geodesic.json" \
            --start "${start}" --end "${end}" --steps 8 --output "${dir}/geodesic" ;;
        shoot)
          [[ -f "${dir}/geodesic/shape_001.ply" ]] || continue
          rm -rf "${dir}/shoot"
          run "${name}" "${vertices}" "${posename}" shoot "${dir}/shoot.json" \
            --first "${dir}/geodesic/shape_000.ply" \
            --second "${dir}/geodesic/shape_001.ply" --steps 8 \
            --output "${dir}/shoot" ;;
        transport)
          [[ -f "${dir}/geodesic/shape_001.ply" ]] || continue
          "${pose}" "${start}" pull 0.02 0 "${dir}/variation.ply" norigid
          rm -rf "${dir}/transport"
          run "${name}" "${vertices}" "${posename}" transport "${dir}/transport.json" \
            --path "${dir}/geodesic" --variation "${dir}/variation.ply" \
            --output "${dir}/transport" ;;
        mean)
          rm -f "${dir}/mean.ply"
          run "${name}" "${vertices}" "${posename}" mean "${dir}/mean.json" \
            --inputs "${start},${end}" --output "${dir}/mean.ply" ;;
      esac
    done
  done
done
echo
echo "| verb | runs | converged (exit 0) | CPU s |"
echo "|---|---|---|---|"
for verb in ${verbs}; do
  echo "| ${verb} | ${runs[${verb}]:-0} | ${met[${verb}]:-0} | ${cpu_total[${verb}]:-0} |"
done
echo
echo "outputs and logs: ${out}"
