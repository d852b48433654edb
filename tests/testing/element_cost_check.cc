#include "tests/testing/element_cost_check.h"

#include <gtest/gtest.h>

#include "tests/testing/derivative_check.h"

namespace shellspace::testing {

double CheckJacobian(const ceres::CostFunction& cost,
                     const std::vector<double*>& params, double tolerance) {
  const double relative = CostFunctionJacobianError(cost, params);
  EXPECT_LT(relative, tolerance);
  return relative;
}

}  // namespace shellspace::testing
