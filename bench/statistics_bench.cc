// The statistics workloads of issue 4, one run each (heavy: not part of the
// test suite): the elastic mean of the 4 faces (7118 vertices), and one
// leave-one-out fold of the shell-vs-Procrustes PCA evaluation over the 19
// cactus poses (cactus0 held out, m = 0..5, LOG_2/EXP_2 displacements; every
// LM solve capped at 30 iterations: the elastic-mean and LOG solves of the
// cactus converge only linearly, a large-residual least-squares problem).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "geometry/mesh_io.h"
#include "geometry/topology.h"
#include "problems/elastic_mean.h"
#include "problems/leave_one_out.h"

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
  for (auto _ : state) {
    const ElasticMeanResult result =
        ComputeElasticMean(space, shapes, SolverSettings{});
    const auto& s = result.summary;
    state.counters["energy"] = result.energy;
    state.counters["iterations"] = static_cast<double>(s.iterations.size());
    state.counters["converged"] =
        s.termination_type == ceres::CONVERGENCE ? 1 : 0;
    state.counters["linear_solver_s"] = s.linear_solver_time_in_seconds;
    state.counters["jacobian_s"] = s.jacobian_evaluation_time_in_seconds;
  }
}
BENCHMARK(BM_FaceElasticMean)->Iterations(1)->Unit(benchmark::kSecond);

void BM_CactusLeaveOneOutFold(benchmark::State& state) {
  std::vector<Positions> shapes;
  Mesh first;
  for (int i = 0; i < 19; ++i) {
    Mesh mesh = ReadMesh(Data("cactus/cactus" + std::to_string(i) + ".ply"));
    if (i == 0) first = mesh;
    shapes.push_back(mesh.positions);
  }
  const ShellSpace space(first, Topology::Build(first), ShellMaterial{});
  LeaveOneOutOptions options;
  options.max_modes = 5;
  options.held_out = {static_cast<int>(state.range(0))};
  SolverSettings settings;
  settings.max_iterations = 30;
  for (auto _ : state) {
    const LeaveOneOutTable table =
        EvaluateLeaveOneOut(space, shapes, options, settings);
    const LeaveOneOutFold& fold = table.folds[0];
    state.counters["mean_iterations"] = fold.mean_iterations;
    state.counters["mean_energy"] = fold.mean_energy;
    for (int m : {1, 5}) {
      const std::string suffix = "_m" + std::to_string(m);
      state.counters["shell_err" + suffix] = fold.shell_vertex_error[m];
      state.counters["shell_W" + suffix] = fold.shell_energy[m];
      state.counters["procrustes_err" + suffix] =
          fold.procrustes_vertex_error[m];
      state.counters["procrustes_W" + suffix] = fold.procrustes_energy[m];
    }
  }
}
BENCHMARK(BM_CactusLeaveOneOutFold)
    ->Arg(0)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

BENCHMARK_MAIN();
