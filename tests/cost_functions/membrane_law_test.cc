// The membrane laws (membrane_law.h) on their own, for every registered law:
//   - 1/2 |r|^2 equals the closed-form energy to round-off on random
//     distortions;
//   - the residual Jacobian in (a, b, c, abar) equals central differences,
//     and a wrong entry is reported by the same helper (negative twin);
//   - the energy vanishes at rest with zero residuals;
// and the St. Venant-Kirchhoff law against its closed forms: a uniaxial
// stretch s (G = diag(s^2, 1)) costs abar (mu + lambda/2) (s^2 - 1)^2 / 4, a
// pure shear (G = [[1, g], [g, 1]]) abar mu g^2 / 2; the names round-trip.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/membrane_law.h"
#include "tests/testing/derivative_check.h"

namespace shellspace {
namespace {

// A distortion (a, b, c) = G in an orthonormal reference frame, with its
// reference area.
struct Distortion {
  double a, b, c, area;
};

// No Jacobian wanted (Evaluate's last argument; T is deduced from it too).
constexpr double (*kNoJacobian)[4] = nullptr;

std::vector<Distortion> RandomDistortions(int count) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  std::vector<Distortion> out;
  while (static_cast<int>(out.size()) < count) {
    // G = F^T F for a random 2 x 2 F near the identity: positive definite.
    Eigen::Matrix2d f = Eigen::Matrix2d::Identity();
    f(0, 0) += u(random);
    f(0, 1) += u(random);
    f(1, 0) += u(random);
    f(1, 1) += u(random);
    const Eigen::Matrix2d g = f.transpose() * f;
    if (g.determinant() < 1e-3) continue;
    out.push_back({g(0, 0), g(0, 1), g(1, 1), 0.5 + std::abs(u(random))});
  }
  return out;
}

template <class Law>
double HalfSquaredResiduals(const Law& law, const Distortion& g) {
  double r[4];
  EXPECT_TRUE(law.Evaluate(g.a, g.b, g.c, g.area, r, kNoJacobian));
  return 0.5 * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
}

template <class Law>
double ClosedForm(const Law& law, const Distortion& g) {
  double e = NAN;
  EXPECT_TRUE(law.Energy(g.a + g.c, g.a * g.c - g.b * g.b, g.area, &e));
  return e;
}

// The residuals as a function of q = (a, b, c, abar), and the analytic
// Jacobian's columns (optionally one entry wrong).
template <class Law>
double JacobianError(const Law& law, const Distortion& g,
                     const testing::WrongEntry* wrong) {
  const testing::VectorFunction residuals = [&law](const Eigen::VectorXd& q) {
    Eigen::VectorXd r(4);
    if (!law.Evaluate(q(0), q(1), q(2), q(3), r.data(), kNoJacobian)) {
      r.setConstant(NAN);
    }
    return r;
  };
  double r[4], jacobian[4][4];
  EXPECT_TRUE(law.Evaluate(g.a, g.b, g.c, g.area, r, jacobian));
  testing::DerivativeColumn column = [jacobian](int q) {
    Eigen::VectorXd out(4);
    for (int m = 0; m < 4; ++m) out(m) = jacobian[m][q];
    return out;
  };
  if (wrong) {
    column = testing::WrongInOneEntry(column, wrong->row, wrong->col,
                                      wrong->offset);
  }
  const Eigen::Vector4d q(g.a, g.b, g.c, g.area);
  return testing::CentralDifferenceError(residuals, q, column, {0, 1, 2, 3},
                                         1e-6);
}

template <class Law>
void CheckLaw(const char* name) {
  SCOPED_TRACE(name);
  Law law;
  law.mu = 1.3;
  law.lambda = 0.7;
  double worst_energy = 0, worst_jacobian = 0;
  for (const Distortion& g : RandomDistortions(50)) {
    const double closed = ClosedForm(law, g);
    worst_energy = std::max(
        worst_energy, std::abs(HalfSquaredResiduals(law, g) - closed) /
                          std::max(1.0, std::abs(closed)));
    worst_jacobian = std::max(worst_jacobian, JacobianError(law, g, nullptr));
    // Negative twin: one entry of the Jacobian off by 1e-4.
    const testing::WrongEntry wrong{2, 1, 1e-4};
    EXPECT_GT(JacobianError(law, g, &wrong), 1e-6);
  }
  EXPECT_LT(worst_energy, 1e-13);
  EXPECT_LT(worst_jacobian, 1e-7);
  // Rest: zero energy, zero residuals.
  const Distortion rest{1, 0, 1, 0.8};
  double r[4];
  ASSERT_TRUE(law.Evaluate(rest.a, rest.b, rest.c, rest.area, r, kNoJacobian));
  for (double x : r) EXPECT_NEAR(x, 0, 1e-15);
  EXPECT_NEAR(ClosedForm(law, rest), 0, 1e-15);
  // A degenerate distortion is rejected by both.
  double e;
  EXPECT_FALSE(law.Evaluate(1.0, 1.0, 1.0, 0.8, r, kNoJacobian));
  EXPECT_FALSE(law.Energy(2.0, 0.0, 0.8, &e));
}

TEST(MembraneLawTest, ResidualsEnergiesAndJacobiansOfEveryLaw) {
  int laws = 0;
#define SHELLSPACE_CHECK_LAW(type, value, name) \
  CheckLaw<type>(name);                         \
  ++laws;
  SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_CHECK_LAW)
#undef SHELLSPACE_CHECK_LAW
  EXPECT_EQ(laws, 2);
}

