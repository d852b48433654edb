// The statistics workloads (mean, PCA), one run each, single-threaded (heavy:
// not part of the test suite):
//  - the elastic mean of the 4 faces (7118 vertices), LM alone (arg 0) and LM
//    with the Newton finish (arg 1), both to the default relative gradient
//    tolerance 1e-8;
//  - one leave-one-out fold of the shell-vs-Procrustes PCA evaluation over
//    the 19 cactus poses (arg = the held-out pose, m = 0..5, LOG_2
//    displacements, safeguarded EXP_4 reconstructions, the fold's mean
//    started from the elastic mean of all 19, as the pca verb does). Every
//    LM solve is capped at 30 iterations: the LOG_2 midpoint solves of the
//    cactus have large residuals and LM converges only linearly there;
//    Newton finishes them (geodesic.h); the counters say whether the fold's
//    mean converged (LM chunks + Newton).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"

namespace shellspace {
namespace {

std::string Data(const std::string& name) {
  return std::string(SHELLSPACE_DATA_DIR) + "/" + name;
}

void BM_FaceElasticMean(benchmark::State& state) {
  std::vector<Mesh> meshes;
  for (const char* name : {"neutral", "smile", "disgust", "surprise"}) {
    meshes.push_back(ReadMesh(Data(std::string("faces/") + name + ".ply")));
  }
  std::vector<Positions> shapes;
  for (const Mesh& mesh : meshes) shapes.push_back(mesh.positions);
  const ShellSpace space(meshes[0], Topology::Build(meshes[0]),
                         ShellMaterial{});
  SolverSettings settings;
  settings.num_threads = 1;
  ElasticMeanOptions options;
  options.newton = state.range(0) != 0;
  for (auto _ : state) {
    const ElasticMeanResult result =
        ComputeElasticMean(space, shapes, settings, nullptr, options);
    state.counters["energy"] = result.energy;
    state.counters["lm_iterations"] = result.lm_iterations;
    state.counters["newton_iterations"] = result.newton_iterations;
    state.counters["gradient_max_norm"] = result.gradient_norm;
    state.counters["initial_gradient_max_norm"] = result.initial_gradient_norm;
    state.counters["converged"] = result.converged ? 1 : 0;
  }
}
BENCHMARK(BM_FaceElasticMean)
    ->ArgName("newton")
    ->Arg(0)
    ->Arg(1)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// The cactus poses 0..18 (without cactus8 if asked) and the mesh of cactus0.
struct CactusPoses {
  std::vector<Positions> shapes;
  Mesh first;
  explicit CactusPoses(bool without_pose_8) {
    for (int i = 0; i < 19; ++i) {
      if (without_pose_8 && i == 8) continue;
      Mesh mesh = ReadMesh(Data("cactus/cactus" + std::to_string(i) + ".ply"));
      if (i == 0) first = mesh;
      shapes.push_back(mesh.positions);
    }
  }
};

// The leave-one-out protocol of both benchmarks below: LOG_2, EXP_4 with the
// safeguard up to EXP_16, m = 0..5, one thread, 30 LM iterations per solve
// (plus the Newton finish). As the pca verb, every fold's mean starts from
// the mean of all the poses (one uncapped solve, made here, not timed).
struct CactusLeaveOneOut {
  CactusPoses poses;
  ShellSpace space;
  LeaveOneOutOptions options;
  SolverSettings settings;
  explicit CactusLeaveOneOut(bool without_pose_8)
      : poses(without_pose_8),
        space(poses.first, Topology::Build(poses.first), ShellMaterial{}) {
    options.max_modes = 5;
    options.pca.steps = 2;
    options.pca.exp_steps = 4;
    options.pca.max_exp_steps = 16;
    settings.num_threads = 1;
    options.initial_mean =
        ComputeElasticMean(space, poses.shapes, settings).mean;
    settings.max_iterations = 30;
  }
  LeaveOneOutTable Run() const {
    return EvaluateLeaveOneOut(space, poses.shapes, options, settings);
  }
};

void BM_CactusLeaveOneOutFold(benchmark::State& state) {
  CactusLeaveOneOut loo(state.range(1) != 0);
  loo.options.held_out = {static_cast<int>(state.range(0))};
  for (auto _ : state) {
    const LeaveOneOutTable table = loo.Run();
    const LeaveOneOutFold& fold = table.folds[0];
    state.counters["mean_lm_iterations"] = fold.mean_iterations;
    state.counters["mean_newton_iterations"] = fold.mean_newton_iterations;
    state.counters["mean_converged"] = fold.mean_converged ? 1 : 0;
    state.counters["mean_energy"] = fold.mean_energy;
    state.counters["fold_s"] = fold.seconds;
    int failed_shots = 0, max_exp_steps = 0;
    for (const ExpShotReport& shot : fold.shell_shots) {
      failed_shots += shot.ok ? 0 : 1;
      max_exp_steps = std::max(max_exp_steps, shot.steps);
    }
    state.counters["failed_exp_shots"] = failed_shots;
    state.counters["max_exp_steps"] = max_exp_steps;
    for (int m = 1; m <= 5; ++m) {
      const std::string suffix = "_m" + std::to_string(m);
      state.counters["shell_err" + suffix] = fold.shell_vertex_error[m];
      state.counters["shell_W" + suffix] = fold.shell_energy[m];
      state.counters["procrustes_err" + suffix] =
          fold.procrustes_vertex_error[m];
      state.counters["procrustes_W" + suffix] = fold.procrustes_energy[m];
    }
  }
}
// Args: held-out index, and 1 to leave cactus8 out of the set altogether
// (it has a folded patch of 4 vertices: W[cactus7, cactus8] = 1.62 against
// W[cactus7, cactus9] = 0.063; then index h >= 8 is pose h + 1).
BENCHMARK(BM_CactusLeaveOneOutFold)
    ->ArgNames({"held_out", "without_8"})
    ->Args({0, 0})
    ->Args({8, 0})
    ->Args({0, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Part p of P of the whole leave-one-out evaluation (folds h with h mod P =
// p) over the 19 cactus poses or the 18 without cactus8: one process per
// core runs one part; each fold prints its line (all m) on stderr, the rows
// of the part are counters. Args: p, P, 1 to leave cactus8 out.
void BM_CactusLeaveOneOutPart(benchmark::State& state) {
  CactusLeaveOneOut loo(state.range(2) != 0);
  for (int h = 0; h < static_cast<int>(loo.poses.shapes.size()); ++h) {
    if (h % state.range(1) == state.range(0)) loo.options.held_out.push_back(h);
  }
  loo.options.log = [](const std::string& line) {
    std::fprintf(stderr, "loo: %s\n", line.c_str());
  };
  for (auto _ : state) {
    const LeaveOneOutTable table = loo.Run();
    for (const LeaveOneOutRow& row : table.rows) {
      const std::string m = "_m" + std::to_string(row.modes);
      state.counters["shell_err" + m] = row.shell_vertex_error;
      state.counters["shell_W" + m] = row.shell_energy;
      state.counters["failed" + m] = row.shell_failed;
      state.counters["procrustes_err" + m] = row.procrustes_vertex_error;
      state.counters["procrustes_W" + m] = row.procrustes_energy;
    }
  }
}
BENCHMARK(BM_CactusLeaveOneOutPart)
    ->ArgNames({"part", "of", "without_8"})
    ->Args({0, 2, 0})
    ->Args({1, 2, 0})
    ->Args({0, 2, 1})
    ->Args({1, 2, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

