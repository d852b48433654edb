#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/problems/calculus/elastic_deformation.h"

#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

ElasticDeformationResult SolveElasticDeformation(
    const ShellSpace& space, const ElasticDeformationInput& input,
    const SolverSettings& settings) {
  ElasticDeformationResult result;
  result.deformed = input.initial;
  for (int v : input.fixed_vertices) {
    result.deformed.row(v) = input.targets.row(v);
  }
  ceres::Problem problem;
  AddDeformationEnergy(space, ShellArgument::Fixed(input.reference),
                       ShellArgument::Variable(&result.deformed), 1.0,
                       &problem);
  for (int v : input.fixed_vertices) {
    problem.SetParameterBlockConstant(result.deformed.data() + 3 * v);
  }
  if (input.fixed_vertices.empty()) PinRigidMotions(&result.deformed, &problem);
  result.summary = SolveWithSettings(&problem, settings);
  result.energy =
      EvaluateDeformationEnergy(space, input.reference, result.deformed);
  return result;
}

}  // namespace shellspace
