#include "shellspace/cost_functions/shell/deformation_energy.h"

#include <type_traits>

namespace shellspace {

bool TryEvaluateDeformationEnergy(const ShellSpace& space,
                                  const Positions& reference,
                                  const Positions& deformed,
                                  DeformationEnergy* energy,
                                  ElementFailure* failure) {
  *energy = DeformationEnergy();
  bool ok = true;
  double total = 0;
  space.elements().ForEachGroupWithZeroWeight([&](const auto& group) {
    if (!ok) return;
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    Vec3<double> ref[kV], def[kV];
    double sum = 0;
    for (int i = 0; i < group.size(); ++i) {
      GatherVertices(reference, group.stencils[i], ref);
      GatherVertices(deformed, group.stencils[i], def);
      double e = 0;
      if (!group.element.Energy(ref, def, &e)) {
        ok = false;
        if (failure) {
          failure->element =
              group.in_energy() ? group.first_element + i : -1;
          failure->description = group.Describe(i);
        }
        return;
      }
      sum += e;
    }
    (group.part == EnergyPart::kMembrane ? energy->membrane
                                         : energy->bending) += sum;
    if (group.in_energy()) total += group.weight * sum;
  });
  energy->total = total;
  return ok;
}

DeformationEnergy EvaluateDeformationEnergy(const ShellSpace& space,
                                            const Positions& reference,
                                            const Positions& deformed) {
  DeformationEnergy energy;
  ElementFailure failure;
  if (!TryEvaluateDeformationEnergy(space, reference, deformed, &energy,
                                    &failure)) {
    throw InputError("W[reference, deformed]: " + failure.description +
                     " is degenerate");
  }
  return energy;
}

}  // namespace shellspace
