// CompareShapes (problems/calculus/shape_comparison.h) against closed forms:
// a rigid motion of the same shells gives zero distance and W = 0; moving
// the centre of the symmetric square4 by d gives max 4d/5, mean 8d/25 (the
// alignment shifts by the centroid's d/5); paths related by per-frame rigid
// motions have the same E_K; mismatched sides are an InputError.
#include <gtest/gtest.h>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/problems/calculus/shape_comparison.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

TEST(ShapeComparisonTest, RigidMotionIsEqual) {
  const testing::ShellPair pair =
      testing::LoadPair("simple/square4.ply", "simple/square4_bent.ply");
  const ShapeComparison c =
      CompareShapes(pair.space, {pair.end.positions},
                    {testing::RandomRigidMotion(pair.end.positions, 5)});
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_LT(c.max_distance, 1e-14);
  EXPECT_LT(c.relative_max_distance, 1e-14);
  EXPECT_NEAR(c.diameter, std::sqrt(2.0), 0.5);
  EXPECT_LT(std::abs(c.energy_a_to_b), 1e-14);  // round-off of the rotation
}

TEST(ShapeComparisonTest, MovedCentreVertexGivesTheClosedForm) {
  // square4: centre (0, 0, 0) and four corners (+-0.5, +-0.5, 0). b moves
  // the centre by d along z; the best rigid motion of b onto a is the
  // translation by -d/5 (symmetry: no rotation), so the centre is 4d/5 and
  // every corner d/5 away.
  const testing::ShellPair pair =
      testing::LoadPair("simple/square4.ply", "simple/square4.ply");
  const Positions a = pair.start.positions;
  ASSERT_EQ(a.rows(), 5);
  ASSERT_EQ(a.row(0).norm(), 0.0);
  const double d = 1e-3;
  Positions b = a;
  b(0, 2) += d;
  const ShapeComparison c = CompareShapes(pair.space, {a}, {b});
  EXPECT_NEAR(c.max_distance, 0.8 * d, 1e-12);
  EXPECT_NEAR(c.mean_distance, (0.8 + 4 * 0.2) / 5 * d, 1e-12);
  EXPECT_NEAR(c.relative_max_distance, 0.8 * d / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(c.energy_a_to_b,
              EvaluateDeformationEnergy(pair.space, a, b).total, 1e-18);
  EXPECT_GT(c.energy_a_to_b, 0.0);
}

TEST(ShapeComparisonTest, PathsUpToRigidMotionsPerFrame) {
  const testing::ShellPair pair =
      testing::LoadPair("simple/square4.ply", "simple/square4_bent.ply");
  const ShellPath a = LinearPath(pair.start.positions, pair.end.positions, 4);
  ShellPath b;
  for (size_t k = 0; k < a.size(); ++k) {
    b.push_back(testing::RandomRigidMotion(a[k], 10 + k));
  }
  const ShapeComparison equal = CompareShapes(pair.space, a, a);
  EXPECT_EQ(equal.max_distance, 0.0);
  EXPECT_EQ(equal.relative_energy_difference, 0.0);
  const ShapeComparison same = CompareShapes(pair.space, a, b);
  ASSERT_EQ(same.frames.size(), 5u);
  EXPECT_LT(same.max_distance, 1e-14);
  EXPECT_GT(same.energy_a, 1e-6);
  EXPECT_NEAR(same.energy_b, same.energy_a, 1e-12 * same.energy_a);
  EXPECT_LT(same.relative_energy_difference, 1e-12);
  // Another path between the same ends: distance only in the inner frames,
  // and a different E_K.
  ShellPath other = a;
  other[2].col(2) *= 1.5;
  const ShapeComparison differ = CompareShapes(pair.space, a, other);
  EXPECT_LT(differ.frames[0].max_distance, 1e-14);
  EXPECT_LT(differ.frames[4].max_distance, 1e-14);
  EXPECT_GT(differ.frames[2].max_distance, 1e-3);
  EXPECT_GT(differ.relative_energy_difference, 1e-3);
}

TEST(ShapeComparisonTest, MismatchedSidesAreInputErrors) {
  const testing::ShellPair pair =
      testing::LoadPair("simple/square4.ply", "simple/square4_bent.ply");
  const ShellPath a = LinearPath(pair.start.positions, pair.end.positions, 2);
  EXPECT_THROW(CompareShapes(pair.space, a, {a[0], a[1]}), InputError);
  EXPECT_THROW(CompareShapes(pair.space, {}, {}), InputError);
  EXPECT_THROW(CompareShapes(pair.space, {a[0]}, {a[0].topRows(3)}), InputError);
}

}  // namespace
}  // namespace shellspace
