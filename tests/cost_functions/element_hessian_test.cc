// Degenerate elements: the hand-derived element second derivatives
// (ElementSecondDerivatives::Compute and the slice form of one inner
// shape) fail exactly where the dual path (Evaluate) fails, on a triangle
// and an edge flap with a vertex moved onto another.
#include <gtest/gtest.h>

#include <type_traits>
#include <utility>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "tests/testing/element_samples.h"

namespace shellspace {
namespace {

using testing::Derivatives;
using testing::kSides;

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
