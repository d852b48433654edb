// LΘA spline timing: the spline through cactus0, cactus6, cactus12,
// cactus18 at 0, 2, 4, 6 with K = 6 (natural ends; periodic:0), and the closed
// variant with K = 8 (periodic:1), default solver settings.
// One run; reports the spline and reconstruction times, LM iterations per
// frame and the final LΘA cost of each reconstructed frame.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/problems/splines/ltheta_spline.h"

namespace shellspace {
namespace {

std::string Data(const std::string& name) {
  return std::string(SHELLSPACE_DATA_DIR) + "/" + name;
}

void BM_CactusLThetaSpline(benchmark::State& state) {
  const std::vector<std::string> names = {"cactus0", "cactus6", "cactus12",
                                          "cactus18"};
  std::vector<Mesh> meshes;
  for (const auto& name : names) {
    const std::string path = Data("cactus/" + name + ".ply");
    meshes.push_back(ReadMesh(path));
    ValidateShell(meshes.back(), path);
    if (meshes.size() > 1) {
      CheckCompatible(meshes.front(), names.front(), meshes.back(), name);
    }
  }
  const Topology topology = ValidateShell(meshes.front(), names.front());
  const ShellSpace space(meshes.front(), topology, ShellMaterial{});
  std::vector<Positions> keyframes;
  for (const Mesh& mesh : meshes) keyframes.push_back(mesh.positions);
  const std::vector<int> at = {0, 2, 4, 6};
  // Periodic: K = 8 (index 6 < K), frame 7 closes cactus18 -> cactus0.
  const bool periodic = state.range(0) != 0;
  const int steps = periodic ? 8 : 6;
  LThetaSplineReport report;
  for (auto _ : state) {
    const ShellPath path = LThetaSpline(space, keyframes, at, steps, periodic,
                                        SolverSettings{}, &report);
    benchmark::DoNotOptimize(path.data());
  }
  state.counters["vertices"] = space.num_vertices;
  state.counters["spline_s"] = report.spline_seconds;
  state.counters["solve_s"] = report.solve_seconds;
  for (size_t n = 0; n < report.solved_frames.size(); ++n) {
    const std::string frame = std::to_string(report.solved_frames[n]);
    const ceres::Solver::Summary& s = report.summaries[n];
    state.counters["iter_" + frame] = static_cast<double>(s.iterations.size());
    state.counters["cost_" + frame] = s.final_cost;
    state.counters["s_" + frame] = s.total_time_in_seconds;
    state.counters["pre_s_" + frame] = s.preprocessor_time_in_seconds;
    state.counters["lin_s_" + frame] = s.linear_solver_time_in_seconds;
    state.counters["jac_s_" + frame] = s.jacobian_evaluation_time_in_seconds;
  }
}
BENCHMARK(BM_CactusLThetaSpline)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("periodic")
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

