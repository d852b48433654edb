// Example 1: an elastic deformation with a soft constraint of your own.
//
//   minimise  W[S̄, S] + k/2 |S_v - target|^2   over S,
//
// S̄ a mesh you read, the vertices of a mask held fixed, and vertex v pulled
// towards a target point by a residual written here (a Ceres AutoDiff
// functor). shellspace contributes W through AddDeformationEnergy; the rest
// is plain Ceres.
//
//   deform_with_soft_constraint MESH.ply MASK.txt VERTEX DX DY DZ OUT.ply
//
// pulls VERTEX by (DX, DY, DZ) from its rest position; prints W and the
// distance left to the target.
#include <ceres/ceres.h>
#include <shellspace/cost_functions/deformation_energy_residuals.h>
#include <shellspace/cost_functions/shell/deformation_energy.h>
#include <shellspace/cost_functions/shell/shell_space.h>
#include <shellspace/geometry/validation.h>
#include <shellspace/io/mesh_io.h>
#include <shellspace/solvers/problem_checks.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "example_inputs.h"

namespace {

// r = sqrt(k) (x - target): 1/2 |r|^2 = k/2 |x - target|^2.
struct PullToTarget {
  template <typename T>
  bool operator()(const T* x, T* r) const {
    for (int c = 0; c < 3; ++c) r[c] = T(std::sqrt(stiffness)) * (x[c] - T(target[c]));
    return true;
  }
  Eigen::Vector3d target;
  double stiffness;
};

int Run(int /*argc: Main checked the 7 arguments*/, char** argv) {
  const shellspace::Mesh reference = shellspace::ReadMesh(argv[1]);
  const shellspace::Topology topology = shellspace::ValidateShell(reference, argv[1]);
  const std::vector<int> mask =
      shellspace::ReadMask(argv[2], reference.num_vertices());
  const int vertex = std::atoi(argv[3]);
  if (vertex < 0 || vertex >= reference.num_vertices()) {
    std::fprintf(stderr, "vertex %d outside the mesh\n", vertex);
    return 2;
  }
  const Eigen::Vector3d target =
      reference.positions.row(vertex).transpose() +
      Eigen::Vector3d(std::atof(argv[4]), std::atof(argv[5]), std::atof(argv[6]));

  shellspace::ShellMaterial material;  // mu = lambda = 1, eta = 0.01
  const shellspace::ShellSpace space(reference, topology, material);
  shellspace::Positions deformed = reference.positions;  // the unknowns

  ceres::Problem problem;
  shellspace::AddDeformationEnergy(
      space, shellspace::ShellArgument::Fixed(reference.positions),
      shellspace::ShellArgument::Variable(&deformed), 1.0, &problem);
  const ceres::ResidualBlockId pull = problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<PullToTarget, 3, 3>(
          new PullToTarget{target, 10.0}),
      nullptr, deformed.data() + 3 * vertex);
  for (int v : mask) problem.SetParameterBlockConstant(deformed.data() + 3 * v);
  // A pull on a masked vertex could not move anything (Ceres would report
  // CONVERGENCE after 0 iterations): a clear error instead.
  shellspace::RequireVariableResidual(problem, pull,
                                      "the pull on vertex " + std::to_string(vertex));

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 200;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  const shellspace::DeformationEnergy w =
      shellspace::EvaluateDeformationEnergy(space, reference.positions, deformed);
  const double left = (deformed.row(vertex).transpose() - target).norm();
  shellspace::WriteMesh(shellspace::Mesh{deformed, reference.faces}, argv[7]);
  std::printf("%s after %d iterations (%s): W = %.9g (membrane %.6g, bending "
              "%.6g), distance to target %.6g (of %.6g); wrote %s\n",
              summary.IsSolutionUsable() ? "usable" : "NOT usable",
              static_cast<int>(summary.iterations.size()) - 1,
              ceres::TerminationTypeToString(summary.termination_type), w.total,
              w.membrane, w.bending, left,
              (reference.positions.row(vertex).transpose() - target).norm(),
              argv[7]);
  return summary.IsSolutionUsable() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return examples::Main(Run, {7, 7, "MESH MASK VERTEX DX DY DZ OUT.ply"},
                        argc, argv);
}
