#!/usr/bin/env bash
# The headline workflows on the shared meshes, each a CLI run under /usr/bin/time -v, with the defaults a
# new user gets (the scale-aware material: eta = 1e-4 x the first input's
# area) unless a row says otherwise. Prints a Markdown table: wall time,
# CPU time (user + sys), peak RSS, exit code, whether the verb's criterion
# was met, iterations, and the run's main number.
#
# Usage: bench/workflow_bench.sh [BUILD_DIR] [OUT_DIR]
#   BUILD_DIR  default build (uses BUILD_DIR/shellspace)
#   OUT_DIR    default a new temporary directory (kept: frames, JSON, logs)
# Environment: WORKFLOW_CAP seconds per run (default 600, the verbs'
# --time_limit: a run that reaches it writes its best state, marked
# partial, and exits 124), WORKFLOW_ONLY a regular expression of the row
# names to run (default all).
#
# Targets (2 cores): faces geodesic K = 8 <= 60 s; transport along it at
# epsilon = 1, every rung solved, <= 3 min; cactus spline through 0, 9, 18
# (K = 8, rel. gradient 1e-4) <= 5 min; regression through 0, 3, ..., 18
# (K = 6, sigma = 0.01, 1e-4) <= 5 min; faces mean <= 30 s.
set -uo pipefail

build="${1:-build}"
cli="${build}/shellspace"
out="${2:-$(mktemp -d "${TMPDIR:-/tmp}/shellspace-workflows.XXXXXX")}"
cap="${WORKFLOW_CAP:-600}"
only="${WORKFLOW_ONLY:-.}"
data="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../shared/data" && pwd)"
faces="${data}/faces"
cactus="${data}/cactus"
if [[ ! -x "${cli}" ]]; then
  echo "$0: ${cli} not found (build first, or pass BUILD_DIR)" >&2
  exit 2
fi
mkdir -p "${out}"

echo "| workflow | wall s | CPU s (user + sys) | peak RSS MB | exit | criterion met | iterations | bending share | result |"
echo "|---|---|---|---|---|---|---|---|---|"

# run NAME KEY ARGS...: one verb run; KEY is the JSON field shown as result.
run() {
  local name="$1" key="$2"
  shift 2
  [[ "${name}" =~ ${only} ]] || return 0
  local json="${out}/${name}.json" log="${out}/${name}.time"
  # The verb's own --time_limit stops it at the cap (best state written,
  # "partial": true, exit 124); timeout is only a guard against a hang.
  timeout --signal=KILL "$((cap + 120))" /usr/bin/time -v "${cli}" "$@" \
    --time_limit "${cap}" --json >"${json}" 2>"${log}"
  local rc=$?
  python3 - "${name}" "${key}" "${json}" "${log}" "${rc}" <<'PY'
import json, re, sys
name, key, json_path, log_path, rc = sys.argv[1:]
log = open(log_path, errors="replace").read()
def field(pattern, scale=1.0):
    m = re.search(pattern, log)
    return float(m.group(1)) * scale if m else float("nan")
wall_text = re.search(r"Elapsed \(wall clock\) time.*: (\S+)", log)
wall = float("nan")
if wall_text:
    parts = [float(p) for p in wall_text.group(1).split(":")]
    wall = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
user = field(r"User time \(seconds\): (\S+)")
system = field(r"System time \(seconds\): (\S+)")
rss = field(r"Maximum resident set size \(kbytes\): (\S+)", 1 / 1024)
try:
    report = json.loads(open(json_path).read().strip().splitlines()[-1])
except Exception:
    report = {}
def find(obj, k):
    if isinstance(obj, dict):
        if k in obj:
            return obj[k]
        for v in obj.values():
            r = find(v, k)
            if r is not None:
                return r
    return None
met = report.get("converged", report.get("all_solved"))
if report.get("partial"):
    met = "%s (partial: %s)" % (met, report.get("stop_reason"))
iterations = report.get("iterations", "")
value = find(report, key)
value = "%s %.6g" % (key, value) if isinstance(value, (int, float)) else "-"
last = [l for l in log.splitlines() if l.startswith("shellspace ")]
note = "" if rc == "0" else " (" + (last[-1][:80] if last else "no output") + ")"
share = find(report, "bending_share")
share = "%.3g" % share if isinstance(share, (int, float)) else "-"
print("| %s | %.1f | %.1f + %.1f | %.0f | %s | %s | %s | %s | %s%s |" % (
    name, wall, user, system, rss, rc, met, iterations, share, value, note))
PY
}

