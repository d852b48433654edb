// Symmetries of the hand-derived element second derivatives
// (ElementSecondDerivatives::Compute) on elements of real meshes (sampled
// by tests/testing/element_samples.h):
//   - D_1^2 and D_2^2 symmetric, the two mixed blocks transposes;
//   - equivariant under rotations of either argument, H(RX) = R H(X) R^T,
//     and, infinitesimally, H (w x X) = w x g (translations: H t = 0);
// and every check has a negative twin: one entry of a block perturbed, the
// same helper must report it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <iostream>
#include <random>
#include <type_traits>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/element_samples.h"

namespace shellspace {
namespace {

using testing::Derivatives;
using testing::ElementHessianTest;
using testing::ElementSample;
using testing::ForSampledElements;
using testing::kSides;

// max |H - H^T| / max |H|.
double Asymmetry(const Eigen::MatrixXd& h) {
  return testing::NormwiseRelativeError(h, h.transpose());
}

TEST_P(ElementHessianTest, SymmetricPureAndTransposedMixedBlocks) {
  double worst = 0;
  ForSampledElements(GetParam(), 60, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    Derivatives<kV> r, d;
    ASSERT_TRUE(s.Compute(element, ShellSide::kReference, 1.0, &r));
    ASSERT_TRUE(s.Compute(element, ShellSide::kDeformed, 1.0, &d));
    const double e11 = Asymmetry(r.d_grad_reference);
    const double e22 = Asymmetry(d.d_grad_deformed);
    // d_Xbar d_X (rows Xbar) from the deformed-active call, its transpose
    // (rows X) from the reference-active call.
    const double mixed = testing::NormwiseRelativeError(
        r.d_grad_deformed.transpose(), d.d_grad_reference);
    worst = std::max({worst, e11, e22, mixed});
    EXPECT_LT(e11, 1e-12) << kV;
    EXPECT_LT(e22, 1e-12) << kV;
    EXPECT_LT(mixed, 1e-12) << kV;
    // Negative twins: one off-diagonal entry perturbed by 1e-10.
    Eigen::MatrixXd wrong = d.d_grad_deformed;
    wrong(0, 4) += 1e-10 * wrong.cwiseAbs().maxCoeff();
    EXPECT_GT(Asymmetry(wrong), 1e-12);
    wrong = d.d_grad_reference;
    wrong(0, 4) += 1e-10 * wrong.cwiseAbs().maxCoeff();
    EXPECT_GT(testing::NormwiseRelativeError(r.d_grad_deformed.transpose(),
                                             wrong),
              1e-12);
  });
  std::cout << "worst asymmetry / mixed mismatch " << worst << "\n";
}

// The block-diagonal I_kV (x) R.
template <int kV>
Eigen::Matrix<double, 3 * kV, 3 * kV> BlockRotation(const Eigen::Matrix3d& r) {
  Eigen::Matrix<double, 3 * kV, 3 * kV> out;
  out.setZero();
  for (int v = 0; v < kV; ++v) out.template block<3, 3>(3 * v, 3 * v) = r;
  return out;
}

template <int kV>
Eigen::Matrix<double, 3 * kV, 1> Transform(
    const Eigen::Matrix<double, 3 * kV, 1>& x, const Eigen::Matrix3d& r,
    const Eigen::Vector3d& t) {
  Eigen::Matrix<double, 3 * kV, 1> out;
  for (int v = 0; v < kV; ++v) {
    out.template segment<3>(3 * v) = r * x.template segment<3>(3 * v) + t;
  }
  return out;
}

// n independent standard normal samples, drawn in order (not as arguments
// of one call, whose evaluation order C++ leaves open).
template <int n>
Eigen::Matrix<double, n, 1> StandardNormal(std::mt19937& rng) {
  std::normal_distribution<double> n01;
  Eigen::Matrix<double, n, 1> x;
  for (int i = 0; i < n; ++i) x(i) = n01(rng);
  return x;
}

// A uniformly distributed rotation: a normalised Gaussian quaternion.
Eigen::Matrix3d RandomRotation(std::mt19937& rng) {
  const Eigen::Vector4d q = StandardNormal<4>(rng);
  return Eigen::Quaterniond(q(0), q(1), q(2), q(3))
      .normalized()
      .toRotationMatrix();
}

// Rigid motions: with (R, t) applied to the deformed shape,
//   D_2^2(Xbar, RX + t) = Rb D_2^2 Rb^T,  d_Xbar d_X(Xbar, RX + t) =
//   (d_Xbar d_X) Rb^T,  D_1^2(Xbar, RX + t) = D_1^2,   Rb = I (x) R,
// and with (R, t) applied to the reference, the mirror statements.
TEST_P(ElementHessianTest, EquivariantUnderRigidMotions) {
  std::mt19937 rng(7);
  double worst = 0;
  ForSampledElements(GetParam(), 40, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    const Eigen::Matrix3d rot = RandomRotation(rng);
    const Eigen::Vector3d t = StandardNormal<3>(rng);
    const auto rb = BlockRotation<kV>(rot);
    Derivatives<kV> base[2], moved_def[2], moved_ref[2];
    const auto ref_moved = Transform<kV>(s.ref, rot, t);
    const auto def_moved = Transform<kV>(s.def, rot, t);
    for (int a = 0; a < 2; ++a) {
      ASSERT_TRUE(s.Compute(element, kSides[a], 1.0, &base[a]));
      ASSERT_TRUE(moved_def[a].Compute(element, s.ref.data(),
                                       def_moved.data(), kSides[a], 1.0));
      ASSERT_TRUE(moved_ref[a].Compute(element, ref_moved.data(),
                                       s.def.data(), kSides[a], 1.0));
    }
    const auto& b = base;
    using M = Eigen::MatrixXd;
    // d_grad of the gradient on side k (0: reference, 1: deformed).
    auto d_grad = [](const Derivatives<kV>& d, int k) -> const auto& {
      return k == 1 ? d.d_grad_deformed : d.d_grad_reference;
    };
    // The four statements with side m moved (o the other side): the blocks
    // of the moved side's Hessian (active m) and of the other's (active o).
    auto errors_moved = [&](const Derivatives<kV>* moved, int m) {
      const int o = 1 - m;
      return std::array<double, 4>{
          testing::NormwiseRelativeError(
              d_grad(moved[m], m), M(rb * d_grad(b[m], m) * rb.transpose())),
          testing::NormwiseRelativeError(d_grad(moved[m], o),
                                         M(d_grad(b[m], o) * rb.transpose())),
          testing::NormwiseRelativeError(d_grad(moved[o], o), d_grad(b[o], o)),
          testing::NormwiseRelativeError(d_grad(moved[o], m),
                                         M(rb * d_grad(b[o], m))),
      };
    };
    for (const std::array<double, 4>& errors :
         {errors_moved(moved_def, 1), errors_moved(moved_ref, 0)}) {
      for (double e : errors) {
        worst = std::max(worst, e);
        EXPECT_LT(e, 1e-10) << kV;
      }
    }
    // Negative twin: a wrong D_2^2 is not equivariant.
    M wrong = b[1].d_grad_deformed;
    wrong(2, 5) += 1e-8 * wrong.cwiseAbs().maxCoeff();
    EXPECT_GT(testing::NormwiseRelativeError(moved_def[1].d_grad_deformed,
                                             M(rb * wrong * rb.transpose())),
              1e-10);
  });
  std::cout << "worst rigid-motion equivariance error " << worst << "\n";
}

