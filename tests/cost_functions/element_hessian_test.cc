// The hand-derived element second derivatives (MembraneElement and
// BendingElement ::SecondDerivatives, used by ElementSecondDerivatives::
// Compute) on elements of real meshes (reference != deformed):
//   - equal to the dual-number differentiation of the analytic gradient
//     (ComputeWithDualNumbers) to 1e-12, all four blocks and both gradients;
//   - equal to central differences of the analytic gradient;
//   - D_1^2 and D_2^2 symmetric, the two mixed blocks transposes;
//   - equivariant under rotations of either argument, H(RX) = R H(X) R^T,
//     and, infinitesimally, H (w x X) = w x g (translations: H t = 0);
//   - the Rows options compute only what they are asked, bit for bit the
//     same numbers;
//   - degenerate elements rejected exactly as by Evaluate;
// and every check has a negative twin: one entry of a block perturbed, the
// same helper must report it.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <random>
#include <type_traits>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

static_assert(HasAnalyticSecondDerivatives<MembraneElement>::value, "");
static_assert(HasAnalyticSecondDerivatives<BendingElement>::value, "");
static_assert(HasSliceSecondDerivatives<MembraneElement>::value, "");
static_assert(HasSliceSecondDerivatives<BendingElement>::value, "");

struct Pair {
  const char* reference;
  const char* deformed;
};

// One element of a real mesh pair: its coordinates on both sides (vertex-
// major, 3 kV each).
template <int kV>
struct Sample {
  Eigen::Matrix<double, 3 * kV, 1> ref, def;
  double edge = 0;  // the longest reference edge of the stencil (length scale)

  // This sample with the coordinates of the `active` side replaced by x.
  Sample With(ShellSide active, const Eigen::VectorXd& x) const {
    Sample moved = *this;
    (active == ShellSide::kReference ? moved.ref : moved.def) = x;
    return moved;
  }

  // d->Compute of `element` at this sample (false if it is degenerate).
  template <class Element>
  bool Compute(const Element& element, ShellSide active, double weight,
               ElementSecondDerivatives<kV>* d,
               typename ElementSecondDerivatives<kV>::Rows rows =
                   ElementSecondDerivatives<kV>::Rows::kBoth) const {
    return d->Compute(element, ref.data(), def.data(), active, weight, rows);
  }
};

template <int kV>
using Derivatives = ElementSecondDerivatives<kV>;

// Every stride-th element of `group`, up to `count` of them.
template <class Group>
std::vector<Sample<Group::kVertices>> SampleElements(const Group& group,
                                                     const Positions& ref,
                                                     const Positions& def,
                                                     int count) {
  constexpr int kV = Group::kVertices;
  std::vector<Sample<kV>> out;
  const int stride = std::max(1, group.size() / count);
  for (int e = 0; e < group.size() && static_cast<int>(out.size()) < count;
       e += stride) {
    Sample<kV> s;
    GatherCoordinates(ref, group.stencils[e], s.ref.data());
    GatherCoordinates(def, group.stencils[e], s.def.data());
    for (int a = 0; a < kV; ++a) {
      for (int b = 0; b < a; ++b) {
        s.edge = std::max(s.edge, (s.ref.template segment<3>(3 * a) -
                                   s.ref.template segment<3>(3 * b))
                                      .norm());
      }
    }
    out.push_back(s);
  }
  return out;
}

// Calls check(element, sample) for sampled elements of every term of W on
// the pair (each mesh pair, membrane and bending, eta of the default
// material).
template <class Check>
void ForSampledElements(const Pair& pair, int count, Check&& check) {
  const Mesh ref = testing::LoadData(pair.reference);
  const Mesh def = testing::LoadData(pair.deformed);
  const ShellSpace space = testing::MakeSpace(ref);
  int groups = 0;
  space.elements().ForEachGroup([&](const auto& group) {
    ++groups;
    for (const auto& s :
         SampleElements(group, ref.positions, def.positions, count)) {
      check(group.element, s);
    }
  });
  ASSERT_EQ(groups, 2);  // membrane and bending
}

