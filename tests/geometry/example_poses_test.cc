// Tests of the example sets (geometry/example_poses.h): their sizes, masks
// and faces, and the motions that relate their poses.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "shellspace/geometry/example_poses.h"

namespace shellspace {
namespace {

TEST(ExamplePosesTest, EverySetIsValid) {
  const std::map<std::string, int> vertices = {
      {"finger", 721}, {"plate", 323}, {"cylinder", 576}, {"collection", 321}};
  ASSERT_EQ(ExampleSetNames().size(), vertices.size());
  for (const auto& [name, description] : ExampleSetNames()) {
    SCOPED_TRACE(name);
    const ExampleSet set = MakeExampleSet(name);
    EXPECT_EQ(set.name, name);
    EXPECT_EQ(set.description, description);
    ASSERT_GE(set.shapes.size(), 2u);
    const int n = set.shapes[0].second.rows();
    EXPECT_EQ(n, vertices.at(name));
    EXPECT_GE(set.faces.minCoeff(), 0);
    EXPECT_LT(set.faces.maxCoeff(), n);
    // Every vertex is in a face.
    std::set<int> used(set.faces.data(), set.faces.data() + set.faces.size());
    EXPECT_EQ(static_cast<int>(used.size()), n);
    ASSERT_FALSE(set.mask.empty());
    for (const int v : set.mask) {
      EXPECT_GE(v, 0);
      EXPECT_LT(v, n);
    }
    for (size_t k = 1; k < set.shapes.size(); ++k) {
      EXPECT_EQ(set.shapes[k].second.rows(), n);
      EXPECT_TRUE(set.shapes[k].second.allFinite());
      // Each pose is another shape.
      EXPECT_GT((set.shapes[k].second - set.shapes[0].second).norm(), 0.1)
          << set.shapes[k].first;
    }
  }
}

TEST(ExamplePosesTest, TheTwistTurnsEachRingAboutTheAxis) {
  const ExampleSet set = MakeExampleSet("cylinder");
  const Positions& tube = set.shapes[0].second;
  const Positions& twisted = set.shapes[1].second;
  for (Eigen::Index i = 0; i < tube.rows(); ++i) {
    EXPECT_NEAR(twisted(i, 1), tube(i, 1), 1e-12);
    EXPECT_NEAR(std::hypot(twisted(i, 0), twisted(i, 2)),
                std::hypot(tube(i, 0), tube(i, 2)), 1e-12);
    // By 90 degrees times the height over the length (4).
    const double turn = std::atan2(tube(i, 0) * twisted(i, 2) -
                                       tube(i, 2) * twisted(i, 0),
                                   tube(i, 0) * twisted(i, 0) +
                                       tube(i, 2) * twisted(i, 2));
    EXPECT_NEAR(-turn, 0.5 * std::acos(-1.0) * tube(i, 1) / 4.0, 1e-9);
  }
}

TEST(ExamplePosesTest, ThePlateRollsAboutTwoAxesWithoutStretchingTheMidlines) {
  const ExampleSet set = MakeExampleSet("plate");
  const Positions& flat = set.shapes[0].second;
  for (Eigen::Index i = 0; i < flat.rows(); ++i) {
    EXPECT_EQ(flat(i, 2), 0);
    // Rolled about y: y kept; about x: x kept.
    EXPECT_NEAR(set.shapes[1].second(i, 1), flat(i, 1), 1e-12);
    EXPECT_NEAR(set.shapes[2].second(i, 0), flat(i, 0), 1e-12);
    // Both on a cylinder of radius 2 through the origin.
    const Eigen::RowVector3d a = set.shapes[1].second.row(i);
    const Eigen::RowVector3d b = set.shapes[2].second.row(i);
    EXPECT_NEAR(std::hypot(a(0), a(2) + 2), 2, 1e-12);
    EXPECT_NEAR(std::hypot(b(1), b(2) + 2), 2, 1e-12);
  }
}

TEST(ExamplePosesTest, TheCollectionBendsFurtherPoseByPose) {
  const ExampleSet set = MakeExampleSet("collection");
  ASSERT_EQ(set.shapes.size(), 7u);
  // The tip (the last vertex, the pole) moves further from the straight
  // pose's with each pose.
  const Eigen::Index tip = set.shapes[0].second.rows() - 1;
  double last = 0;
  for (size_t k = 1; k < set.shapes.size(); ++k) {
    const double moved = (set.shapes[k].second.row(tip) -
                          set.shapes[0].second.row(tip)).norm();
    EXPECT_GT(moved, last) << set.shapes[k].first;
    last = moved;
  }
  // The bottom ring (y = 0, in the mask) does not move.
  for (size_t k = 1; k < set.shapes.size(); ++k) {
    for (const int v : set.mask) {
      if (set.shapes[0].second(v, 1) != 0.0) continue;
      EXPECT_NEAR((set.shapes[k].second.row(v) - set.shapes[0].second.row(v)).norm(),
                  0, 1e-12);
    }
  }
}

TEST(ExamplePosesTest, AnUnknownNameIsAnInputErrorListingTheNames) {
  try {
    MakeExampleSet("cactus");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "no example set 'cactus' (known: finger, plate, cylinder, "
                 "collection)");
  }
}

}  // namespace
}  // namespace shellspace
