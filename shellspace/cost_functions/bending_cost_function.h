// Ceres cost function of one interior edge's bending energy.
#ifndef SHELLSPACE_COST_FUNCTIONS_BENDING_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BENDING_COST_FUNCTION_H_

#include "shellspace/cost_functions/shell/bending_element.h"
#include "shellspace/cost_functions/element_cost_function.h"

namespace shellspace {

// One residual r = sqrt(weight * 2 eta * 3 |Ebar|^2 / (abar_0 + abar_1)) *
// (theta - thetabar) for the edge flap (i, j, k, l) (geometry/topology.h).
// Parameter blocks (each 3 doubles): [Xbar_i, Xbar_j, Xbar_k, Xbar_l] if the
// reference is variable, then [X_i, X_j, X_k, X_l] if the deformed flap is
// variable; Jacobian blocks 1 x 3.
class BendingCostFunction : public ElementCostFunction<BendingElement, 4> {
 public:
  using ElementCostFunction::ElementCostFunction;

  // `fixed_reference` / `fixed_deformed`: 12 doubles or nullptr (variable).
  static BendingCostFunction* Create(double eta, const double* fixed_reference,
                                     const double* fixed_deformed,
                                     double weight = 1.0) {
    BendingElement element;
    element.eta = eta;
    return new BendingCostFunction(element, fixed_reference, fixed_deformed,
                                   weight);
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_BENDING_COST_FUNCTION_H_
