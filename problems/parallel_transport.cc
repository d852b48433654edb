#include "problems/parallel_transport.h"

namespace shellspace {

TransportResult ParallelTransport(const ShellSpace& space,
                                  const ShellPath& path,
                                  const Positions& variation, double epsilon,
                                  const std::vector<int>& fixed_vertices,
                                  const SolverSettings& settings) {
  if (!(epsilon > 0)) throw InputError("--epsilon must be positive");
  if (path.size() < 2)
    throw InputError("transport needs a path of >= 2 shapes");
  TransportResult result;
  result.variations.push_back(variation);
  Positions p = path[0] + epsilon * variation;
  result.shapes.push_back(p);
  for (size_t k = 1; k < path.size(); ++k) {
    const Positions initial = 0.5 * (p + path[k]);
    const Positions midpoint = SolveWeightedMidpoint(
        space, p, path[k], 1.0, 1.0, initial, fixed_vertices, settings);
    p = ExpStep(space, path[k - 1], midpoint, StepDirection::kForward,
                fixed_vertices, settings)
            .shape;
    result.shapes.push_back(p);
    result.variations.push_back((p - path[k]) / epsilon);
  }
  return result;
}

}  // namespace shellspace
