// The geodesic-calculus workloads of the issue, one run each (heavy: not
// part of the test suite): finger0 -> finger1 geodesic (mask, eta = 0.001,
// K = 8, to a relative gradient norm of 1e-8), cactus0 -> cactus1 geodesic
// (bottom mask, K = 8), an 8-step EXP shot on the finger, and a transport
// of finger_var - finger0 along the finger geodesic.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/reusable_cholesky.h"

namespace shellspace {
namespace {

std::string Data(const std::string& name) {
  return std::string(SHELLSPACE_DATA_DIR) + "/" + name;
}

void ReportSummary(benchmark::State& state, const ceres::Solver::Summary& s) {
  state.counters["iterations"] = static_cast<double>(s.iterations.size());
  state.counters["jacobian_s"] = s.jacobian_evaluation_time_in_seconds;
  state.counters["residual_s"] = s.residual_evaluation_time_in_seconds;
  state.counters["linear_solver_s"] = s.linear_solver_time_in_seconds;
}

// The LM stage (Ceres' summary: LM iterations, Jacobian / residual /
// linear-solver seconds) and the Newton stage (steps, Hessian assembly,
// Cholesky factorisations, CG on the reused factor).
void ReportGeodesic(benchmark::State& state, const GeodesicResult& g) {
  ReportSummary(state, g.summary);
  state.counters["lm_s"] = g.summary.total_time_in_seconds;
  state.counters["newton_steps"] = g.newton.steps;
  state.counters["newton_s"] = g.newton.seconds;
  state.counters["hessian_s"] = g.newton.assembly_seconds;
  state.counters["factorizations"] = g.newton.factorizations;
  state.counters["cholesky_s"] = g.newton.factorization_seconds;
  state.counters["cg_iterations"] = g.newton.cg_iterations;
  state.counters["cg_s"] = g.newton.cg_seconds;
  state.counters["final_gradient"] = g.final_gradient;
  state.counters["E_K"] = g.path_energy;
}

// finger0, finger1, the variation and the base mask, with eta = 0.001.
struct Finger {
  Mesh a = ReadMesh(Data("finger/finger0.ply"));
  Mesh b = ReadMesh(Data("finger/finger1.ply"));
  ShellSpace space{a, Topology::Build(a), ShellMaterial{1.0, 1.0, 0.001}};
  std::vector<int> mask =
      ReadMask(Data("finger/finger_mask.txt"), a.num_vertices());

  GeodesicResult Geodesic() const {
    GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 8);
    input.fixed_vertices = mask;
    return SolveGeodesic(space, input, SolverSettings{});
  }
};

void BM_FingerGeodesic(benchmark::State& state) {
  const Finger finger;
  for (auto _ : state) ReportGeodesic(state, finger.Geodesic());
}
BENCHMARK(BM_FingerGeodesic)->Iterations(1)->Unit(benchmark::kSecond);

// One assembly of the exact path Hessian (finger, K = 8, mask) on the linear
// interpolation, with 1 or 2 threads: the per-step cost of the Newton stage.
void BM_FingerPathHessian(benchmark::State& state) {
  const Finger finger;
  const int K = 8;
  const ShellPath path = LinearPath(finger.a.positions, finger.b.positions, K);
  const std::vector<Eigen::SparseMatrix<double>> bases(
      K - 1, FreeVertexBasis(finger.a.num_vertices(), finger.mask));
  const PathHessianAssembler assembler(finger.space);
  for (auto _ : state) {
    const auto h = assembler.Assemble(path, bases, state.range(0));
    state.counters["nonzeros"] = static_cast<double>(h.nonZeros());
  }
}
BENCHMARK(BM_FingerPathHessian)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The linear algebra of one spline / LOG_2 midpoint Newton step on the cactus
// (one free shape, rigid gauge): assembly of H, a factorisation, and one CG
// iteration on a reused factor (reported as cg_iteration_ms).
void BM_CactusMidpointHessian(benchmark::State& state) {
  const Mesh a = ReadMesh(Data("cactus/cactus0.ply"));
  const Mesh b = ReadMesh(Data("cactus/cactus1.ply"));
  const ShellSpace space(a, Topology::Build(a), ShellMaterial{});
  const Positions m = 0.5 * (a.positions + b.positions);
  const std::vector<Eigen::SparseMatrix<double>> bases = {RigidGaugeBasis(m)};
  const std::vector<int> vertex_of = BasisColumnVertices(bases[0]);
  const PathHessianAssembler assembler(space);
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(bases[0].cols());
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto h = assembler.Assemble({a.positions, m, b.positions}, bases, 1);
    const auto t1 = std::chrono::steady_clock::now();
    ReusableCholesky solver;
    Eigen::VectorXd x;
    solver.Solve(h, vertex_of, a.num_vertices(), rhs, 1e-12, &x);
    const auto t2 = std::chrono::steady_clock::now();
    solver.Solve(h * 1.01, vertex_of, a.num_vertices(), rhs, 1e-12, &x);
    state.counters["assembly_ms"] =
        1e3 * std::chrono::duration<double>(t1 - t0).count();
    state.counters["factorization_ms"] =
        1e3 * std::chrono::duration<double>(t2 - t1).count();
    state.counters["cg_iteration_ms"] =
        1e3 * solver.stats().cg_seconds /
        std::max(1, solver.stats().cg_iterations);
  }
}
BENCHMARK(BM_CactusMidpointHessian)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

void BM_CactusGeodesic(benchmark::State& state) {
  const Mesh a = ReadMesh(Data("cactus/cactus0.ply"));
  const Mesh b = ReadMesh(Data("cactus/cactus1.ply"));
  const ShellSpace space(a, Topology::Build(a), ShellMaterial{});
  GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 8);
  input.fixed_vertices =
      ReadMask(Data("cactus/cactus_bottom_mask.txt"), a.num_vertices());
  for (auto _ : state) {
    const GeodesicResult g = SolveGeodesic(space, input, SolverSettings{});
    ReportGeodesic(state, g);
  }
}
BENCHMARK(BM_CactusGeodesic)->Iterations(1)->Unit(benchmark::kSecond);

void BM_FingerShootAndTransport(benchmark::State& state) {
  const Finger finger;
  const Mesh& a = finger.a;
  const ShellSpace& space = finger.space;
  const std::vector<int>& mask = finger.mask;
  const Mesh var = ReadMesh(Data("finger/finger_var.ply"));
  const GeodesicResult g = finger.Geodesic();
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<ceres::Solver::Summary> summaries;
    const ShellPath shot =
        Shoot(space, g.path[0], g.path[1], 8, StepDirection::kForward, mask,
              SolverSettings{}, &summaries);
    const auto t1 = std::chrono::steady_clock::now();
    const TransportResult t =
        ParallelTransport(space, g.path, var.positions - a.positions, 1.0, mask,
                          SolverSettings{});
    const auto t2 = std::chrono::steady_clock::now();
    state.counters["shoot_s"] = std::chrono::duration<double>(t1 - t0).count();
    state.counters["transport_s"] =
        std::chrono::duration<double>(t2 - t1).count();
    state.counters["shoot_end_error"] =
        (shot.back() - g.path.back()).rowwise().norm().maxCoeff();
    state.counters["transport_max_exp_residual"] =
        *std::max_element(t.exp_residuals.begin(), t.exp_residuals.end());
  }
}
BENCHMARK(BM_FingerShootAndTransport)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace shellspace

