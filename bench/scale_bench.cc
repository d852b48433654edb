// Geodesic interpolation at production scale: K = 8, from the linear path to a
// relative gradient of 1e-8, one run per case, each with multiresolution off
// (levels:0) or on.
//
//   finger_ring   finger0 -> finger1, a 10-ring mask around the base vertex
//                 nearest the centroid of finger_mask.txt, eta = 3.3e-4
//   cactus_ring   cactus0 -> cactus1, a 10-ring mask around the bottom
//                 vertex nearest the centroid of cactus_bottom_mask.txt,
//                 eta = 3.3e-4
//   cactus_bottom cactus0 -> cactus1, cactus_bottom_mask.txt, eta = 0.001
//   faces         neutral -> smile, no mask (rigid gauge), eta = 0.01
//   cactus_x4     the cactus pair midpoint-subdivided once (21,038
//                 vertices), bottom mask carried to the new vertices
//   cactus_x16    subdivided twice (84,146 vertices)
//
// Benchmarks are named Scale/case:C/levels:L, C the index in the list above
// (0 finger_ring ... 5 cactus_x16). Run one case at a time under
// /usr/bin/time -v for wall, CPU and peak RSS:
// SHELLSPACE_LM=auto|ceres|engine chooses who runs the LM stages
// (GeodesicLm; default auto).
//   OPENBLAS_NUM_THREADS=1 /usr/bin/time -v build/bench/scale_bench \
//       --benchmark_filter='Scale/case:1/levels:1/'
// The environment variable SHELLSPACE_LINEAR_SOLVER=auto|direct|block-jacobi
// forces the linear solver of the Newton finish (default auto; see
// PathLinearSolver); the counter block_jacobi is 1 if block-Jacobi CG ran.
// SHELLSPACE_NEWTON_FROM sets GeodesicInput::newton_from (1: no LM stage).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "shellspace/geometry/subdivision.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/workflows/solve_choice_words.h"