TEST(MembraneLawTest, StVenantKirchhoffClosedForms) {
  StVenantKirchhoffLaw law;
  law.mu = 1.3;
  law.lambda = 0.7;
  const double area = 0.6;
  for (double s : {0.5, 0.9, 1.2, 2.0}) {
    const Distortion stretch{s * s, 0, 1, area};
    const double expected =
        area * (law.mu + law.lambda / 2) * (s * s - 1) * (s * s - 1) / 4;
    EXPECT_NEAR(HalfSquaredResiduals(law, stretch), expected, 1e-14) << s;
    EXPECT_NEAR(ClosedForm(law, stretch), expected, 1e-14) << s;
  }
  for (double shear : {0.1, 0.4}) {
    const Distortion g{1, shear, 1, area};
    EXPECT_NEAR(ClosedForm(law, g), area * law.mu * shear * shear / 2, 1e-15);
  }
  // The neo-Hookean law differs from it away from rest but agrees to second
  // order at rest: both are mu tr(E^2) + lambda/2 (tr E)^2 + O(|E|^3).
  NeoHookeanLaw neo;
  neo.mu = law.mu;
  neo.lambda = law.lambda;
  const double eps = 1e-3;
  const Distortion small{1 + 2 * eps, eps, 1 - eps, area};
  const double svk = ClosedForm(law, small), nh = ClosedForm(neo, small);
  EXPECT_NEAR(nh / svk, 1, 1e-2);
  const Distortion large{4, 0, 1, area};
  EXPECT_GT(std::abs(ClosedForm(neo, large) / ClosedForm(law, large) - 1),
            0.1);
}

TEST(MembraneLawTest, NamesRoundTrip) {
  for (MembraneLaw law :
       {MembraneLaw::kNeoHookean, MembraneLaw::kStVenantKirchhoff}) {
    MembraneLaw parsed = MembraneLaw::kNeoHookean;
    ASSERT_TRUE(ParseMembraneLaw(MembraneLawName(law), &parsed));
    EXPECT_EQ(parsed, law);
  }
  EXPECT_STREQ(MembraneLawName(MembraneLaw::kStVenantKirchhoff),
               "st-venant-kirchhoff");
  MembraneLaw unchanged = MembraneLaw::kStVenantKirchhoff;
  EXPECT_FALSE(ParseMembraneLaw("hookean", &unchanged));
  EXPECT_EQ(unchanged, MembraneLaw::kStVenantKirchhoff);
  EXPECT_EQ(MembraneLawNames(), "neo-hookean or st-venant-kirchhoff");
}

}  // namespace
}  // namespace shellspace
