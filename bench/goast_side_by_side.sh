#!/usr/bin/env bash
# shellspace against the authors' reference code GOAST on the same discrete
# geodesics, on this machine. GOAST is read and built from a checkout given
# on the command line (nothing of it is kept in this repository): its
# example interpolationShells (examples/geodesic_interpolation_shells.cpp)
# is built in Release, and two programs are made next to it in the build
# directory:
#   - a copy of that example reading its meshes, centre vertex, ring size,
#     number of shapes and bending weight from the command line (and printing
#     the final energy with 17 digits); with finger0/1, 1302, 10, 5 it is
#     the example itself;
#   - pathcheck, GOAST's path energy E_K and its masked gradient (2-norm and
#     max-norm) on a path written by shellspace (frames parsed in double
#     precision: OpenMesh's PLY reader rounds coordinates to float), so both
#     programs' results are measured with one yardstick.
#
# Problems (as GOAST's example): the vertex mask is the 10-ring of a vertex
# (all vertices within 10 edges, Topology::getVertexNRingVertices), the
# initial path the linear interpolation of the vertex positions
# (initializationScheme 2), bendWeight 0.001, which is shellspace's
# eta = 0.001 / 3 (GOAST's SimpleBendingEnergy sums
# dtheta^2 |e|^2 / (|T1| + |T2|) and omits the 3 of d_e = (|T1| + |T2|)/3).
#   finger  finger0 -> finger1, 5 shapes (K = 4), ring around vertex 1302
#   cactus  cactus0 -> cactus1, K = 8, ring around the vertex of
#           cactus_bottom_mask.txt nearest to that mask's centroid
# and five cases of the stress corpus (bench/stress_corpus.sh) that
# shellspace's defaults do not converge on, as a masked problem both
# programs can solve: the cgal mesh and its pose by bench/stress_pose
# without the rigid motion (a geodesic does not depend on it), K = 8, the
# ring around the vertex that moves least, eta = 1e-4 x the start's area
# (shellspace's default relative_eta; GOAST's bendWeight is 3 eta):
#   bull_bend120, triceratops_pull0.15, ChineseDragon_twist180,
#   ChineseDragon_twist60, triceratops_bend120
# shellspace runs them twice, as GOAST (--init linear --multires off) and
# with its defaults otherwise (ss_<problem>_defaults).
# Shooting (EXP) the same way, on the corpus poses whose shoots shellspace
# does not solve from a converged geodesic (exp_ChineseDragon_bend75,
# exp_ChineseDragon_bend120): shellspace's masked geodesic (defaults) gives
# s_0 and s_1; from them shellspace's `shoot --steps 8` and GOAST's example
# extrapolationShells (examples/geodesic_extrapolation_shells.cpp, a copy
# reading its inputs from argv: Newton from s_k, 50 steps, tolerance 1e-8
# on its gradient norm) each extrapolate 7 steps with the same mask and
# weights. Their own table lists, per EXP step, whether it was solved and
# the Newton steps it took.
# GOAST runs with OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1; shellspace with
# --tolerance 1e-10 and its default, each with one thread and with the
# default threads. shellspace also runs on the inputs rounded to float32,
# which is what GOAST computes with (OpenMesh reads PLY coordinates as float).
# Every run under /usr/bin/time -v with the load average before it.
#
# Usage: bench/goast_side_by_side.sh GOAST_SRC [BUILD_DIR] [OUT_DIR]
#   GOAST_SRC  a GOAST checkout (its CMakeLists.txt, include/, examples/)
#   BUILD_DIR  shellspace's build directory (default build; uses
#              BUILD_DIR/shellspace)
#   OUT_DIR    default a new temporary directory (GOAST's build in
#              OUT_DIR/goast-build, frames, logs)
# Environment: GOAST_EXTRA_PROBLEMS (more corpus-style problems, each
# MESH_FILE:KIND:STRENGTH with an absolute path, e.g.
# /tmp/meshes/man.off:bend:75, named by the file's name up to its first
# "-": man_bend75), GOAST_BUILD (GOAST's build directory, default
# OUT_DIR/goast-build), GOAST_TIMEOUT seconds per GOAST run (default 900;
# a run stopped there is reported partial; shellspace's runs of the corpus
# problems get the same --time_limit), JOBS (default 1), ONLY a regular
# expression of the problems (default finger|cactus; the corpus problems
# by name, e.g. ONLY=bull; the shooting problems with their prefix,
# e.g. ONLY=exp_ChineseDragon_bend75), TABLE_ONLY=1 prints the table of the runs
# already in OUT_DIR.
set -uo pipefail

