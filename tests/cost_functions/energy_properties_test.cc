// The smoothness of psi, the signed square root of the divergence
// x - 1 - log x in the membrane law: its square and its derivative on both
// sides of the series switch.
#include <gtest/gtest.h>

#include <cmath>

#include "shellspace/cost_functions/shell/membrane_law.h"

namespace shellspace {
namespace {

// psi^2 = x - 1 - log x on both sides of the series switch (|x - 1| = 0.1),
// and psi' agrees with central differences.
TEST(EnergyPropertiesTest, SignedSqrtDivergence) {
  for (double x : {0.3, 0.8, 0.9, 0.9000001, 0.95, 0.999, 1.0, 1.0001, 1.05,
                   1.0999999, 1.1, 1.1000001, 2.5, 10.0}) {
    double psi, dpsi;
    SignedSqrtDivergence(x, &psi, &dpsi);
    const double f = x - 1 - std::log(x);
    EXPECT_NEAR(psi * psi, f, 1e-15 + 1e-12 * f) << x;
    EXPECT_GE(psi * (x - 1), 0.0) << x;
    const double h = 1e-6;
    double p_plus, p_minus, unused;
    SignedSqrtDivergence(x + h, &p_plus, &unused);
    SignedSqrtDivergence(x - h, &p_minus, &unused);
    EXPECT_NEAR(dpsi, (p_plus - p_minus) / (2 * h), 1e-7) << x;
  }
  double psi, dpsi;
  SignedSqrtDivergence(1.0, &psi, &dpsi);
  EXPECT_NEAR(dpsi, 1 / std::sqrt(2.0), 1e-15);
}

}  // namespace
}  // namespace shellspace
