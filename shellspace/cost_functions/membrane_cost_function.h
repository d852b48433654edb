// Ceres cost function of one triangle's membrane energy.
#ifndef SHELLSPACE_COST_FUNCTIONS_MEMBRANE_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_MEMBRANE_COST_FUNCTION_H_

#include "shellspace/cost_functions/element_cost_function.h"
#include "shellspace/cost_functions/shell/membrane_element.h"

namespace shellspace {

// Four residuals r with 1/2 |r|^2 = weight * abar W_m(G) for the triangle
// (i, j, k) (docs/math.md, "Membrane energy"; membrane_law.h):
//   r = sqrt(weight) (w (a - c), 2 w b, sqrt(2 mu abar) psi(sqrt d),
//                     sqrt(lambda abar / 2) psi(d)).
// Parameter blocks (each 3 doubles, one vertex): [Xbar_i, Xbar_j, Xbar_k] if
// the reference is variable, then [X_i, X_j, X_k] if the deformed triangle is
// variable; Jacobian blocks are 4 x 3 row-major. Units: residuals scale like
// length (energy like area).
class MembraneCostFunction : public ElementCostFunction<MembraneElement, 3> {
 public:
  using ElementCostFunction::ElementCostFunction;

  // `fixed_reference` / `fixed_deformed`: 9 doubles (x_i, x_j, x_k) for a side
  // that is data, nullptr for a side given as parameter blocks.
  static MembraneCostFunction* Create(const MembraneLaw& law,
                                      const double* fixed_reference,
                                      const double* fixed_deformed,
                                      double weight = 1.0) {
    MembraneElement element;
    element.law = law;
    return new MembraneCostFunction(element, fixed_reference, fixed_deformed,
                                    weight);
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_MEMBRANE_COST_FUNCTION_H_