namespace shellspace {
namespace {

std::string Data(const std::string& name) {
  return std::string(SHELLSPACE_DATA_DIR) + "/" + name;
}

// The vertex of `mask` nearest to the mask's centroid (in `mesh`).
int CentralMaskVertex(const Mesh& mesh, const std::vector<int>& mask) {
  Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
  for (int v : mask) centroid += mesh.positions.row(v) / double(mask.size());
  int best = mask.front();
  for (int v : mask) {
    if ((mesh.positions.row(v) - centroid).squaredNorm() <
        (mesh.positions.row(best) - centroid).squaredNorm()) {
      best = v;
    }
  }
  return best;
}

struct Case {
  Mesh a, b;
  std::vector<int> mask;
  double eta = 0.01;
};

Case MakeCase(const std::string& name) {
  Case c;
  if (name == "finger_ring") {
    c.a = ReadMesh(Data("finger/finger0.ply"));
    c.b = ReadMesh(Data("finger/finger1.ply"));
    const int seed = CentralMaskVertex(
        c.a, ReadMask(Data("finger/finger_mask.txt"), c.a.num_vertices()));
    c.mask = VertexRing(c.a.faces, c.a.num_vertices(), seed, 10);
    c.eta = 3.3e-4;
  } else if (name == "faces") {
    c.a = ReadMesh(Data("faces/neutral.ply"));
    c.b = ReadMesh(Data("faces/smile.ply"));
  } else {
    c.a = ReadMesh(Data("cactus/cactus0.ply"));
    c.b = ReadMesh(Data("cactus/cactus1.ply"));
    const std::vector<int> bottom =
        ReadMask(Data("cactus/cactus_bottom_mask.txt"), c.a.num_vertices());
    c.eta = 0.001;
    c.mask = bottom;
    if (name == "cactus_ring") {
      c.mask = VertexRing(c.a.faces, c.a.num_vertices(),
                          CentralMaskVertex(c.a, bottom), 10);
      c.eta = 3.3e-4;
    }
    const int subdivisions = name == "cactus_x4"    ? 1
                             : name == "cactus_x16" ? 2
                                                    : 0;
    for (int s = 0; s < subdivisions; ++s) {
      const MidpointSubdivision sub(c.a.faces, c.a.num_vertices());
      c.a = Mesh{sub.Apply(c.a.positions), sub.faces};
      c.b = Mesh{sub.Apply(c.b.positions), sub.faces};
      c.mask = sub.CarryMask(c.mask);
    }
  }
  return c;
}

// The word of the environment variable `variable`, "auto" if it is unset or
// empty.
std::string ChoiceFromEnvironment(const char* variable) {
  const char* value = std::getenv(variable);
  return value && *value ? value : "auto";
}

const char* kCases[] = {"finger_ring", "cactus_ring", "cactus_bottom",
                        "faces",       "cactus_x4",   "cactus_x16"};

void BM_Scale(benchmark::State& state) {
  const std::string name = kCases[state.range(0)];
  const int levels = static_cast<int>(state.range(1));
  const Case c = MakeCase(name);
  const ShellSpace space(c.a, Topology::Build(c.a),
                         ShellMaterial{1.0, 1.0, c.eta});
  GeodesicInput input = GeodesicInput::Between(c.a.positions, c.b.positions, 8);
  input.fixed_vertices = c.mask;
  // SHELLSPACE_LINEAR_SOLVER (auto|direct|block-jacobi) and SHELLSPACE_LM
  // (auto|ceres|engine: who runs the LM stages), as the CLI's words.
  try {
    input.linear_solver = ParsePathLinearSolver(
        ChoiceFromEnvironment("SHELLSPACE_LINEAR_SOLVER"),
        "SHELLSPACE_LINEAR_SOLVER");
    input.lm = ParseGeodesicLm(ChoiceFromEnvironment("SHELLSPACE_LM"),
                               "SHELLSPACE_LM");
  } catch (const InputError& e) {
    state.SkipWithError(e.what());  // one line, no abort
    return;
  }
  // SHELLSPACE_NEWTON_FROM: GeodesicInput::newton_from (default 1e-3; 1:
  // the Newton finish from the first iteration, no LM stage).
  if (const char* from = std::getenv("SHELLSPACE_NEWTON_FROM")) {
    if (*from) input.newton_from = std::atof(from);
  }
  SolverSettings settings;
  settings.progress = true;
  settings.progress_label = name;
  MultiresolutionSettings multires;
  multires.levels = levels;
  for (auto _ : state) {
    const MultiresolutionResult r =
        SolveGeodesicMultiresolution(space, input, settings, multires);
    const GeodesicResult& g = r.geodesic;
    state.counters["vertices"] = c.a.num_vertices();
    state.counters["fixed"] = static_cast<double>(c.mask.size());
    state.counters["E_K"] = g.path_energy;
    state.counters["iterations"] = g.iterations;
    state.counters["engine_lm"] =
        !g.stages.empty() && g.stages.front().solver != "ceres";
    state.counters["newton_steps"] = g.newton.steps;
    state.counters["factorizations"] = g.newton.factorizations;
    state.counters["time_coupled"] = g.newton.time_coupled_factorizations;
    state.counters["cg_iterations"] = g.newton.cg_iterations;
    state.counters["block_jacobi"] = g.newton.linear_solver == "block-jacobi";
    state.counters["newton_seconds"] = g.newton.seconds;
    state.counters["final_gradient"] = g.final_gradient;
    state.counters["converged"] = r.levels.back().converged;
    state.counters["coarse_iterations"] =
        r.levels.size() > 1 ? r.levels.front().iterations : 0;
    state.counters["coarse_vertices"] = r.levels.front().vertices;
    const auto [lo, hi] =
        std::minmax_element(g.step_energies.begin(), g.step_energies.end());
    state.counters["step_spread"] = *lo > 0 ? *hi / *lo - 1 : 0;
  }
}
BENCHMARK(BM_Scale)
    ->Name("Scale")
    ->ArgNames({"case", "levels"})
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1, 2}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

