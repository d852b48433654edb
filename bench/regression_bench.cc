// Shape regression on the cactus: the poses cactus0, 3, 6,
// ..., 18 observed at path indices k_j = 0, 1, ..., 6 (K = 6), minimising
//   R[s] = sum_j W[S_j, s_{k_j}] + sigma F_K[s]
// for growing sigma, each solve warm-started from the previous one (the first
// from the data themselves, where the data term is 0) and capped at Arg
// L-BFGS iterations. Prints one row per sigma:
//   sigma, F_K, data term sum_j W[S_j, s_{k_j}], mean vertex distance
//   |s_{k_j} - S_j| after rigid alignment (mean over vertices and j, and
//   relative to the bounding-box diagonal of cactus0), L-BFGS iterations,
//   seconds.
// Single-threaded; run with OPENBLAS_NUM_THREADS=1.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/splines/spline.h"

namespace shellspace {
namespace {

double MeanVertexDistance(const Positions& s, const Positions& data) {
  const Positions aligned = AlignRigidly(s, data);
  return (aligned - data).rowwise().norm().mean();
}

void BM_CactusRegression(benchmark::State& state) {
  std::vector<Positions> data;
  std::vector<int> at;
  Mesh first;
  for (int pose = 0; pose <= 18; pose += 3) {
    Mesh m = ReadMesh(std::string(SHELLSPACE_DATA_DIR) + "/cactus/cactus" +
                      std::to_string(pose) + ".ply");
    if (pose == 0) first = m;
    data.push_back(m.positions);
    at.push_back(pose / 3);
  }
  const int steps = 6;
  const double diagonal = (first.positions.colwise().maxCoeff() -
                           first.positions.colwise().minCoeff())
                              .norm();
  const ShellSpace space(first, Topology::Build(first), ShellMaterial{});
  SplineSettings settings;
  settings.inner.num_threads = 1;
  settings.inner.gradient_tolerance = 1e-10;  // as the regress verb
  settings.max_iterations = static_cast<int>(state.range(0));
  for (auto _ : state) {
    // The data path itself: data term 0, F_K of the interpolating path.
    SplineSettings evaluate = settings;
    evaluate.max_iterations = 0;
    const SplineResult start =
        SolveRegression(space, data, at, steps, 1.0, {}, evaluate);
    std::printf("%8s %12s %12s %12s %10s %6s %8s\n", "sigma", "F_K",
                "data_term", "mean_dist", "rel_dist", "iters", "seconds");
    std::printf("%8s %12.5g %12.5g %12.5g %10.3g %6d %8s\n", "data",
                start.spline_energy, start.data_energy, 0.0, 0.0, 0, "-");
    ShellPath warm = start.path;
    for (double sigma : {1e-3, 1e-2, 1e-1, 1.0}) {
      const auto clock = std::chrono::steady_clock::now();
      const SplineResult r =
          SolveRegression(space, data, at, steps, sigma, warm, settings);
      const double seconds = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - clock)
                                 .count();
      double distance = 0;
      for (size_t j = 0; j < data.size(); ++j) {
        distance += MeanVertexDistance(r.path[at[j]], data[j]) / data.size();
      }
      const int iterations = static_cast<int>(r.summary.iterations.size()) - 1;
      std::printf("%8.0e %12.5g %12.5g %12.5g %10.3g %6d %8.1f\n", sigma,
                  r.spline_energy, r.data_energy, distance, distance / diagonal,
                  iterations, seconds);
      std::fflush(stdout);
      warm = r.path;
      const std::string tag =
          "_" + std::to_string(static_cast<int>(std::round(std::log10(sigma))));
      state.counters["F" + tag] = r.spline_energy;
      state.counters["data" + tag] = r.data_energy;
    }
  }
}
BENCHMARK(BM_CactusRegression)
    ->ArgName("max_iterations")
    ->Arg(20)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

