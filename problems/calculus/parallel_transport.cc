#include "shellspace/problems/calculus/parallel_transport.h"

#include <algorithm>
#include <cstdio>

#include "shellspace/cost_functions/shell/energy_derivatives.h"

namespace shellspace {

TransportResult ParallelTransport(const ShellSpace& space,
                                  const ShellPath& path,
                                  const Positions& variation, double epsilon,
                                  const std::vector<int>& fixed_vertices,
                                  const SolverSettings& settings) {
  if (!(epsilon > 0)) throw InputError(
        "parallel transport: the step epsilon must be positive, got " +
        std::to_string(epsilon));
  if (path.size() < 2)
    throw InputError("transport needs a path of >= 2 shapes");
  TransportResult result;
  result.variations.push_back(variation);
  Positions p = path[0] + epsilon * variation;
  result.shapes.push_back(p);
  for (size_t k = 1; k < path.size(); ++k) {
    if (StopRequested(settings)) break;  // the rungs done so far
    const Positions initial = 0.5 * (p + path[k]);
    ceres::Solver::Summary midpoint_summary;
    const Positions midpoint =
        SolveWeightedMidpoint(space, p, path[k], 1.0, 1.0, initial,
                              fixed_vertices, settings, &midpoint_summary);
    if (StoppedByRequest(midpoint_summary)) break;  // an unfinished rung
    // Besides 2 m_k - s_{k-1}, start from s_k + (p_{k-1} - s_{k-1}): the
    // previous rung's variation at the new base point (the same point in
    // Euclidean space; the better one of the two on curved paths).
    const Positions carried = path[k] + (p - path[k - 1]);
    const ExpStepResult step =
        ExpStep(space, path[k - 1], midpoint, StepDirection::kForward,
                fixed_vertices, settings, &carried);
    if (StoppedByRequest(step.summary)) break;
    p = step.shape;
    const double scale =
        EnergyGradient(space, path[k - 1], midpoint, ShellSide::kDeformed)
            .cwiseAbs()
            .maxCoeff();
    result.exp_residuals.push_back(step.residual_norm /
                                   std::max(scale, 1e-300));
    result.shapes.push_back(p);
    result.variations.push_back((p - path[k]) / epsilon);
    if (settings.progress) {
      std::fprintf(stderr, "%s rung %zu of %zu  relative EXP residual %.3e\n",
                   settings.progress_label.c_str(), k, path.size() - 1,
                   result.exp_residuals.back());
    }
  }
  return result;
}

}  // namespace shellspace
