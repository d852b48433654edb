// Splines through cactus0, cactus6, cactus12, cactus18 at 0, 2, 4, 6 (K = 6):
// the LΘA spline and the nonlinear spline started from it (L-BFGS, at most
// Arg iterations), with F_K of each and where the nonlinear solve spends its
// time (midpoint LM solves, Newton polish, adjoint gradient). One run, one
// thread (OPENBLAS_NUM_THREADS=1 recommended).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"

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

double Seconds(std::chrono::steady_clock::time_point a,
               std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void BM_CactusSplines(benchmark::State& state) {
  CactusKeyframes data;
  const ShellSpace space(data.first, Topology::Build(data.first),
                         ShellMaterial{});
  const std::vector<int> at = {0, 2, 4, 6};
  SolverSettings single;
  single.num_threads = 1;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const ShellPath ltheta =
        LThetaSpline(space, data.keyframes, at, 6, false, single);
    const auto t1 = std::chrono::steady_clock::now();
    SplineSettings settings;
    settings.inner.num_threads = 1;
    settings.inner.gradient_tolerance = 1e-10;  // as the spline verb
    settings.max_iterations = 0;
    const SplineResult ltheta_energy =
        SolveSpline(space, data.keyframes, at, 6, false, ltheta, settings);
    const auto t2 = std::chrono::steady_clock::now();
    settings.max_iterations = static_cast<int>(state.range(0));
    settings.progress = true;
    const SplineResult nonlinear =
        SolveSpline(space, data.keyframes, at, 6, false, ltheta, settings);
    const auto t3 = std::chrono::steady_clock::now();
    const SplineTimings& t = nonlinear.timings;
    std::fprintf(stderr,
                 "nonlinear: %d F_K evaluations (%d with gradient); %d LM "
                 "midpoint solves (%d iterations, %.1f s), %d Newton steps "
                 "(%d factorisations, %d CG iterations, %.1f s), adjoint "
                 "%.1f s; %s\n",
                 t.evaluations, t.gradient_evaluations, t.lm_solves,
                 t.lm_iterations, t.lm_seconds, t.newton_steps,
                 t.factorizations, t.cg_iterations, t.newton_seconds,
                 t.gradient_seconds, nonlinear.summary.BriefReport().c_str());
    state.counters["ltheta_s"] = Seconds(t0, t1);
    state.counters["F_ltheta"] = ltheta_energy.spline_energy;
    state.counters["F_eval_s"] = Seconds(t1, t2);
    state.counters["nonlinear_s"] = Seconds(t2, t3);
    state.counters["F_nonlinear"] = nonlinear.spline_energy;
    state.counters["lbfgs_iterations"] =
        static_cast<double>(nonlinear.summary.iterations.size()) - 1;
    state.counters["lm_s"] = t.lm_seconds;
    state.counters["newton_s"] = t.newton_seconds;
    state.counters["adjoint_s"] = t.gradient_seconds;
    state.counters["factorizations"] = t.factorizations;
    state.counters["cg_iterations"] = t.cg_iterations;
  }
}
BENCHMARK(BM_CactusSplines)->Arg(30)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