class ElementHessianTest : public ::testing::TestWithParam<Pair> {};

constexpr ShellSide kSides[] = {ShellSide::kReference, ShellSide::kDeformed};

// Largest entry of the four blocks (the element's Hessian scale).
template <int kV>
double HessianScale(const Derivatives<kV>& active_ref,
                    const Derivatives<kV>& active_def) {
  return std::max(std::max(active_ref.d_grad_reference.cwiseAbs().maxCoeff(),
                           active_ref.d_grad_deformed.cwiseAbs().maxCoeff()),
                  std::max(active_def.d_grad_reference.cwiseAbs().maxCoeff(),
                           active_def.d_grad_deformed.cwiseAbs().maxCoeff()));
}

TEST_P(ElementHessianTest, AnalyticEqualsDualNumbers) {
  double worst_block = 0, worst_gradient = 0, worst_energy = 0;
  int elements = 0;
  ForSampledElements(GetParam(), 60, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    Derivatives<kV> analytic[2], dual[2];
    for (int a = 0; a < 2; ++a) {
      ASSERT_TRUE(s.Compute(element, kSides[a], 1.0, &analytic[a]));
      ASSERT_TRUE(dual[a].ComputeWithDualNumbers(element, s.ref.data(),
                                                 s.def.data(), kSides[a], 1.0));
    }
    const double h_scale = HessianScale(dual[0], dual[1]);
    ASSERT_GT(h_scale, 0);
    for (int a = 0; a < 2; ++a) {
      // Each block relative to its own largest entry.
      for (const auto& [x, y] :
           {std::make_pair(&analytic[a].d_grad_reference,
                           &dual[a].d_grad_reference),
            std::make_pair(&analytic[a].d_grad_deformed,
                           &dual[a].d_grad_deformed)}) {
        const double error = testing::NormwiseRelativeError(*x, *y);
        worst_block = std::max(worst_block, error);
        EXPECT_LT(error, 1e-12) << kV << " active " << a;
      }
      // Gradients (which vanish at rest) relative to the gradient scale of
      // the element, |H| times its longest edge; the energy relative to
      // |H| edge^2.
      for (const auto& [x, y] :
           {std::make_pair(&analytic[a].grad_reference,
                           &dual[a].grad_reference),
            std::make_pair(&analytic[a].grad_deformed,
                           &dual[a].grad_deformed)}) {
        const double error =
            testing::NormwiseRelativeError(*x, *y, h_scale * s.edge);
        worst_gradient = std::max(worst_gradient, error);
        EXPECT_LT(error, 1e-12) << kV << " active " << a;
      }
      const double energy_error = std::abs(analytic[a].energy - dual[a].energy) /
                                  (h_scale * s.edge * s.edge);
      worst_energy = std::max(worst_energy, energy_error);
      EXPECT_LT(energy_error, 1e-12) << kV;
    }
    ++elements;
  });
  EXPECT_GT(elements, 100);
  std::cout << elements << " elements: worst block " << worst_block
            << ", gradient " << worst_gradient << ", energy " << worst_energy
            << "\n";
}

// Negative twin of AnalyticEqualsDualNumbers: one entry of each block off by
// 1e-10 of the block's scale; the same helper reports it.
TEST_P(ElementHessianTest, WrongBlockIsCaughtByDualComparison) {
  int elements = 0;
  ForSampledElements(GetParam(), 5, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    for (ShellSide side : kSides) {
      Derivatives<kV> analytic, dual;
      ASSERT_TRUE(s.Compute(element, side, 1.0, &analytic));
      ASSERT_TRUE(dual.ComputeWithDualNumbers(element, s.ref.data(),
                                              s.def.data(), side, 1.0));
      for (auto* block :
           {&analytic.d_grad_reference, &analytic.d_grad_deformed}) {
        auto& same = block == &analytic.d_grad_reference
                         ? dual.d_grad_reference
                         : dual.d_grad_deformed;
        Eigen::MatrixXd wrong = *block;
        wrong(1, 3 * kV - 2) += 1e-10 * same.cwiseAbs().maxCoeff();
        EXPECT_GT(testing::NormwiseRelativeError(wrong, same), 1e-12);
      }
    }
    ++elements;
  });
  EXPECT_GT(elements, 5);
}

