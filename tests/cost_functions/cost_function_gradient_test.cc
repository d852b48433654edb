// Analytic Jacobians of the membrane and bending cost functions against
// ceres::GradientChecker (central differences) on random triangles and
// edge flaps, for every combination of variable reference / deformed
// arguments, and the checker's negative twin (a wrong Jacobian fails it).
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <random>

#include "shellspace/cost_functions/bending_cost_function.h"
#include "shellspace/cost_functions/membrane_cost_function.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/element_cost_check.h"

namespace shellspace {
namespace {

using testing::MakeCost;
using testing::Mode;

// testing::CheckJacobian of the element's cost function at (ref, def) with
// every side variable, the reference fixed and the deformed fixed.
template <class Cost, int kVertices, class Element>
void CheckEveryMode(const Element& element, std::vector<double>& ref,
                    std::vector<double>& def, double tolerance) {
  for (Mode mode :
       {Mode::kBothVariable, Mode::kReferenceFixed, Mode::kDeformedFixed}) {
    std::vector<double*> params;
    auto cost = MakeCost<Cost, kVertices>(element, ref, def, mode, &params);
    testing::CheckJacobian(*cost, params, tolerance);
  }
}

TEST(CostFunctionGradientTest, RandomTriangles) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  MembraneElement membrane;
  membrane.law.mu = 1.3;
  membrane.law.lambda = 0.7;
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> ref(9), def(9);
    for (double& x : ref) x = u(rng);
    for (int i = 0; i < 9; ++i) def[i] = ref[i] + 0.3 * u(rng);
    // Include near-rest configurations (series branch of psi).
    if (trial % 5 == 0) {
      for (int i = 0; i < 9; ++i) def[i] = ref[i] + 1e-3 * u(rng);
    }
    CheckEveryMode<MembraneCostFunction, 3>(membrane, ref, def, 1e-8);
  }
}

TEST(CostFunctionGradientTest, RandomEdgeFlaps) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  BendingElement bending;
  bending.eta = 0.3;
  for (int trial = 0; trial < 50; ++trial) {
    // A reasonable flap: edge along x, opposite vertices on either side.
    std::vector<double> ref = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0};
    std::vector<double> def(12);
    for (double& x : ref) x += 0.3 * u(rng);
    for (int i = 0; i < 12; ++i) def[i] = ref[i] + 0.4 * u(rng);
    CheckEveryMode<BendingCostFunction, 4>(bending, ref, def, 1e-8);
  }
}

// The negative twin of the checks above: a Jacobian wrong in one entry,
// through the same helper and tolerance, must fail -- for both elements and
// every argument mode.
TEST(CostFunctionGradientTest, CheckerDetectsWrongJacobian) {
  std::vector<double> ref = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0};
  std::vector<double> def = {0, 0, 0.1, 1.1, 0, 0, 0.5, 1, 0.3, 0.4, -1, 0};
  for (int which = 0; which < 2; ++which) {
    for (Mode mode :
         {Mode::kBothVariable, Mode::kReferenceFixed, Mode::kDeformedFixed}) {
      std::vector<double*> params;
      std::unique_ptr<ceres::CostFunction> inner =
          which == 0 ? MakeCost<MembraneCostFunction, 3>(MembraneElement(), ref,
                                                         def, mode, &params)
                     : MakeCost<BendingCostFunction, 4>(BendingElement(), ref,
                                                        def, mode, &params);
      // The correct one passes the helper ...
      EXPECT_LT(testing::CostFunctionJacobianError(*inner, params), 1e-8);
      // ... and one entry off by 1e-4 of the Jacobian's scale does not.
      testing::CostFunctionWithWrongJacobian wrong(std::move(inner), 1, 2,
                                                   1e-4);
      EXPECT_GT(testing::CostFunctionJacobianError(wrong, params), 1e-8)
          << which << int(mode);
    }
  }
}

}  // namespace
}  // namespace shellspace
