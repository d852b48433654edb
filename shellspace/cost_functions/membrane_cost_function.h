// Ceres cost function of one triangle's membrane energy.
#ifndef SHELLSPACE_COST_FUNCTIONS_MEMBRANE_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_MEMBRANE_COST_FUNCTION_H_

#include "shellspace/cost_functions/element_cost_function.h"
#include "shellspace/cost_functions/shell/membrane_element.h"

namespace shellspace {

// Four residuals r with 1/2 |r|^2 = weight * abar W(G) for the triangle
// (i, j, k) (docs/math.md, "Membrane energy"; membrane_law.h), W the law
// `Law`; for the neo-Hookean law (MembraneCostFunction)
//   r = sqrt(weight) (w (a - c), 2 w b, sqrt(2 mu abar) psi(sqrt d),
//                     sqrt(lambda abar / 2) psi(d)),
// for the St. Venant-Kirchhoff law (st_venant_kirchhoff_law.h) residuals
// linear in the distortion (a, b, c).
// Parameter blocks (each 3 doubles, one vertex): [Xbar_i, Xbar_j, Xbar_k] if
// the reference is variable, then [X_i, X_j, X_k] if the deformed triangle is
// variable; Jacobian blocks are 4 x 3 row-major. Units: residuals scale like
// length (energy like area).
template <class Law>
class MembraneCostFunctionOf
    : public ElementCostFunction<MembraneElementOf<Law>, 3> {
 public:
  using ElementCostFunction<MembraneElementOf<Law>, 3>::ElementCostFunction;

  // `fixed_reference` / `fixed_deformed`: 9 doubles (x_i, x_j, x_k) for a side
  // that is data, nullptr for a side given as parameter blocks.
  static MembraneCostFunctionOf* Create(const Law& law,
                                        const double* fixed_reference,
                                        const double* fixed_deformed,
                                        double weight = 1.0) {
    MembraneElementOf<Law> element;
    element.law = law;
    return new MembraneCostFunctionOf(element, fixed_reference,
                                      fixed_deformed, weight);
  }
};

// The cost function of the specification's (neo-Hookean) law.
using MembraneCostFunction = MembraneCostFunctionOf<NeoHookeanLaw>;

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_MEMBRANE_COST_FUNCTION_H_