goast="${1:?usage: bench/goast_side_by_side.sh GOAST_SRC [BUILD_DIR] [OUT_DIR]}"
goast="$(cd "$goast" && pwd)" || exit 1
build="${2:-build}"
cli="$(cd "$(dirname "$build/shellspace")" && pwd)/shellspace"
out="${3:-$(mktemp -d "${TMPDIR:-/tmp}/goast-side-by-side.XXXXXX")}"
mkdir -p "$out" && out="$(cd "$out" && pwd)"
gbuild="${GOAST_BUILD:-$out/goast-build}"
timeout_s="${GOAST_TIMEOUT:-900}"
jobs="${JOBS:-1}"
only="${ONLY:-finger|cactus}"
data="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../shared/data" && pwd)"
python=/usr/bin/python3
[ -x "$cli" ] || { echo "no shellspace CLI at $cli" >&2; exit 1; }
[ -f "$goast/examples/geodesic_interpolation_shells.cpp" ] ||
  { echo "$goast is not a GOAST checkout" >&2; exit 1; }

# --- table -------------------------------------------------------------------
table() {
"$python" - "$out" <<'EOF'
import glob, json, os, re, sys
out = sys.argv[1]
def timing(name):
    t = open(f'{out}/logs/{name}.time').read()
    g = lambda k: re.search(k + r': (.*)', t).group(1).strip()
    wall = g(r'Elapsed \(wall clock\) time \(h:mm:ss or m:ss\)').split(':')
    wall = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall)))
    cpu = float(g('User time \(seconds\)')) + float(g('System time \(seconds\)'))
    rss = int(g('Maximum resident set size \(kbytes\)')) / 1024
    load = open(f'{out}/logs/{name}.load').read()
    load1 = re.search(r'load average: ([0-9.]+)', load).group(1)
    rc = re.search(r'rc=(\d+)', load).group(1)
    return wall, cpu, rss, load1, rc
print('| run | wall s | CPU s | peak RSS MB | load | iterations | E_K | own final gradient | gradient of the path by GOAST: 2-norm / max-norm |')
print('|---|---|---|---|---|---|---|---|---|')
names = sorted(os.path.basename(p)[:-5] for p in glob.glob(f'{out}/logs/*.time'))
for name in names:
    if name.startswith('exp_') or name.startswith('tr_'): continue
    wall, cpu, rss, load, rc = timing(name)
    if name.startswith('goast_'):
        o, e = open(f'{out}/logs/{name}.out').read(), open(f'{out}/logs/{name}.err').read()
        gd = re.search(r'Finished gradient descent after (\d+) steps', o)
        gd = gd.group(1) if gd else '?'
        bfgs = re.search(r'Finished BFGS after (\d+) steps', o)
        newton = re.findall(r'-- LSN -- Iter +(\d+):', o)
        its = f'GD {gd}, BFGS {bfgs.group(1) if bfgs else "?"}, Newton {newton[-1] if newton else 0}'
        energy = re.search(r'Final path energy = (\S+)', e)
        grad = re.search(r'Final path energy gradient norm = (\S+)', e)
        state = '' if rc == '0' else f' (stopped, rc {rc})'
        print(f'| {name}{state} | {wall:.1f} | {cpu:.1f} | {rss:.0f} | {load} | {its} | '
              f'{energy.group(1) if energy else "-"} | 2-norm {grad.group(1) if grad else "-"} | |')
    else:
        try: s = json.load(open(f'{out}/logs/{name}.out'))
        except Exception: print(f'| {name} | {wall:.1f} | {cpu:.1f} | {rss:.0f} | {load} | rc {rc} | | | |'); continue
        its = ' + '.join(f"{x['method'][:6]} {x['iterations']}" for x in s['stages'])
        check = ''
        p = f'{out}/logs/{name}.pathcheck'
        if os.path.exists(p):
            try:
                c = json.load(open(p)); check = f"{c['gradient_norm2']:.2e} / {c['gradient_maxnorm']:.2e}"
            except Exception: check = 'pathcheck failed'
        print(f"| {name} | {wall:.1f} | {cpu:.1f} | {rss:.0f} | {load} | {its} | {s['path_energy']!r} | "
              f"max {s['final_gradient_norm']:.2e} | {check} |")