// Both gradients of one element as functions of the coordinates of the
// active side (analytic second derivatives not involved: Compute's
// gradients are checked against the dual path above).
template <class E, int kV>
testing::VectorFunction Gradients(const E& element, const Sample<kV>& s,
                                  ShellSide active) {
  return [&element, s, active](const Eigen::VectorXd& x) {
    Derivatives<kV> d;
    Eigen::VectorXd out(6 * kV);
    if (!s.With(active, x).Compute(element, active, 1.0, &d)) {
      out.setConstant(NAN);
      return out;
    }
    out << d.grad_reference, d.grad_deformed;
    return out;
  };
}

TEST_P(ElementHessianTest, MatchesCentralDifferencesOfTheGradient) {
  double worst = 0;
  int elements = 0;
  ForSampledElements(GetParam(), 12, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    std::vector<int> probes(3 * kV);
    for (int j = 0; j < 3 * kV; ++j) probes[j] = j;
    for (ShellSide side : kSides) {
      Derivatives<kV> d;
      ASSERT_TRUE(s.Compute(element, side, 1.0, &d));
      const testing::DerivativeColumn columns = [d](int j) {
        Eigen::VectorXd c(6 * kV);
        c << d.d_grad_reference.col(j), d.d_grad_deformed.col(j);
        return c;
      };
      const double scale = std::max(d.d_grad_reference.cwiseAbs().maxCoeff(),
                                    d.d_grad_deformed.cwiseAbs().maxCoeff());
      const Eigen::VectorXd x =
          side == ShellSide::kReference ? s.ref : s.def;
      const double h = 1e-6 * s.edge;
      const double error = testing::CentralDifferenceError(
          Gradients(element, s, side), x, columns, probes, h, scale);
      worst = std::max(worst, error);
      EXPECT_LT(error, 1e-6) << kV << " side " << int(side);
      // Negative twin: one entry off by 1e-4 of the scale.
      EXPECT_GT(testing::CentralDifferenceError(
                    Gradients(element, s, side), x,
                    testing::WrongInOneEntry(columns, 2, 4, 1e-4 * scale),
                    probes, h, scale),
                1e-6);
    }
    ++elements;
  });
  EXPECT_GT(elements, 20);
  std::cout << elements << " elements: worst central-difference error "
            << worst << "\n";
}

// The residual vector of one element as a function of the coordinates of
// the active side (for the Gauss-Newton check: J by central differences of
// the residuals, independent of Evaluate's analytic Jacobians).
template <class E, int kV>
testing::VectorFunction Residuals(const E& element, const Sample<kV>& s,
                                  ShellSide active) {
  return [&element, s, active](const Eigen::VectorXd& x) {
    const Sample<kV> at = s.With(active, x);
    Vec3<double> r3[kV], d3[kV];
    for (int v = 0; v < kV; ++v) {
      r3[v] = at.ref.template segment<3>(3 * v);
      d3[v] = at.def.template segment<3>(3 * v);
    }
    Eigen::VectorXd out(E::kNumResiduals);
    if (!element.Evaluate(r3, d3, out.data(),
                          static_cast<typename E::template Jacobian<double>*>(
                              nullptr),
                          static_cast<typename E::template Jacobian<double>*>(
                              nullptr))) {
      out.setConstant(NAN);
    }
    return out;
  };
}