inputs4="${faces}/neutral.ply,${faces}/smile.ply,${faces}/disgust.ply,${faces}/surprise.ply"
cactus7="$(for i in 0 3 6 9 12 15 18; do printf '%s/cactus%d.ply,' "${cactus}" "$i"; done)"
cactus7="${cactus7%,}"
# cactus_spline NAME A B C [ARGS...]: the spline through cactusA, B, C at
# 0, 4, 8 (K = 8) to a relative gradient of 1e-4, frames in OUT_DIR/NAME.
cactus_spline() {
  local name="$1" a="$2" b="$3" c="$4"
  shift 4
  run "${name}" spline_energy spline --quiet --keyframes \
    "${cactus}/cactus${a}.ply,${cactus}/cactus${b}.ply,${cactus}/cactus${c}.ply" \
    --at 0,4,8 --steps 8 --tolerance 1e-4 --output "${out}/${name}" "$@"
}

run faces_geodesic_K8 path_energy geodesic --quiet --start "${faces}/neutral.ply" \
  --end "${faces}/smile.ply" --steps 8 --output "${out}/faces_geodesic"
run faces_transport_eps1 rungs transport --quiet --path "${out}/faces_geodesic" \
  --variation "${faces}/disgust.ply" --epsilon 1 --output "${out}/faces_transport"
cactus_spline cactus_spline_0_9_18 0 9 18
run cactus_regress_K6 spline_energy regress --quiet --inputs "${cactus7}" \
  --at 0,1,2,3,4,5,6 --steps 6 --sigma 0.01 --tolerance 1e-4 \
  --output "${out}/cactus_regress"
run faces_mean energy mean --quiet --inputs "${inputs4}" --output "${out}/faces_mean.ply"
run faces_pca_from_mean mean_energy pca --quiet --inputs "${inputs4}" --modes 2 \
  --mean "${out}/faces_mean.ply" --output "${out}/faces_pca"
# A variant nobody tuned to: another pair of expressions.
run faces_geodesic_surprise_disgust_K8 path_energy geodesic --quiet \
  --start "${faces}/surprise.ply" --end "${faces}/disgust.ply" --steps 8 \
  --output "${out}/faces_geodesic_variant"
# Variants nobody tuned to: another variation to transport, other keyframes,
# other regression inputs.
run faces_transport_surprise_eps1 rungs transport --quiet \
  --path "${out}/faces_geodesic" --variation "${faces}/surprise.ply" \
  --epsilon 1 --output "${out}/faces_transport_variant"
cactus_spline cactus_spline_2_10_17 2 10 17
# The same keyframes from the piecewise geodesic (--init geodesic), the
# headline keyframes likewise, and keyframes nobody looked at with both.
cactus_spline cactus_spline_2_10_17_init_geodesic 2 10 17 --init geodesic
cactus_spline cactus_spline_0_9_18_init_geodesic 0 9 18 --init geodesic
cactus_spline cactus_spline_5_11_18 5 11 18
cactus_spline cactus_spline_5_11_18_init_geodesic 5 11 18 --init geodesic
cactus6="$(for i in 1 4 7 10 13 16; do printf '%s/cactus%d.ply,' "${cactus}" "$i"; done)"
run cactus_regress_1_4_16_K5 spline_energy regress --quiet --inputs "${cactus6%,}" \
  --at 0,1,2,3,4,5 --steps 5 --sigma 0.01 --tolerance 1e-4 \
  --output "${out}/cactus_regress_variant"
echo
echo "outputs and logs: ${out}"
