// A consumer of the installed shellspace package. It demonstrates that an
// outside project can put shellspace's cost functions into a ceres::Problem of
// its own, next to residuals it defines itself:
//
//   minimise  W[flat, X] + k/2 |X_pulled - target|^2  over the deformed grid X,
//
// with W the discrete-shell deformation energy (membrane + bending) relative to
// a flat 4 x 4 grid, one corner pulled out of the plane towards a target point
// by the consumer's own residual and the three other corners held fixed (so
// the grid has to stretch and bend, not just tilt). No data files: the mesh is
// built in code (grid.h). Exits non-zero unless the solution is sane.
#include <ceres/ceres.h>
#include <shellspace/cost_functions/deformation_energy_residuals.h>
#include <shellspace/cost_functions/shell/deformation_energy.h>
#include <shellspace/cost_functions/shell/shell_space.h>
#include <shellspace/geometry/mesh.h>
#include <shellspace/geometry/topology.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include "grid.h"

namespace {

using consumer::kGridSize;
using consumer::MakeFlatGrid;
using consumer::VertexIndex;
constexpr double kPullStiffness = 1.0;

// The consumer's own residual: r = sqrt(k) (x - target) for one vertex, so
// that 1/2 |r|^2 = k/2 |x - target|^2.
struct PullToTarget {
  PullToTarget(const Eigen::Vector3d& target, double stiffness)
      : target(target), sqrt_stiffness(std::sqrt(stiffness)) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int c = 0; c < 3; ++c) {
      residual[c] = T(sqrt_stiffness) * (x[c] - T(target[c]));
    }
    return true;
  }

  Eigen::Vector3d target;
  double sqrt_stiffness;
};

double PullCost(const Eigen::Vector3d& x, const Eigen::Vector3d& target) {
  return 0.5 * kPullStiffness * (x - target).squaredNorm();
}

int Run() {
  const shellspace::Mesh reference = MakeFlatGrid();
  const shellspace::ShellMaterial material;  // mu = lambda = 1, eta = 0.01
  const shellspace::ShellSpace space(
      reference, shellspace::Topology::Build(reference), material);

  // The deformed shell starts at the reference; its vertices are the
  // parameter blocks (3 doubles each, contiguous in the row-major matrix).
  shellspace::Positions deformed = reference.positions;
  const int pulled = VertexIndex(kGridSize - 1, kGridSize - 1);
  const std::vector<int> anchored = {VertexIndex(0, 0),
                                     VertexIndex(kGridSize - 1, 0),
                                     VertexIndex(0, kGridSize - 1)};
  const Eigen::Vector3d target(1.1, 1.05, 0.4);

  ceres::Problem problem;
  shellspace::AddDeformationEnergy(
      space, shellspace::ShellArgument::Fixed(reference.positions),
      shellspace::ShellArgument::Variable(&deformed), 1.0, &problem);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PullToTarget, 3, 3>(
                               new PullToTarget(target, kPullStiffness)),
                           nullptr, deformed.data() + 3 * pulled);
  for (const int vertex : anchored) {
    problem.SetParameterBlockConstant(deformed.data() + 3 * vertex);
  }

  const Eigen::Vector3d start = deformed.row(pulled).transpose();
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  // W from shellspace's closed-form evaluation must match the solver's final
  // cost minus the consumer's own term.
  const Eigen::Vector3d end = deformed.row(pulled).transpose();
  const shellspace::DeformationEnergy energy =
      shellspace::EvaluateDeformationEnergy(space, reference.positions,
                                            deformed);
  const double pull_cost = PullCost(end, target);
  const double solver_energy = summary.final_cost - pull_cost;
  const double mismatch = std::abs(solver_energy - energy.total) /
                          std::max(std::abs(energy.total), 1e-300);
  double anchor_shift = 0;
  for (const int vertex : anchored) {
    anchor_shift +=
        (deformed.row(vertex) - reference.positions.row(vertex)).norm();
  }

  std::vector<const char*> failures;
  if (!summary.IsSolutionUsable()) failures.push_back("solution not usable");
  if (!std::isfinite(summary.final_cost) || !std::isfinite(energy.total)) {
    failures.push_back("non-finite energy");
  }
  if (!(summary.final_cost < summary.initial_cost)) {
    failures.push_back("cost did not decrease");
  }
  if (!((end - target).norm() < (start - target).norm())) {
    failures.push_back("pulled vertex did not move towards its target");
  }
  if (!(energy.membrane > 0 && energy.bending > 0)) {
    failures.push_back("no membrane or no bending energy stored");
  }
  if (!(mismatch <= 1e-8)) {
    failures.push_back("EvaluateDeformationEnergy != solver cost - own term");
  }
  if (anchor_shift != 0) failures.push_back("an anchored vertex moved");

  std::printf(
      "shellspace consumer: %s  cost %.6g -> %.6g in %d iterations, "
      "W = %.10g (membrane %.6g, bending %.6g), |W - (cost - pull)|/W = "
      "%.2e, pulled-vertex distance to target %.4g -> %.4g\n",
      failures.empty() ? "OK" : "FAILED", summary.initial_cost,
      summary.final_cost, static_cast<int>(summary.iterations.size()) - 1,
      energy.total, energy.membrane, energy.bending, mismatch,
      (start - target).norm(), (end - target).norm());
  for (const char* failure : failures) {
    std::fprintf(stderr, "shellspace consumer: FAILED: %s\n", failure);
  }
  return failures.empty() ? 0 : 1;
}

}  // namespace

int main() {
  try {
    return Run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shellspace consumer: FAILED: %s\n", e.what());
    return 1;
  }
}