// Central-difference residual Jacobian (kNumResiduals x 3 kV) of one side.
template <class E, int kV>
Eigen::MatrixXd ResidualJacobian(const E& element, const Sample<kV>& s,
                                 ShellSide side) {
  const testing::VectorFunction r = Residuals(element, s, side);
  const Eigen::VectorXd x = side == ShellSide::kReference ? s.ref : s.def;
  const double h = 1e-6 * s.edge;
  Eigen::MatrixXd j(E::kNumResiduals, 3 * kV);
  for (int c = 0; c < 3 * kV; ++c) {
    Eigen::VectorXd plus = x, minus = x;
    plus(c) += h;
    minus(c) -= h;
    j.col(c) = (r(plus) - r(minus)) / (2 * h);
  }
  return j;
}

// HessianModel::kGaussNewton: every block is weight J_X^T J_active with J the
// residual Jacobian (here by central differences of the residuals), the model
// is positive semidefinite, and at rest (deformed = reference, r = 0) it is the
// exact Hessian (docs/math.md, "Membrane energy"). Its twin: away from rest the
// exact blocks differ from J^T J by more than the same helper's bound, so the
// rest comparison can fail.
TEST_P(ElementHessianTest, GaussNewtonModelIsJTransposeJ) {
  double worst_fd = 0, worst_rest = 0, most_negative = 0, largest_gap = 0;
  int elements = 0;
  ForSampledElements(GetParam(), 12, [&](const auto& element, const auto& s) {
    using E = std::decay_t<decltype(element)>;
    constexpr int kV = E::kNumVertices;
    const double weight = 0.7;
    const Eigen::MatrixXd j_ref = ResidualJacobian(element, s, ShellSide::kReference);
    const Eigen::MatrixXd j_def = ResidualJacobian(element, s, ShellSide::kDeformed);
    Eigen::MatrixXd full(6 * kV, 6 * kV);  // (ref, def) x (ref, def)
    for (ShellSide side : kSides) {
      Derivatives<kV> gn, exact;
      ASSERT_TRUE(gn.ComputeModel(HessianModel::kGaussNewton, element,
                                  s.ref.data(), s.def.data(), side, weight));
      ASSERT_TRUE(exact.ComputeModel(HessianModel::kExact, element,
                                     s.ref.data(), s.def.data(), side, weight));
      const Eigen::MatrixXd& j_active =
          side == ShellSide::kReference ? j_ref : j_def;
      const Eigen::MatrixXd expect_ref = weight * j_ref.transpose() * j_active;
      const Eigen::MatrixXd expect_def = weight * j_def.transpose() * j_active;
      const double scale = std::max(expect_ref.cwiseAbs().maxCoeff(),
                                    expect_def.cwiseAbs().maxCoeff());
      for (const auto& [x, y] : {std::make_pair(Eigen::MatrixXd(gn.d_grad_reference), expect_ref),
                                 std::make_pair(Eigen::MatrixXd(gn.d_grad_deformed), expect_def)}) {
        const double error = testing::NormwiseRelativeError(x, y, scale);
        worst_fd = std::max(worst_fd, error);
        EXPECT_LT(error, 1e-6) << kV;
      }
      // Energy and gradients are the exact ones (relative to the element's
      // scales |H| edge^2 and |H| edge, as in AnalyticEqualsDualNumbers:
      // both vanish at rest).
      const double h_scale =
          std::max(exact.d_grad_reference.cwiseAbs().maxCoeff(),
                   exact.d_grad_deformed.cwiseAbs().maxCoeff());
      EXPECT_LT(std::abs(gn.energy - exact.energy),
                1e-12 * h_scale * s.edge * s.edge);
      EXPECT_LT(testing::NormwiseRelativeError(gn.grad_deformed,
                                               exact.grad_deformed,
                                               h_scale * s.edge),
                1e-12);
      largest_gap = std::max(
          largest_gap, testing::NormwiseRelativeError(gn.d_grad_deformed,
                                                      exact.d_grad_deformed));
      const int col = side == ShellSide::kReference ? 0 : 3 * kV;
      full.block(0, col, 3 * kV, 3 * kV) = gn.d_grad_reference;
      full.block(3 * kV, col, 3 * kV, 3 * kV) = gn.d_grad_deformed;
      // At rest the model is the Hessian.
      Derivatives<kV> gn_rest, exact_rest;
      ASSERT_TRUE(gn_rest.ComputeModel(HessianModel::kGaussNewton, element,
                                       s.ref.data(), s.ref.data(), side, weight));
      ASSERT_TRUE(exact_rest.Compute(element, s.ref.data(), s.ref.data(), side,
                                     weight));
      for (const auto& [x, y] :
           {std::make_pair(&gn_rest.d_grad_reference, &exact_rest.d_grad_reference),
            std::make_pair(&gn_rest.d_grad_deformed, &exact_rest.d_grad_deformed)}) {
        const double error = testing::NormwiseRelativeError(*x, *y);
        worst_rest = std::max(worst_rest, error);
        EXPECT_LT(error, 1e-12) << kV;
      }
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
        0.5 * (full + full.transpose()));
    const double ratio = eigen.eigenvalues().minCoeff() /
                         eigen.eigenvalues().cwiseAbs().maxCoeff();
    most_negative = std::min(most_negative, ratio);
    EXPECT_GT(ratio, -1e-12) << kV;
    ++elements;
  });
  EXPECT_GT(elements, 20);
  // The twin: away from rest the same comparison fails for some element.
  EXPECT_GT(largest_gap, 1e-6);
  std::cout << elements << " elements: J^T J vs central differences "
            << worst_fd << ", vs the Hessian at rest " << worst_rest
            << ", smallest eigenvalue / largest " << most_negative
            << ", largest Hessian - J^T J gap away from rest " << largest_gap
            << "\n";
}

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

