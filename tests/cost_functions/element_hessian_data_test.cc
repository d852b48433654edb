// The hand-derived element second derivatives (MembraneElement and
// BendingElement ::SecondDerivatives, used by ElementSecondDerivatives::
// Compute) on elements of real meshes (reference != deformed; sampled by
// tests/testing/element_samples.h):
//   - equal to the dual-number differentiation of the analytic gradient
//     (ComputeWithDualNumbers) to 1e-12, all four blocks and both gradients;
//   - equal to central differences of the analytic gradient;
//   - the Gauss-Newton model: J^T J of the residuals' central differences,
//     positive semidefinite, the exact Hessian at rest;
//   - the Rows options compute only what they are asked, bit for bit the
//     same numbers; the weight scales every output linearly;
//   - one inner shape's slice blocks equal the two terms added;
// and every check has a negative twin: one entry of a block perturbed, the
// same helper must report it.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <type_traits>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/element_samples.h"

namespace shellspace {
namespace {

using testing::Derivatives;
using testing::ElementHessianTest;
using testing::ElementSample;
using testing::ForSampledElements;
using testing::kSides;

static_assert(HasAnalyticSecondDerivatives<MembraneElement>::value, "");
static_assert(HasAnalyticSecondDerivatives<BendingElement>::value, "");
static_assert(HasSliceSecondDerivatives<MembraneElement>::value, "");
static_assert(HasSliceSecondDerivatives<BendingElement>::value, "");

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
testing::VectorFunction Gradients(const E& element, const ElementSample<kV>& s,
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
testing::VectorFunction Residuals(const E& element, const ElementSample<kV>& s,
                                  ShellSide active) {
  return [&element, s, active](const Eigen::VectorXd& x) {
    const ElementSample<kV> at = s.With(active, x);
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
Eigen::MatrixXd ResidualJacobian(const E& element, const ElementSample<kV>& s,
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
Eigen::Matrix<double, 3 * kV, 1> Between(const ElementSample<kV>& s) {
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
    ::testing::ValuesIn(testing::ElementHessianMeshPairs()));

}  // namespace
}  // namespace shellspace
