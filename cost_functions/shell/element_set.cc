#include "shellspace/cost_functions/shell/element_set.h"

#include <stdexcept>

namespace shellspace {

ElementSet::ElementSet(const Faces& faces, const Topology& topology,
                       const ShellMaterial& material)
    : material_(material),
      num_faces_(static_cast<int>(faces.rows())),
      num_interior_edges_(static_cast<int>(topology.interior_edges.size())) {
  // 1. Membrane: one element per face.
  ElementGroup<MembraneElement> membrane;
  membrane.term = "membrane";
  membrane.stencil_kind = "triangle";
  membrane.part = EnergyPart::kMembrane;
  membrane.weight = 1;
  membrane.element = material.membrane();
  membrane.stencils.resize(faces.rows());
  for (int f = 0; f < faces.rows(); ++f) {
    membrane.stencils[f] = {faces(f, 0), faces(f, 1), faces(f, 2)};
  }
  Add(std::move(membrane));

  // 2. Bending, weight eta, by the material's bending model.
  switch (material.bending_model) {
    case BendingModel::kDiscreteShells: {
      ElementGroup<BendingElement> bending;
      bending.term = "bending (Discrete Shells)";
      bending.stencil_kind = "interior edge";
      bending.part = EnergyPart::kBending;
      bending.weight = material.eta;
      bending.element = material.bending();
      bending.stencils.reserve(topology.interior_edges.size());
      for (const EdgeFlap& flap : topology.interior_edges) {
        bending.stencils.push_back({flap.i, flap.j, flap.k, flap.l});
      }
      Add(std::move(bending));
      break;
    }
    default:
      throw InputError("material: unknown bending model " +
                       std::to_string(static_cast<int>(material.bending_model)));
  }
}

template <class E>
void ElementSet::Add(ElementGroup<E> group) {
  // A term of weight 0 (eta = 0) is not part of W: no elements, no residuals
  // (as eta <= 0 skipped the bending loops before the set existed).
  if (group.weight > 0) {
    group.first_element = num_elements_;
    num_elements_ += group.size();
  } else {
    group.first_element = -1;
  }
  groups_.emplace_back(std::move(group));
}

std::string ElementSet::Describe(int element) const {
  std::string out;
  ForEachGroup([&](const auto& group) {
    const int i = element - group.first_element;
    if (i >= 0 && i < group.size()) out = group.Describe(i);
  });
  if (out.empty()) {
    throw std::out_of_range("ElementSet::Describe: no element " +
                            std::to_string(element));
  }
  return out;
}

void ElementSet::Fail(int element, ElementFailure* failure) const {
  if (failure == nullptr) return;
  failure->element = element;
  failure->description = Describe(element);
}

}  // namespace shellspace
