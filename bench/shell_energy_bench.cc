// Evaluation of W[cactus0, cactus1] (5,261 vertices): residuals and Jacobians
// w.r.t. both arguments through ceres::Problem::Evaluate, with 1 and 2
// threads; and the assembly of the sparse Hessian D_2^2 W. The assembly of
// the path Hessian of the finger geodesic (finger0 -> finger1, K = 8, finger
// mask, eta = 0.001, linear path), one thread.
#include <benchmark/benchmark.h>
#include <ceres/crs_matrix.h>
#include <ceres/problem.h>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"

namespace shellspace {
namespace {

struct Cactus {
  Mesh reference =
      ReadMesh(std::string(SHELLSPACE_DATA_DIR) + "/cactus/cactus0.ply");
  Mesh deformed =
      ReadMesh(std::string(SHELLSPACE_DATA_DIR) + "/cactus/cactus1.ply");
  ShellSpace space{reference, Topology::Build(reference), ShellMaterial{}};
};

void BM_ResidualsAndJacobians(benchmark::State& state) {
  Cactus cactus;
  Positions ref = cactus.reference.positions, def = cactus.deformed.positions;
  ceres::Problem problem;
  AddDeformationEnergy(cactus.space, ShellArgument::Variable(&ref),
                       ShellArgument::Variable(&def), 1.0, &problem);
  ceres::Problem::EvaluateOptions options;
  options.num_threads = static_cast<int>(state.range(0));
  double cost = 0;
  std::vector<double> residuals;
  ceres::CRSMatrix jacobian;
  for (auto _ : state) {
    problem.Evaluate(options, &cost, &residuals, nullptr, &jacobian);
    benchmark::DoNotOptimize(cost);
  }
  state.counters["W"] = cost;
}
BENCHMARK(BM_ResidualsAndJacobians)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond);

void BM_GradientBothArguments(benchmark::State& state) {
  Cactus cactus;
  for (auto _ : state) {
    auto g1 = EnergyGradient(cactus.space, cactus.reference.positions,
                             cactus.deformed.positions, ShellSide::kReference);
    auto g2 = EnergyGradient(cactus.space, cactus.reference.positions,
                             cactus.deformed.positions, ShellSide::kDeformed);
    benchmark::DoNotOptimize(g1.data());
    benchmark::DoNotOptimize(g2.data());
  }
}
BENCHMARK(BM_GradientBothArguments)->Unit(benchmark::kMillisecond);

void BM_HessianDeformed(benchmark::State& state) {
  Cactus cactus;
  for (auto _ : state) {
    SparseMatrix h = EnergyHessian(cactus.space, cactus.reference.positions,
                                   cactus.deformed.positions,
                                   ShellSide::kDeformed, ShellSide::kDeformed);
    benchmark::DoNotOptimize(h.nonZeros());
  }
}
BENCHMARK(BM_HessianDeformed)->Unit(benchmark::kMillisecond);

void BM_PathHessianFinger(benchmark::State& state) {
  const std::string dir = std::string(SHELLSPACE_DATA_DIR) + "/finger/";
  const Mesh a = ReadMesh(dir + "finger0.ply");
  const Mesh b = ReadMesh(dir + "finger1.ply");
  ShellMaterial material;
  material.eta = 0.001;
  const ShellSpace space(a, Topology::Build(a), material);
  const int K = 8;
  const ShellPath path = LinearPath(a.positions, b.positions, K);
  const std::vector<SparseMatrix> bases(
      K - 1, FreeVertexBasis(space.num_vertices,
                             ReadMask(dir + "finger_mask.txt",
                                      space.num_vertices)));
  const PathHessianAssembler assembler(space);
  for (auto _ : state) {
    SparseMatrix h = assembler.Assemble(path, bases, 1);
    benchmark::DoNotOptimize(h.nonZeros());
  }
}
BENCHMARK(BM_PathHessianFinger)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace shellspace

