// The bending energy of a flap folded to nearly +-pi (BendingElement with
// DihedralAngleChange, geometry/element_geometry.h): theta - thetabar is the
// turn the flap made, also across atan2's branch cut, so the energy is the
// closed form 3 eta dphi^2 |E|^2 / (a_0 + a_1) of a hinge turned by dphi on
// both sides of the cut, its gradient and Hessian match central differences
// there (with negative twins through the same helpers), and the Ceres cost
// of the elastic energy sees no jump.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>

#include "shellspace/cost_functions/shell/bending_element.h"
#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/geometry/element_geometry.h"
#include "tests/testing/derivative_check.h"

namespace shellspace {
namespace {

constexpr double kDegree = M_PI / 180.0;

// The flap (i, j, k, l) of a unit hinge along the x axis: k = (1/2, 1, 0),
// l = k turned by phi about the edge (phi = pi: flat; phi -> 0: folded
// shut). Its dihedral angle is pi - phi in (-pi, pi] (a flat flap has
// theta = 0, a nearly shut one +-pi).
Eigen::Matrix<double, 12, 1> Hinge(double phi) {
  Eigen::Matrix<double, 12, 1> x;
  x << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, std::cos(phi), -std::sin(phi);
  return x;
}

// The unweighted term of BendingElement::Energy.
double BendingTerm(const Eigen::Matrix<double, 12, 1>& ref,
                   const Eigen::Matrix<double, 12, 1>& def) {
  const StencilPositions<4> x(ref.data(), def.data());
  double e = NAN;
  EXPECT_TRUE(BendingElement().Energy(x.ref, x.def, &e));
  return e;
}

TEST(DihedralAngleChangeTest, RepresentativeInMinusPiToPi) {
  EXPECT_DOUBLE_EQ(DihedralAngleChange(179 * kDegree, -179 * kDegree),
                   358 * kDegree - 2 * M_PI);
  EXPECT_NEAR(DihedralAngleChange(-179 * kDegree, 179 * kDegree),
              2 * kDegree, 1e-15);
  EXPECT_DOUBLE_EQ(DihedralAngleChange(0.3, 0.1), 0.3 - 0.1);
  // The boundary: pi is represented by -pi.
  EXPECT_DOUBLE_EQ(DihedralAngleChange(M_PI, 0.0), -M_PI);
}

// A hinge folded to 2 degrees (theta_bar = 178 deg) closing or opening by
// dphi: the reference areas are 1/2 each and |E| = 1, so the term is
// (dphi)^2 * 1 / (1/3) = 3 dphi^2 -- on both sides of the cut, which the
// closing hinge crosses once it passes phi = 0.
TEST(DihedralAngleChangeTest, FoldedHingeEnergyIsTheClosedFormAcrossTheCut) {
  const double phi_bar = 2 * kDegree;
  for (const double dphi_degrees : {-1.0, -1.9, -2.5, -3.0, -6.0, 1.0, 5.0}) {
    const double dphi = dphi_degrees * kDegree;
    const double term = BendingTerm(Hinge(phi_bar), Hinge(phi_bar + dphi));
    EXPECT_NEAR(term, 3 * dphi * dphi, 1e-12 * 3 * dphi * dphi + 1e-15)
        << "dphi " << dphi_degrees << " deg";
  }
}

// The residual's Jacobian (Evaluate) and the element Hessian
// (SecondDerivatives) against central differences at a deformed hinge that
// has crossed the cut (theta_bar = 178 deg, theta = -178 deg), and their
// twins with one wrong entry through the same helper.
TEST(DihedralAngleChangeTest, DerivativesAcrossTheCutMatchCentralDifferences) {
  const BendingElement bending;
  const Eigen::Matrix<double, 12, 1> ref = Hinge(2 * kDegree);
  const Eigen::Matrix<double, 12, 1> def = Hinge(-2 * kDegree);
  const auto residual = [&](const Eigen::VectorXd& x) {
    StencilPositions<4> p(ref.data(), x.data());
    double r = NAN;
    EXPECT_TRUE(bending.Evaluate<double>(p.ref, p.def, &r, nullptr, nullptr));
    return Eigen::VectorXd::Constant(1, r);
  };
  StencilPositions<4> p(ref.data(), def.data());
  double r = NAN;
  BendingElement::Jacobian<double> jac;
  ASSERT_TRUE(bending.Evaluate<double>(p.ref, p.def, &r, nullptr, &jac));
  // The turn is 4 degrees, not 356.
  EXPECT_NEAR(std::abs(r) / std::sqrt(2 * bending.eta * 3.0), 4 * kDegree,
              1e-12);
  const testing::DerivativeColumn analytic = [&](int j) {
    return Eigen::VectorXd::Constant(1, jac(0, j));
  };
  std::vector<int> all(12);
  for (int j = 0; j < 12; ++j) all[j] = j;
  const Eigen::VectorXd x = def;
  EXPECT_LT(testing::CentralDifferenceError(residual, x, analytic, all, 1e-7),
            1e-7);
  EXPECT_GT(testing::CentralDifferenceError(
                residual, x,
                testing::WrongInOneEntry(analytic, 0, 10, 1e-3 * jac.norm()),
                all, 1e-7),
            1e-5);

  // The Hessian of the deformed side against differences of its gradient.
  ElementSecondDerivatives<4> d;
  ASSERT_TRUE(d.Compute(bending, ref.data(), def.data(), ShellSide::kDeformed,
                        1.0));
  const auto gradient = [&](const Eigen::VectorXd& y) {
    ElementSecondDerivatives<4> at;
    EXPECT_TRUE(at.Compute(bending, ref.data(), y.data(),
                           ShellSide::kDeformed, 1.0));
    return Eigen::VectorXd(at.grad_deformed);
  };
  const testing::DerivativeColumn hessian = [&](int j) {
    return Eigen::VectorXd(d.d_grad_deformed.col(j));
  };
  const double scale = d.d_grad_deformed.cwiseAbs().maxCoeff();
  EXPECT_LT(testing::CentralDifferenceError(gradient, x, hessian, all, 1e-6,
                                            scale),
            1e-6);
  EXPECT_GT(testing::CentralDifferenceError(
                gradient, x,
                testing::WrongInOneEntry(hessian, 4, 7, 1e-3 * scale), all,
                1e-6, scale),
            1e-4);
}

}  // namespace
}  // namespace shellspace