# GOAST's Newton solves in `text`: (steps, reached its tolerance, final norm).
# Some of its solvers print the tolerance with two decimals ("tol = 0.00"):
# the tolerance is then taken as GOAST's default, 1e-8.
NEWTON = re.compile(r"Finished Newton's method after (\d+) steps \(max\. steps = \d+, tol = (\S+)\)\.\s*"
                    r"Final stepsize = \S+, final norm = (\S+)")
def newton_solves(text):
    return [(int(n), float(r) <= max(float(t), 1e-8), float(r)) for n, t, r in NEWTON.findall(text)]
# One table of solves per run: each solve (an EXP step, a transport rung)
# solved or not, its Newton steps and final residual.
def solve_table(prefix, geo_prefix, header, solves_of, total=None):
    runs = [n for n in names if n.startswith(prefix) and not n.startswith(geo_prefix)]
    if not runs: return
    print()
    print(header)
    print('|---|---|---|---|---|---|---|---|')
    for name in runs:
        wall, cpu, rss, load, rc = timing(name)
        steps = solves_of(name)
        solved = sum(1 for _, ok, _ in steps if ok)
        cells = ', '.join(f"{n}{'' if ok else ' (no)'} / {r:.1e}" for n, ok, r in steps)
        print(f'| {name} | {wall:.1f} | {cpu:.1f} | {rss:.0f} | {load} | {rc} | {solved} of {total or len(steps)} | {cells} |')
def shellspace_json(name, key, fields):
    try: s = json.load(open(f'{out}/logs/{name}.out'))
    except Exception: return []
    return [fields(x) for x in s[key]]
# Shooting: per EXP step s_2 ... s_8, solved or not and its Newton steps.
def shooting_solves(name):
    if name.startswith('exp_goast_'):
        return newton_solves(open(f'{out}/logs/{name}.out').read())
    return shellspace_json(name, 'stages', lambda x: (x['iterations'], x['solved'], x['relative_residual']))
solve_table('exp_', 'exp_geo_', '| shooting run | wall s | CPU s | peak RSS MB | load | exit | EXP steps solved | per step: Newton steps (no: not solved) / final residual (GOAST: its gradient 2-norm; shellspace: relative to the scale of F) |', shooting_solves)
# Transport: per rung, solved or not (GOAST: every Newton solve of the rung
# -- the midpoint's and the EXP step's -- reached its tolerance).
def transport_solves(name):
    if not name.startswith('tr_goast_'):
        return shellspace_json(name, 'rungs', lambda x: (x['newton_steps'] + x['lm_iterations'], x['solved'], x['relative_residual']))
    o = open(f'{out}/logs/{name}.out').read() + open(f'{out}/logs/{name}.err').read()
    rungs = []
    for part in re.split(r'^rung \d+$', o, flags=re.M)[1:]:
        solves = newton_solves(part)
        if solves:
            rungs.append((sum(n for n, _, _ in solves), all(ok for _, ok, _ in solves), solves[-1][2]))
    return rungs
solve_table('tr_', 'tr_geo_', "| transport run | wall s | CPU s | peak RSS MB | load | exit | rungs solved | per rung: Newton steps (no: not solved) / final residual (GOAST: the EXP step's gradient 2-norm; shellspace: relative to the scale of F) |", transport_solves, 8)
EOF
}
if [ -n "${TABLE_ONLY:-}" ]; then table; exit 0; fi

# --- GOAST: the example, its command-line copy and pathcheck ---------------
mkdir -p "$gbuild" "$out/logs" "$out/runs"
cmake -S "$goast" -B "$gbuild" -DCMAKE_BUILD_TYPE=Release \
  -DGOAST_BUILD_TESTS=OFF -DGOAST_BUILD_TOOLS=OFF -DGOAST_BUILD_EXAMPLES=ON \
  -DGOAST_WITH_IPOPT=OFF -DGOAST_WITH_ADOLC=OFF -DGOAST_WITH_TRLIB=OFF \
  -DGOAST_WITH_MOSEK=OFF -DGOAST_WITH_VTK=OFF > "$out/logs/goast_cmake.log" 2>&1 ||
  { echo "GOAST cmake failed: $out/logs/goast_cmake.log" >&2; exit 1; }
nice -n 10 cmake --build "$gbuild" -j"$jobs" --target interpolationShells \
  > "$out/logs/goast_build.log" 2>&1 ||
  { echo "GOAST build failed: $out/logs/goast_build.log" >&2; exit 1; }

