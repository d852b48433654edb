#include "shellspace/cost_functions/deformation_energy_residuals.h"

#include <type_traits>

#include "shellspace/cost_functions/element_cost_function.h"
#include "shellspace/cost_functions/shell/element_set.h"

namespace shellspace {

namespace {

// Gathers the coordinates of `vertices` of a fixed shell (nullptr if variable)
// and the parameter blocks of a variable one.
template <std::size_t kVertices>
const double* Gather(const ShellArgument& arg,
                     const std::array<int, kVertices>& vertices,
                     double* buffer, std::vector<double*>* blocks) {
  for (std::size_t v = 0; v < kVertices; ++v) {
    double* p = arg.positions + 3 * vertices[v];
    if (arg.variable) {
      blocks->push_back(p);
    } else {
      for (int c = 0; c < 3; ++c) buffer[3 * v + c] = p[c];
    }
  }
  return arg.variable ? nullptr : buffer;
}

}  // namespace

void AddDeformationEnergy(const ShellSpace& space, ShellArgument reference,
                          ShellArgument deformed, double weight,
                          ceres::Problem* problem,
                          std::vector<ceres::ResidualBlockId>* ids) {
  std::vector<double*> blocks;
  space.elements().ForEachGroup([&](const auto& group) {
    using Group = std::decay_t<decltype(group)>;
    using Cost = ElementCostFunction<typename Group::Element, Group::kVertices>;
    double ref_buffer[3 * Group::kVertices], def_buffer[3 * Group::kVertices];
    for (const auto& stencil : group.stencils) {
      blocks.clear();
      const double* ref = Gather(reference, stencil, ref_buffer, &blocks);
      const double* def = Gather(deformed, stencil, def_buffer, &blocks);
      auto* cost = new Cost(group.element, ref, def, weight);
      const auto id = problem->AddResidualBlock(cost, nullptr, blocks);
      if (ids) ids->push_back(id);
    }
  });
}

}  // namespace shellspace
