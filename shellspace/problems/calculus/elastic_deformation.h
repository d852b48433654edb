// Elastic deformation: the shell of least deformation energy W[Sbar, S] with
// prescribed positions of some vertices (a Dirichlet mask).
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_ELASTIC_DEFORMATION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_ELASTIC_DEFORMATION_H_

#include <ceres/solver.h>

#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// min_S W[reference, S] subject to S_v = targets_v for v in `fixed_vertices`.
// `initial` is the starting guess (its fixed vertices are replaced by their
// targets); a usual choice is the target mesh itself. With no fixed vertex
// the rigid gauge is pinned (problems/rigid_gauge.h) and the result is the
// reference up to a rigid motion.
struct ElasticDeformationInput {
  Positions reference;
  Positions targets;
  Positions initial;
  std::vector<int> fixed_vertices;
};

struct ElasticDeformationResult {
  Positions deformed;
  DeformationEnergy energy;
  ceres::Solver::Summary summary;
};

ElasticDeformationResult SolveElasticDeformation(
    const ShellSpace& space, const ElasticDeformationInput& input,
    const SolverSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_ELASTIC_DEFORMATION_H_
