// Splines through cactus0, cactus6, cactus12, cactus18 at 0, 2, 4, 6 (K = 6):
// the LΘA spline and the nonlinear spline started from it (L-BFGS, at most
// 30 iterations), with F_K of each. One run.
#include <benchmark/benchmark.h>

#include <chrono>

#include "geometry/mesh_io.h"
#include "problems/ltheta_spline.h"
#include "problems/spline.h"

namespace shellspace {
namespace {

struct CactusKeyframes {
  std::vector<Positions> keyframes;
  Mesh first;
  CactusKeyframes() {
    for (int pose : {0, 6, 12, 18}) {
      Mesh m = ReadMesh(std::string(SHELLSPACE_DATA_DIR) + "/cactus/cactus" +
                        std::to_string(pose) + ".ply");
      if (pose == 0) first = m;
      keyframes.push_back(m.positions);
    }
  }
};

void BM_CactusSplines(benchmark::State& state) {
  CactusKeyframes data;
  const ShellSpace space(data.first, Topology::Build(data.first),
                         ShellMaterial{});
  const std::vector<int> at = {0, 2, 4, 6};
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const ShellPath ltheta =
        LThetaSpline(space, data.keyframes, at, 6, false, SolverSettings{});
    const auto t1 = std::chrono::steady_clock::now();
    SplineSettings settings;
    settings.max_iterations = 0;
    const SplineResult ltheta_energy =
        SolveSpline(space, data.keyframes, at, 6, false, ltheta, settings);
    const auto t2 = std::chrono::steady_clock::now();
    settings.max_iterations = static_cast<int>(state.range(0));
    const SplineResult nonlinear =
        SolveSpline(space, data.keyframes, at, 6, false, ltheta, settings);
    const auto t3 = std::chrono::steady_clock::now();
    state.counters["ltheta_s"] = std::chrono::duration<double>(t1 - t0).count();
    state.counters["F_ltheta"] = ltheta_energy.spline_energy;
    state.counters["F_eval_s"] = std::chrono::duration<double>(t2 - t1).count();
    state.counters["nonlinear_s"] =
        std::chrono::duration<double>(t3 - t2).count();
    state.counters["F_nonlinear"] = nonlinear.spline_energy;
    state.counters["lbfgs_iterations"] =
        static_cast<double>(nonlinear.summary.iterations.size());
  }
}
BENCHMARK(BM_CactusSplines)->Arg(30)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

BENCHMARK_MAIN();