side="$gbuild/side_by_side"
mkdir -p "$side"
# Exit unless every substitution of a copy below took (GOAST's example
# changed otherwise).
require_argv() {
  local pattern
  for pattern in 'argv\[1\]' 'argv\[2\]' 'argv\[3\]' 'argv\[5\]' 'argv\[6\]' 'argv\[7\]'; do
    grep -q "$pattern" "$1" ||
      { echo "GOAST's example changed: $pattern not substituted in $1" >&2; exit 1; }
  done
}
# The example with its inputs from argv (a sed script over the authors' file).
sed -e 's|"../../data/finger/finger0.ply"|argv[1]|' \
    -e 's|"../../data/finger/finger1.ply"|argv[2]|' \
    -e 's|double bendWeight = 0.001;|double bendWeight = std::stod(argv[6]);|' \
    -e 's|int length = 5;|int length = std::stoi(argv[5]);|' \
    -e 's|getVertexNRingVertices( 10, 1302,  indices )|getVertexNRingVertices( std::stoi(argv[4]), std::stoi(argv[3]), indices )|' \
    -e 's|interpolationOp.execute( "fingerInterpolation"|std::cerr << std::setprecision(17); interpolationOp.execute( argv[7]|' \
    -e 's|#include <string>|#include <string>\n#include <iomanip>|' \
    "$goast/examples/geodesic_interpolation_shells.cpp" > "$side/interpolation_args.cpp"
require_argv "$side/interpolation_args.cpp"
# The extrapolation example with its inputs from argv.
sed -e 's|"../../data/finger/finger0.ply"|argv[1]|' \
    -e 's|"../../data/finger/finger_var.ply"|argv[2]|' \
    -e 's|double bendWeight = 0.001;|double bendWeight = std::stod(argv[5]);|' \
    -e 's|int numShootingSteps = 3;|int numShootingSteps = std::stoi(argv[6]);|' \
    -e 's|getVertexNRingVertices( 10, 1302,  indices )|getVertexNRingVertices( std::stoi(argv[4]), std::stoi(argv[3]), indices )|' \
    -e 's|"fingerExtrapolation"|argv[7]|' \
    "$goast/examples/geodesic_extrapolation_shells.cpp" > "$side/extrapolation_args.cpp"
require_argv "$side/extrapolation_args.cpp"
cat > "$side/side_io.h" <<'EOF'
// What the programs of the side-by-side share: GOAST's shell deformation
// and a reader of shellspace's PLY frames in double precision.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <goast/Core.h>
#include <goast/DiscreteShells.h>
#include <goast/GeodesicCalculus.h>
typedef ShellDeformation<DefaultConfigurator, NonlinearMembraneDeformation<DefaultConfigurator>,
                         SimpleBendingDeformation<DefaultConfigurator> > Deformation;