// Rows::kReference / kDeformed compute their half bit for bit as kBoth and
// leave the other half untouched.
TEST_P(ElementHessianTest, RowsComputeOnlyWhatIsAsked) {
  ForSampledElements(GetParam(), 10, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    using Rows = typename Derivatives<kV>::Rows;
    for (ShellSide side : kSides) {
      Derivatives<kV> both;
      ASSERT_TRUE(s.Compute(element, side, 2.0, &both));
      for (Rows rows : {Rows::kReference, Rows::kDeformed}) {
        Derivatives<kV> part;
        part.grad_reference.setConstant(7);
        part.grad_deformed.setConstant(7);
        part.d_grad_reference.setConstant(7);
        part.d_grad_deformed.setConstant(7);
        ASSERT_TRUE(s.Compute(element, side, 2.0, &part, rows));
        const bool ref = rows == Rows::kReference;
        EXPECT_TRUE((ref ? part.grad_reference : part.grad_deformed) ==
                    (ref ? both.grad_reference : both.grad_deformed));
        EXPECT_TRUE((ref ? part.d_grad_reference : part.d_grad_deformed) ==
                    (ref ? both.d_grad_reference : both.d_grad_deformed));
        EXPECT_TRUE((ref ? part.grad_deformed : part.grad_reference).isConstant(7));
        EXPECT_TRUE(
            (ref ? part.d_grad_deformed : part.d_grad_reference).isConstant(7));
      }
    }
  });
}

// The weight scales every output linearly (the path Hessian passes K).
TEST_P(ElementHessianTest, WeightScalesLinearly) {
  ForSampledElements(GetParam(), 5, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    Derivatives<kV> one, eight;
    ASSERT_TRUE(s.Compute(element, ShellSide::kDeformed, 1.0, &one));
    ASSERT_TRUE(s.Compute(element, ShellSide::kDeformed, 8.0, &eight));
    EXPECT_LT(testing::NormwiseRelativeError(eight.d_grad_deformed,
                                             8.0 * one.d_grad_deformed),
              1e-15);
    EXPECT_LT(testing::NormwiseRelativeError(eight.d_grad_reference,
                                             8.0 * one.d_grad_reference),
              1e-15);
  });
}

