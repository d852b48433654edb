// The elastic (Frechet-type) mean of shells (calculus.md, "Elastic mean and
// shell PCA"): s_bar = argmin_s sum_i W[S_i, s], the inputs as references.
#ifndef SHELLSPACE_PROBLEMS_ELASTIC_MEAN_H_
#define SHELLSPACE_PROBLEMS_ELASTIC_MEAN_H_

#include <vector>

#include <ceres/solver.h>

#include "cost_functions/deformation_energy.h"
#include "problems/solver_settings.h"

namespace shellspace {

// Checks that `shapes` is non-empty and that every shape has
// space.num_vertices finite rows; throws InputError otherwise. `what` names
// the shapes in the message.
void CheckShapeSet(const ShellSpace& space, const std::vector<Positions>& shapes,
                   const char* what);

// The vertex average (1/n) sum_i A_i(S_i) of the inputs after rigid alignment
// A_i = AlignRigidly(., S_1) of each to the first one. The initial guess of
// the elastic mean; equivariant under rigid motions of the inputs (moving S_1
// moves the average with it, moving S_i, i > 1, leaves it unchanged).
Positions AlignedVertexAverage(const std::vector<Positions>& shapes);

struct ElasticMeanResult {
  Positions mean;                 // s_bar, rigidly aligned to the first input
  double energy = 0;              // sum_i W[S_i, s_bar]
  std::vector<double> energies;   // W[S_i, s_bar]
  ceres::Solver::Summary summary;
};

// s_bar = argmin_s sum_i W[S_i, s] by sparse LM: every W[S_i, s] adds its
// membrane and bending residuals with S_i as fixed data, s is the variable;
// the rigid gauge of s is pinned (problems/rigid_gauge.h). Starts from
// `initial` if given (same vertex count), else from
// AlignedVertexAverage(shapes). The result is aligned rigidly to shapes[0]
// (W is invariant under rigid motions of either argument). Throws InputError
// on an empty or inconsistent input set.
ElasticMeanResult ComputeElasticMean(const ShellSpace& space,
                                     const std::vector<Positions>& shapes,
                                     const SolverSettings& settings,
                                     const Positions* initial = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_ELASTIC_MEAN_H_