typedef DefaultConfigurator::VectorType VectorType;
// OpenMesh rounds PLY coordinates to float: read them here (GOAST's x..., y..., z... layout).
static bool ReadCoordinates(const std::string& path, VectorType& geom) {
  std::ifstream in(path); std::string line; long nv = -1;
  while (std::getline(in, line)) {
    if (line.rfind("element vertex", 0) == 0) nv = std::stol(line.substr(15));
    if (line == "end_header") break;
  }
  if (nv <= 0) return false;
  geom.resize(3 * nv);
  for (long i = 0; i < nv; ++i) {
    double x, y, z;
    if (!std::getline(in, line) || !(std::istringstream(line) >> x >> y >> z)) return false;
    geom[i] = x; geom[nv + i] = y; geom[2 * nv + i] = z;
  }
  return true;
}
// Frame k of a path directory written by shellspace.
static std::string FramePath(const std::string& dir, int k) {
  char name[32]; snprintf(name, sizeof name, "/shape_%03d.ply", k);
  return dir + name;
}
EOF
cat > "$side/transport_args.cpp" <<'EOF'
// Schild's ladder of GOAST (parTranspSingleStepShort, one call per rung) along
// a path written by shellspace: transport_args DIR K VARIATION centre ring
// bendWeight OUT. Prints "rung k" before each rung; GOAST prints its solvers'
// termination lines. The last transported shape goes to OUT.
#include "side_io.h"
int main(int argc, char** argv) {
  if (argc != 8) { fprintf(stderr, "usage: transport_args DIR K VARIATION centre ring bendWeight OUT\n"); return 2; }
  const std::string dir = argv[1]; const int K = std::stoi(argv[2]);
  TriMesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, FramePath(dir, 0))) { fprintf(stderr, "cannot read %s\n", dir.c_str()); return 1; }
  std::vector<VectorType> frames(K + 1);
  for (int k = 0; k <= K; ++k) {
    if (!ReadCoordinates(FramePath(dir, k), frames[k])) { fprintf(stderr, "cannot read frame %d\n", k); return 1; }
  }
  VectorType variation;
  if (!ReadCoordinates(argv[3], variation)) { fprintf(stderr, "cannot read %s\n", argv[3]); return 1; }
  MeshTopologySaver topology(mesh);
  Deformation W(topology, std::stod(argv[6]));
  std::vector<int> mask;
  topology.getVertexNRingVertices(std::stoi(argv[5]), std::stoi(argv[4]), mask);
  extendBoundaryMask(topology.getNumVertices(), mask);
  OptimizationParameters<DefaultConfigurator> parameters;
  parameters.setGradientIterations(250);
  parameters.setBFGSIterations(0);
  parameters.setNewtonIterations(25);
  parameters.setInitializationScheme(2);
  parameters.setQuietMode(SHOW_TERMINATION_INFO);
  for (int k = 0; k < K; ++k) {
    std::cout << "rung " << k + 1 << std::endl;
    VectorType next;
    parTranspSingleStepShort<DefaultConfigurator>(topology, frames[k], frames[k + 1], variation, mask, W,
                                                  parameters, next, false);
    variation = next;
  }
  setGeometry(mesh, variation);
  OpenMesh::IO::write_mesh(mesh, argv[7]);
  return 0;
}
EOF
cat > "$side/pathcheck.cpp" <<'EOF'
// GOAST's E_K and masked gradient of a path DIR/shape_000.ply ... shape_K.ply.
#include "side_io.h"
int main(int argc, char** argv) {
  if (argc != 6) { fprintf(stderr, "usage: pathcheck DIR K centre ring bendWeight\n"); return 2; }
  const std::string dir = argv[1]; const int K = std::stoi(argv[2]);
  std::vector<VectorType> frames(K + 1); TriMesh mesh;
  for (int k = 0; k <= K; ++k) {
    const std::string name = FramePath(dir, k);
    if ((k == 0 && !OpenMesh::IO::read_mesh(mesh, name)) || !ReadCoordinates(name, frames[k])) {
      fprintf(stderr, "cannot read %s\n", name.c_str()); return 1;
    }
  }
  MeshTopologySaver topology(mesh);
  const int n = frames[0].size();
  VectorType path((K - 1) * n);
  for (int k = 1; k < K; ++k) path.segment((k - 1) * n, n) = frames[k];
  Deformation W(topology, std::stod(argv[5]));
  double energy; VectorType grad;
  DiscretePathEnergy<DefaultConfigurator>(W, K, frames[0], frames[K]).apply(path, energy);
  DiscretePathEnergyGradient<DefaultConfigurator>(W, K, frames[0], frames[K]).apply(path, grad);
  std::vector<int> ring, mask;
  topology.getVertexNRingVertices(std::stoi(argv[4]), std::stoi(argv[3]), ring);
  const size_t ring_size = ring.size();
  extendBoundaryMask(topology.getNumVertices(), ring);
  fillPathMask(K - 1, n, ring, mask);
  applyMaskToVector<VectorType>(mask, grad);
  printf("{\"mask_vertices\": %zu, \"path_energy\": %.17g, \"gradient_norm2\": %.6e, \"gradient_maxnorm\": %.6e}\n",
         ring_size, energy, grad.norm(), grad.lpNorm<Eigen::Infinity>());
  return 0;
}
EOF
cat > "$side/CMakeLists.txt" <<EOF
cmake_minimum_required(VERSION 3.5)
project(goast_side_by_side CXX)
set(CMAKE_CXX_STANDARD 14)
include("$goast/cmake/GOAST.cmake")
add_executable(interpolation_args interpolation_args.cpp)
target_link_libraries(interpolation_args PRIVATE GOAST::GOAST)
add_executable(extrapolation_args extrapolation_args.cpp)
target_link_libraries(extrapolation_args PRIVATE GOAST::GOAST)
add_executable(pathcheck pathcheck.cpp)
target_link_libraries(pathcheck PRIVATE GOAST::GOAST)
add_executable(transport_args transport_args.cpp)
target_link_libraries(transport_args PRIVATE GOAST::GOAST)
EOF
cmake -S "$side" -B "$side/build" -DCMAKE_BUILD_TYPE=Release \
  -DGOAST_WITH_IPOPT=OFF -DGOAST_WITH_ADOLC=OFF -DGOAST_WITH_TRLIB=OFF \
  -DGOAST_WITH_MOSEK=OFF -DGOAST_WITH_VTK=OFF > "$out/logs/side_cmake.log" 2>&1 &&
