// The Jacobian check of one element's cost function (MembraneCostFunction,
// BendingCostFunction), shared by the gradient tests of the cost functions
// on random elements and on the elements of real meshes: the cost function
// built with both sides variable or one of them fixed, and its Jacobians
// against ceres::GradientChecker (testing::CostFunctionJacobianError).
#ifndef SHELLSPACE_TESTS_TESTING_ELEMENT_COST_CHECK_H_
#define SHELLSPACE_TESTS_TESTING_ELEMENT_COST_CHECK_H_

#include <ceres/cost_function.h>

#include <memory>
#include <vector>

namespace shellspace::testing {

// Which arguments of an element's cost function are parameter blocks.
enum class Mode { kBothVariable, kReferenceFixed, kDeformedFixed };

// The cost function (weight 1.7) of `element` on the coordinates `ref` and
// `def` (kVertices x 3 each, vertex-major), with the sides `mode` leaves
// variable as parameter blocks; their pointers (one per vertex, reference
// first) in `params`.
template <class Cost, int kVertices, class Element>
std::unique_ptr<ceres::CostFunction> MakeCost(const Element& element,
                                              std::vector<double>& ref,
                                              std::vector<double>& def,
                                              Mode mode,
                                              std::vector<double*>* params) {
  params->clear();
  const double* fixed_ref =
      mode == Mode::kReferenceFixed ? ref.data() : nullptr;
  const double* fixed_def = mode == Mode::kDeformedFixed ? def.data() : nullptr;
  for (int v = 0; v < kVertices && !fixed_ref; ++v) {
    params->push_back(ref.data() + 3 * v);
  }
  for (int v = 0; v < kVertices && !fixed_def; ++v) {
    params->push_back(def.data() + 3 * v);
  }
  return std::make_unique<Cost>(element, fixed_ref, fixed_def, 1.7);
}

// The normwise relative Jacobian error of `cost` at `params`
// (CostFunctionJacobianError), EXPECTed below `tolerance`; returns it.
double CheckJacobian(const ceres::CostFunction& cost,
                     const std::vector<double*>& params, double tolerance);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_ELEMENT_COST_CHECK_H_