// The field w x X_v (+ t) on the stencil of x.
template <int kV>
Eigen::Matrix<double, 3 * kV, 1> RigidField(
    const Eigen::Matrix<double, 3 * kV, 1>& x, const Eigen::Vector3d& w,
    const Eigen::Vector3d& t) {
  Eigen::Matrix<double, 3 * kV, 1> out;
  for (int v = 0; v < kV; ++v)
    out.template segment<3>(3 * v) = w.cross(x.template segment<3>(3 * v)) + t;
  return out;
}

// |H v - expected|_inf / (max |H| |v|_inf): the infinitesimal equivariance
// check (the derivative of g(RX + t) = R g(X) at R = I: H (w x X + t) =
// w x g).
double InfinitesimalError(const Eigen::MatrixXd& h, const Eigen::VectorXd& v,
                          const Eigen::VectorXd& expected) {
  return testing::NormwiseRelativeError(
      h * v, expected, h.cwiseAbs().maxCoeff() * v.cwiseAbs().maxCoeff());
}

TEST_P(ElementHessianTest, InfinitesimalRigidMotions) {
  std::mt19937 rng(9);
  double worst = 0;
  ForSampledElements(GetParam(), 60, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    using V = Eigen::Matrix<double, 3 * kV, 1>;
    const Eigen::Vector3d w = StandardNormal<3>(rng);
    const Eigen::Vector3d t = StandardNormal<3>(rng);
    Derivatives<kV> r, d;
    ASSERT_TRUE(s.Compute(element, ShellSide::kReference, 1.0, &r));
    ASSERT_TRUE(s.Compute(element, ShellSide::kDeformed, 1.0, &d));
    const V zero = V::Zero();
    const V w_def = RigidField<kV>(s.def, w, t);
    const V w_ref = RigidField<kV>(s.ref, w, t);
    // w x g (the translation part drops out: g is translation invariant).
    const V wg_def = RigidField<kV>(d.grad_deformed, w, Eigen::Vector3d::Zero());
    const V wg_ref = RigidField<kV>(r.grad_reference, w, Eigen::Vector3d::Zero());
    const double errors[] = {
        InfinitesimalError(d.d_grad_deformed, w_def, wg_def),  // D_2^2
        InfinitesimalError(d.d_grad_reference, w_def, zero),   // d_Xbar d_X
        InfinitesimalError(r.d_grad_reference, w_ref, wg_ref), // D_1^2
        InfinitesimalError(r.d_grad_deformed, w_ref, zero),    // d_X d_Xbar
    };
    for (double e : errors) {
      worst = std::max(worst, e);
      EXPECT_LT(e, 1e-11) << kV;
    }
    // Negative twin: one entry of D_2^2 off by 1e-8 of its scale.
    Eigen::MatrixXd wrong = d.d_grad_deformed;
    wrong(1, 1) += 1e-8 * wrong.cwiseAbs().maxCoeff();
    EXPECT_GT(InfinitesimalError(wrong, w_def, wg_def), 1e-11);
  });
  std::cout << "worst infinitesimal rigid-motion error " << worst << "\n";
}

INSTANTIATE_TEST_SUITE_P(
    RealMeshes, ElementHessianTest,
    ::testing::ValuesIn(testing::ElementHessianMeshPairs()));

}  // namespace
}  // namespace shellspace
