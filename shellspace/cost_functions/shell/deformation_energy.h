// Direct evaluation of the deformation energy W[Sbar, S] = W_mem + eta W_bend
// (docs/math.md, "Deformation energy") over the element set of a ShellSpace,
// from each element's closed-form energy (independent of the residual form).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_DEFORMATION_ENERGY_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_DEFORMATION_ENERGY_H_

#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The parts of W.
struct DeformationEnergy {
  double membrane = 0;  // W_mem
  double bending = 0;   // W_bend (without the factor eta; reported also when
                        // eta = 0)
  double total = 0;     // W_mem + eta W_bend
};

// W[reference, deformed] (both #V x 3): the sum over the element set of the
// elements' closed-form energies (MembraneElement::Energy: tr and det of
// gbar^-1 g; BendingElement::Energy), per part, total = sum of weight x part.
// Returns false, with *energy unspecified and *failure (if given) naming the
// first degenerate element, if an element is degenerate: a numerical status
// for line searches, no exception.
bool TryEvaluateDeformationEnergy(const ShellSpace& space,
                                  const Positions& reference,
                                  const Positions& deformed,
                                  DeformationEnergy* energy,
                                  ElementFailure* failure = nullptr);

// The same; throws InputError naming the element if one is degenerate (for
// inputs that must be valid, e.g. the shells a user gives).
DeformationEnergy EvaluateDeformationEnergy(const ShellSpace& space,
                                            const Positions& reference,
                                            const Positions& deformed);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_DEFORMATION_ENERGY_H_