nice -n 10 cmake --build "$side/build" -j"$jobs" > "$out/logs/side_build.log" 2>&1 ||
  { echo "building the GOAST programs failed: $out/logs/side_*.log" >&2; exit 1; }
goast_run="$side/build/interpolation_args"
goast_exp="$side/build/extrapolation_args"
pathcheck="$side/build/pathcheck"
goast_transport="$side/build/transport_args"

# --- the corpus problems' meshes -----------------------------------------
corpus=() exp_corpus=() tr_corpus=()
for entry in bull:bend:120 triceratops:pull:0.15 ChineseDragon-10kv:twist:180 \
    ChineseDragon-10kv:twist:60 triceratops:bend:120 \
    exp:ChineseDragon-10kv:bend:75 exp:ChineseDragon-10kv:bend:120 \
    tr:ChineseDragon-10kv:twist:180 ${GOAST_EXTRA_PROBLEMS:-}; do
  exp=""
  [[ "$entry" == exp:* ]] && exp="exp_" entry="${entry#exp:}"
  [[ "$entry" == tr:* ]] && exp="tr_" entry="${entry#tr:}"
  IFS=: read -r mesh kind strength <<<"$entry"
  file="$data/cgal/$mesh.off"
  if [[ "$mesh" == /* ]]; then file="$mesh" mesh="$(basename "${mesh%.*}")"; fi
  problem="${mesh%%-*}_${kind}${strength}"
  [[ "$exp$problem" =~ $only ]] || continue
  pose="$(dirname "$cli")/bench/stress_pose"
  [ -x "$pose" ] || { echo "no $pose (build the target stress_pose)" >&2; exit 1; }
  "$pose" "$file" none 0 0 "$out/${problem}0.ply" norigid &&
  "$pose" "$file" "$kind" "$strength" 0 "$out/${problem}1.ply" norigid ||
    { echo "stress_pose failed on $mesh" >&2; exit 1; }
  case "$exp" in
    exp_) exp_corpus+=("$problem") ;;
    tr_) tr_corpus+=("$problem") ;;
    *) corpus+=("$problem") ;;
  esac
done

# --- masks, centre vertices and float32 copies of the inputs ---------------
"$python" - "$data" "$out" "${corpus[@]}" "${exp_corpus[@]}" "${tr_corpus[@]}" <<'EOF' || exit 1
import sys
from collections import deque
data, out = sys.argv[1], sys.argv[2]
def read_ply(path):
    lines = open(path).read().split('\n'); i = 0; nv = nf = 0
    while lines[i] != 'end_header':
        if lines[i].startswith('element vertex'): nv = int(lines[i].split()[2])
        if lines[i].startswith('element face'): nf = int(lines[i].split()[2])
        i += 1
    i += 1
    V = [[float(x) for x in lines[i + k].split()[:3]] for k in range(nv)]
    F = [[int(x) for x in lines[i + nv + k].split()[1:4]] for k in range(nf)]
    return V, F
def ring(F, nv, centre, n):  # vertices within n edges of centre
    adj = [set() for _ in range(nv)]
    for a, b, c in F:
        adj[a] |= {b, c}; adj[b] |= {a, c}; adj[c] |= {a, b}
    dist = {centre: 0}; q = deque([centre])
    while q:
        u = q.popleft()
        if dist[u] < n:
            for w in adj[u]:
                if w not in dist: dist[w] = dist[u] + 1; q.append(w)
    return sorted(dist)
def write_float32(src, dst):
    import struct
    V, F = read_ply(src)
    r = lambda x: struct.unpack('f', struct.pack('f', x))[0]
    with open(dst, 'w') as f:
        f.write('ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\n'
                'property double y\nproperty double z\nelement face %d\n'
                'property list uchar int vertex_index\nend_header\n' % (len(V), len(F)))
        for v in V: f.write('%.17g %.17g %.17g\n' % tuple(r(x) for x in v))
        for t in F: f.write('3 %d %d %d\n' % tuple(t))
V, F = read_ply(data + '/finger/finger0.ply')
open(out + '/finger.centre', 'w').write('1302\n')
open(out + '/finger_mask.txt', 'w').write(''.join('%d\n' % i for i in ring(F, len(V), 1302, 10)))
V, F = read_ply(data + '/cactus/cactus0.ply')
bottom = [int(l) for l in open(data + '/cactus/cactus_bottom_mask.txt')
          if l.strip() and not l.startswith('#')]
c = [sum(V[i][j] for i in bottom) / len(bottom) for j in range(3)]
centre = min(bottom, key=lambda i: sum((V[i][j] - c[j]) ** 2 for j in range(3)))
open(out + '/cactus.centre', 'w').write('%d\n' % centre)
open(out + '/cactus_mask.txt', 'w').write(''.join('%d\n' % i for i in ring(F, len(V), centre, 10)))
for name in ('finger/finger0', 'finger/finger1', 'cactus/cactus0', 'cactus/cactus1'):
    write_float32(data + '/' + name + '.ply', out + '/' + name.split('/')[1] + '_f32.ply')
def cross(u, v): return [u[1]*v[2]-u[2]*v[1], u[2]*v[0]-u[0]*v[2], u[0]*v[1]-u[1]*v[0]]
for problem in sys.argv[3:]:  # corpus problems: the ring where the pose moves least
    A, F = read_ply(f'{out}/{problem}0.ply')
    B, _ = read_ply(f'{out}/{problem}1.ply')
    centre = min(range(len(A)), key=lambda i: sum((A[i][j] - B[i][j]) ** 2 for j in range(3)))
    open(f'{out}/{problem}.centre', 'w').write('%d\n' % centre)
    open(f'{out}/{problem}_mask.txt', 'w').write(''.join('%d\n' % i for i in ring(F, len(A), centre, 10)))
    area = 0.0
    for a, b, c in F:
        n = cross([A[b][j] - A[a][j] for j in range(3)], [A[c][j] - A[a][j] for j in range(3)])
        area += 0.5 * sum(x * x for x in n) ** 0.5
    open(f'{out}/{problem}.eta', 'w').write('%.17g\n' % (1e-4 * area))
EOF

# --- runs -------------------------------------------------------------------
timed() {  # NAME command...: NAME.{out,err,time,load}
  local name="$1"; shift
  { uptime; } > "$out/logs/$name.load"
  /usr/bin/time -v -o "$out/logs/$name.time" "$@" \
    > "$out/logs/$name.out" 2> "$out/logs/$name.err"
  echo "rc=$?" >> "$out/logs/$name.load"
}
eta=0.00033333333333333332   # 0.001 / 3
for problem in finger cactus; do
  [[ "$problem" =~ $only ]] || continue
  case "$problem" in
    finger) steps=4 ;;
    cactus) steps=8 ;;
  esac
  centre="$(cat "$out/$problem.centre")"
  a="$data/$problem/${problem}0.ply" b="$data/$problem/${problem}1.ply"
  (cd "$out/runs" && OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
    timed "goast_$problem" timeout "$timeout_s" stdbuf -oL -eL \
      "$goast_run" "$a" "$b" "$centre" 10 $((steps + 1)) 0.001 "goast_$problem")
  common=(geodesic --steps "$steps" --mask "$out/${problem}_mask.txt" --eta "$eta"
          --init linear --multires off --json)
  for tol in 1e-10 default; do
    tflag=(); [ "$tol" = default ] || tflag=(--tolerance "$tol")
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 timed "ss_${problem}_${tol}_1thread" \
      "$cli" "${common[@]}" --start "$a" --end "$b" "${tflag[@]}" --threads 1 \
      --output "$out/runs/ss_${problem}_${tol}_1thread"
    timed "ss_${problem}_${tol}_defaultthreads" \
      "$cli" "${common[@]}" --start "$a" --end "$b" "${tflag[@]}" \
      --output "$out/runs/ss_${problem}_${tol}_defaultthreads"
  done
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 timed "ss_${problem}_f32_1e-10_1thread" \
    "$cli" "${common[@]}" --start "$out/${problem}0_f32.ply" --end "$out/${problem}1_f32.ply" \
    --tolerance 1e-10 --threads 1 --output "$out/runs/ss_${problem}_f32_1e-10_1thread"
  for run in "$out"/runs/ss_"${problem}"_*; do
    [ -d "$run" ] && OMP_NUM_THREADS=1 "$pathcheck" "$run" "$steps" "$centre" 10 0.001 \
      > "$out/logs/$(basename "$run").pathcheck" 2>&1
  done
done

for problem in "${corpus[@]}"; do
  centre="$(cat "$out/$problem.centre")" eta="$(cat "$out/$problem.eta")"
  a="$out/${problem}0.ply" b="$out/${problem}1.ply"
  weight=$("$python" -c "print(repr(3 * float('$eta')))")
  (cd "$out/runs" && OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
    timed "goast_$problem" timeout "$timeout_s" stdbuf -oL -eL \
      "$goast_run" "$a" "$b" "$centre" 10 9 "$weight" "goast_$problem")
  common=(geodesic --steps 8 --mask "$out/${problem}_mask.txt" --eta "$eta" --json
          --time_limit "$timeout_s" --start "$a" --end "$b")
  timed "ss_${problem}_as_goast" "$cli" "${common[@]}" --init linear --multires off \
    --output "$out/runs/ss_${problem}_as_goast"
  timed "ss_${problem}_defaults" "$cli" "${common[@]}" \
    --output "$out/runs/ss_${problem}_defaults"
  for run in "$out"/runs/ss_"${problem}"_*; do
    [ -d "$run" ] && OMP_NUM_THREADS=1 "$pathcheck" "$run" 8 "$centre" 10 "$weight" \
      > "$out/logs/$(basename "$run").pathcheck" 2>&1
  done
done

for problem in "${exp_corpus[@]}"; do
  centre="$(cat "$out/$problem.centre")" eta="$(cat "$out/$problem.eta")"
  weight=$("$python" -c "print(repr(3 * float('$eta')))")
  geo="$out/runs/exp_geo_$problem"
  timed "exp_geo_$problem" "$cli" geodesic --steps 8 --mask "$out/${problem}_mask.txt" \
    --eta "$eta" --json --time_limit "$timeout_s" --start "$out/${problem}0.ply" \
    --end "$out/${problem}1.ply" --output "$geo"
  [ -f "$geo/shape_001.ply" ] || { echo "no geodesic for exp_$problem: $out/logs/exp_geo_$problem.err" >&2; continue; }
  (cd "$out/runs" && OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
    timed "exp_goast_$problem" timeout "$timeout_s" stdbuf -oL -eL \
      "$goast_exp" "$geo/shape_000.ply" "$geo/shape_001.ply" "$centre" 10 "$weight" 7 "exp_goast_$problem")
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 timed "exp_ss_$problem" "$cli" shoot \
    --first "$geo/shape_000.ply" --second "$geo/shape_001.ply" --steps 8 \
    --mask "$out/${problem}_mask.txt" --eta "$eta" --json --time_limit "$timeout_s" \
    --threads 1 --output "$out/runs/exp_ss_$problem"
done

for problem in "${tr_corpus[@]}"; do
  centre="$(cat "$out/$problem.centre")" eta="$(cat "$out/$problem.eta")"
  weight=$("$python" -c "print(repr(3 * float('$eta')))")
  geo="$out/runs/tr_geo_$problem"
  timed "tr_geo_$problem" "$cli" geodesic --steps 8 --mask "$out/${problem}_mask.txt" \
    --eta "$eta" --json --time_limit "$timeout_s" --start "$out/${problem}0.ply" \
    --end "$out/${problem}1.ply" --output "$geo"
  [ -f "$geo/shape_001.ply" ] || { echo "no geodesic for tr_$problem: $out/logs/tr_geo_$problem.err" >&2; continue; }
  variation="$out/${problem}_variation.ply"
  "$(dirname "$cli")/bench/stress_pose" "$geo/shape_000.ply" pull 0.02 0 "$variation" norigid ||
    { echo "stress_pose failed on $geo/shape_000.ply" >&2; continue; }
  (cd "$out/runs" && OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
    timed "tr_goast_$problem" timeout "$timeout_s" stdbuf -oL -eL \
      "$goast_transport" "$geo" 8 "$variation" "$centre" 10 "$weight" "tr_goast_$problem.ply")
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 timed "tr_ss_$problem" "$cli" transport \
    --path "$geo" --variation "$variation" --mask "$out/${problem}_mask.txt" --eta "$eta" \
    --json --time_limit "$timeout_s" --threads 1 --output "$out/runs/tr_ss_$problem"
done

table
echo "outputs and logs: $out"