// One inner shape's blocks from an element (ElementSliceSecondDerivatives):
// the element's SliceSecondDerivatives, which shares X's geometry between
// its two terms, against ComputeBySides (the two SecondDerivatives passes,
// added), with X between the pair's shapes P = reference and N = deformed.
// The largest normwise relative difference of the diagonal and the
// coupling blocks.
template <int kV>
double SliceDifference(const ElementSliceSecondDerivatives<kV>& a,
                       const ElementSliceSecondDerivatives<kV>& b) {
  return std::max(testing::NormwiseRelativeError(a.diagonal, b.diagonal),
                  testing::NormwiseRelativeError(a.coupling, b.coupling));
}

template <int kV>
Eigen::Matrix<double, 3 * kV, 1> Between(const Sample<kV>& s) {
  Eigen::Matrix<double, 3 * kV, 1> x = 0.5 * (s.ref + s.def);
  for (int j = 0; j < 3 * kV; ++j) x(j) += 0.05 * s.edge * std::sin(1.7 * j);
  return x;
}

TEST_P(ElementHessianTest, SliceBlocksEqualTheTwoTermsAdded) {
  double worst = 0;
  int elements = 0;
  ForSampledElements(GetParam(), 12, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    const Eigen::Matrix<double, 3 * kV, 1> x = Between(s);
    for (const bool coupling : {true, false}) {
      ElementSliceSecondDerivatives<kV> shared, sides;
      shared.Compute(HessianModel::kExact, element, s.ref.data(), x.data(),
                     s.def.data(), 3.0, coupling);
      sides.ComputeBySides(HessianModel::kExact, element, s.ref.data(),
                           x.data(), s.def.data(), 3.0, coupling);
      ASSERT_TRUE(shared.before_ok && shared.after_ok);
      ASSERT_TRUE(sides.before_ok && sides.after_ok);
      if (!coupling) sides.coupling = shared.coupling;  // not computed
      worst = std::max(worst, SliceDifference(shared, sides));
      // Twin: one diagonal entry off by 1e-6 of the block's scale.
      ElementSliceSecondDerivatives<kV> wrong = sides;
      wrong.diagonal(1, 2) += 1e-6 * sides.diagonal.cwiseAbs().maxCoeff();
      EXPECT_GT(SliceDifference(shared, wrong), 1e-8);
    }
    ++elements;
  });
  EXPECT_GT(elements, 10);
  EXPECT_LT(worst, 1e-12);
}

// The Gauss-Newton model has no shared form: Compute is ComputeBySides, bit
// for bit.
TEST_P(ElementHessianTest, GaussNewtonSliceBlocksAreTheTwoTermsAdded) {
  ForSampledElements(GetParam(), 4, [&](const auto& element, const auto& s) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    const Eigen::Matrix<double, 3 * kV, 1> x = Between(s);
    ElementSliceSecondDerivatives<kV> model, sides;
    model.Compute(HessianModel::kGaussNewton, element, s.ref.data(), x.data(),
                  s.def.data(), 2.0, true);
    sides.ComputeBySides(HessianModel::kGaussNewton, element, s.ref.data(),
                         x.data(), s.def.data(), 2.0, true);
    EXPECT_EQ(SliceDifference(model, sides), 0.0);
  });
}

INSTANTIATE_TEST_SUITE_P(
    RealMeshes, ElementHessianTest,
    ::testing::Values(Pair{"cactus/cactus0.ply", "cactus/cactus1.ply"},
                      Pair{"finger/finger0.ply", "finger/finger1.ply"},
                      Pair{"faces/neutral.ply", "faces/smile.ply"}));

