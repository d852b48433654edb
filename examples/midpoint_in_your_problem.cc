// Example 3: shellspace residuals inside a ceres::Problem of your own, with
// the unknown shell on both sides of W.
//
//   minimise  W[a, s] + W[s, b] + (k/2) sum_v |s_v - (a_v + b_v)/2|^2
//
// over s: the geodesic midpoint of a and b (the first two terms; in W[a, s]
// s is the deformed side, in W[s, b] the reference side) plus a weak
// Tikhonov term of yours that also removes the rigid-motion null space. For
// a small k the result approaches the library's SolveWeightedMidpoint
// (which pins the gauge instead); the program prints both and their
// distance, and exits 1 if they differ by more than 1e-5 of the diameter.
//
//   midpoint_in_your_problem A.ply B.ply [K_WEIGHT]
#include <ceres/ceres.h>
#include <shellspace/cost_functions/deformation_energy_residuals.h>
#include <shellspace/cost_functions/shell/deformation_energy.h>
#include <shellspace/geometry/rigid_alignment.h>
#include <shellspace/problems/calculus/geodesic.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "example_inputs.h"

namespace {

// r = sqrt(k) (x - centre) for one vertex.
class StayNear : public ceres::SizedCostFunction<3, 3> {
 public:
  StayNear(const Eigen::Vector3d& centre, double k)
      : centre_(centre), sqrt_k_(std::sqrt(k)) {}
  bool Evaluate(double const* const* x, double* r, double** jacobians) const override {
    for (int c = 0; c < 3; ++c) r[c] = sqrt_k_ * (x[0][c] - centre_[c]);
    if (jacobians && jacobians[0]) {
      for (int i = 0; i < 9; ++i) jacobians[0][i] = (i % 4 == 0) ? sqrt_k_ : 0.0;
    }
    return true;
  }

 private:
  Eigen::Vector3d centre_;
  double sqrt_k_;
};

int Run(int argc, char** argv) {
  const examples::TwoPoses poses = examples::ReadTwoPoses(argv[1], argv[2]);
  const shellspace::Mesh& a = poses.first;
  const shellspace::Mesh b{poses.second, a.faces};
  const double k = argc == 4 ? std::atof(argv[3]) : 1e-8;
  const shellspace::ShellSpace space(a, poses.topology, shellspace::ShellMaterial{});

  const shellspace::Positions average = 0.5 * (a.positions + b.positions);
  shellspace::Positions s = average;  // the unknown, started at the average
  ceres::Problem problem;
  shellspace::AddDeformationEnergy(space, shellspace::ShellArgument::Fixed(a.positions),
                                   shellspace::ShellArgument::Variable(&s), 1.0,
                                   &problem);
  shellspace::AddDeformationEnergy(space, shellspace::ShellArgument::Variable(&s),
                                   shellspace::ShellArgument::Fixed(b.positions), 1.0,
                                   &problem);
  for (int v = 0; v < a.num_vertices(); ++v) {
    problem.AddResidualBlock(new StayNear(average.row(v).transpose(), k), nullptr,
                             s.data() + 3 * v);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  shellspace::SolverSettings settings;
  settings.progress = false;
  const shellspace::Positions library = shellspace::SolveWeightedMidpoint(
      space, a.positions, b.positions, 1, 1, average, {}, settings);
  const double energy = shellspace::EvaluateDeformationEnergy(space, a.positions, s).total +
                        shellspace::EvaluateDeformationEnergy(space, s, b.positions).total;
  const double library_energy =
      shellspace::EvaluateDeformationEnergy(space, a.positions, library).total +
      shellspace::EvaluateDeformationEnergy(space, library, b.positions).total;
  const double distance =
      shellspace::RelativeDistanceUpToRigidMotion(s, library);
  std::printf("your problem: W[a,s] + W[s,b] = %.12g after %d iterations (%s)\n"
              "library midpoint:              %.12g\n"
              "max vertex distance up to rigid motion / diameter: %.3g\n",
              energy, static_cast<int>(summary.iterations.size()) - 1,
              ceres::TerminationTypeToString(summary.termination_type), library_energy,
              distance);
  // The example checks itself: with k = 1e-8 the two midpoints agree to
  // about 1e-7 of the size (the regulariser's bias).
  return summary.IsSolutionUsable() && distance < 1e-5 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return examples::Main(Run, {2, 3, "A B [K_WEIGHT]"}, argc, argv);
}
