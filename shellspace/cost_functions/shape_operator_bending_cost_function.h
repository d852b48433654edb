// Ceres cost function of one face's shape-operator bending energy.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHAPE_OPERATOR_BENDING_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_SHAPE_OPERATOR_BENDING_COST_FUNCTION_H_

#include "shellspace/cost_functions/element_cost_function.h"
#include "shellspace/cost_functions/shell/shape_operator_element.h"

namespace shellspace {

// Three residuals r with 1/2 |r|^2 = weight * eta * abar (alpha (tr M)^2 +
// beta tr(M^2)), M = Gbar^-1 (H - Hbar) (docs/math.md, "Bending energy: two
// models"; shell/shape_operator_element.h): with Gbar = L L^T and
// K = L^-1 (H - Hbar) L^-T,
//   r = sqrt(weight eta) (sqrt(2 abar (alpha + beta/2)) (k11 + k22),
//                         sqrt(abar beta) (k11 - k22), 2 sqrt(abar beta) k12).
// The face has kInterior = 0..3 interior edges; its stencil is (X_0, X_1,
// X_2, P_0, .., P_{kInterior-1}): the face rotated so that its interior edges
// are the edges 0 .. kInterior-1 (edge i opposite X_i), P_i across edge i.
// Parameter blocks (each 3 doubles, one vertex): the 3 + kInterior reference
// vertices in stencil order if the reference is variable, then the 3 +
// kInterior deformed vertices if the deformed shell is variable; Jacobian
// blocks 3 x 3 row-major.
template <int kInterior>
class ShapeOperatorBendingCostFunction
    : public ElementCostFunction<ShapeOperatorElement<kInterior>,
                                 3 + kInterior> {
 public:
  using Base =
      ElementCostFunction<ShapeOperatorElement<kInterior>, 3 + kInterior>;
  using Base::Base;

  // `fixed_reference` / `fixed_deformed`: 3 (3 + kInterior) doubles for a
  // side that is data, nullptr for a side given as parameter blocks.
  static ShapeOperatorBendingCostFunction* Create(
      double eta, double alpha, double beta, const double* fixed_reference,
      const double* fixed_deformed, double weight = 1.0) {
    ShapeOperatorElement<kInterior> element;
    element.eta = eta;
    element.alpha = alpha;
    element.beta = beta;
    return new ShapeOperatorBendingCostFunction(element, fixed_reference,
                                                fixed_deformed, weight);
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHAPE_OPERATOR_BENDING_COST_FUNCTION_H_