// Degenerate elements: the analytic path fails exactly where the dual path
// (Evaluate) fails.
TEST(ElementHessianDegenerateTest, SameVerdictAsEvaluate) {
  const MembraneElement membrane;
  const BendingElement bending;
  // A triangle and a flap; then the same with vertex 2 moved onto vertex 0
  // (membrane: deformed or reference degenerate; bending: reference).
  const double tri[9] = {0, 0, 0, 1, 0, 0, 0.2, 0.9, 0};
  const double tri_bad[9] = {0, 0, 0, 1, 0, 0, 0, 0, 0};
  const double flap[12] = {0, 0, 0, 1, 0, 0, 0.3, 0.8, 0.1, 0.6, -0.9, 0.2};
  const double flap_bad[12] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0.6, -0.9, 0.2};
  for (ShellSide side : kSides) {
    Derivatives<3> m;
    EXPECT_TRUE(m.Compute(membrane, tri, tri_bad + 0, side, 1.0) ==
                m.ComputeWithDualNumbers(membrane, tri, tri_bad, side, 1.0));
    EXPECT_FALSE(m.Compute(membrane, tri, tri_bad, side, 1.0));
    EXPECT_FALSE(m.Compute(membrane, tri_bad, tri, side, 1.0));
    EXPECT_FALSE(m.ComputeWithDualNumbers(membrane, tri_bad, tri, side, 1.0));
    EXPECT_TRUE(m.Compute(membrane, tri, tri, side, 1.0));
    Derivatives<4> b;
    EXPECT_FALSE(b.Compute(bending, flap_bad, flap, side, 1.0));
    EXPECT_FALSE(b.ComputeWithDualNumbers(bending, flap_bad, flap, side, 1.0));
    EXPECT_TRUE(b.Compute(bending, flap, flap, side, 1.0));
  }
}

// A slice's verdicts are each side's: a degenerate P fails only the term
// before X, a degenerate N only the term after it, a degenerate X both.
TEST(ElementHessianDegenerateTest, SliceVerdictsAreThoseOfEachSide) {
  const MembraneElement membrane;
  const BendingElement bending;
  const double tri[9] = {0, 0, 0, 1, 0, 0, 0.2, 0.9, 0};
  const double tri_bad[9] = {0, 0, 0, 1, 0, 0, 0, 0, 0};
  const double flap[12] = {0, 0, 0, 1, 0, 0, 0.3, 0.8, 0.1, 0.6, -0.9, 0.2};
  const double flap_bad[12] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0.6, -0.9, 0.2};
  const auto verdicts = [](const auto& element, const double* p,
                           const double* x, const double* n) {
    constexpr int kV = std::decay_t<decltype(element)>::kNumVertices;
    ElementSliceSecondDerivatives<kV> shared, sides;
    shared.Compute(HessianModel::kExact, element, p, x, n, 1.0, true);
    sides.ComputeBySides(HessianModel::kExact, element, p, x, n, 1.0, true);
    EXPECT_EQ(shared.before_ok, sides.before_ok);
    EXPECT_EQ(shared.after_ok, sides.after_ok);
    return std::make_pair(shared.before_ok, shared.after_ok);
  };
  using Verdicts = std::pair<bool, bool>;
  EXPECT_EQ(verdicts(membrane, tri_bad, tri, tri), Verdicts(false, true));
  EXPECT_EQ(verdicts(membrane, tri, tri, tri_bad), Verdicts(true, false));
  EXPECT_EQ(verdicts(membrane, tri, tri_bad, tri), Verdicts(false, false));
  EXPECT_EQ(verdicts(membrane, tri, tri, tri), Verdicts(true, true));
  // The bending element checks its reference flap: P for the term before,
  // X for the term after.
  EXPECT_EQ(verdicts(bending, flap_bad, flap, flap), Verdicts(false, true));
  EXPECT_EQ(verdicts(bending, flap, flap_bad, flap), Verdicts(true, false));
  EXPECT_EQ(verdicts(bending, flap, flap, flap), Verdicts(true, true));
}

}  // namespace
}  // namespace shellspace
