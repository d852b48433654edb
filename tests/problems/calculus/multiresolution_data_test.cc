// Multiresolution geodesics: the shared decimation, the deformation-transfer
// prolongation, and the multiresolution result against the single-level
// optimum of the same problem.
#include "shellspace/problems/calculus/multiresolution.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/problems/calculus/deformation_transfer.h"
#include "shellspace/problems/calculus/shared_decimation.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

double MinFaceArea(const Faces& faces, const Positions& x) {
  double smallest = HUGE_VAL;
  for (int f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d e1 =
        (x.row(faces(f, 1)) - x.row(faces(f, 0))).transpose();
    const Eigen::Vector3d e2 =
        (x.row(faces(f, 2)) - x.row(faces(f, 0))).transpose();
    smallest = std::min(smallest, 0.5 * e1.cross(e2).norm());
  }
  return smallest;
}

TEST(SharedDecimationTest, SurvivorsKeepTheirPositionsInEveryShape) {
  const Mesh a = testing::LoadData("plate/plate4SD.ply");
  const Mesh b = testing::LoadData("plate/plate4SD_rolledA.ply");
  const std::vector<int> locked = {0, 1, 2};
  const int target = a.num_vertices() / 4;
  const SharedDecimation level =
      DecimateShared(a.faces, {a.positions, b.positions}, target, locked);
  EXPECT_LE(level.num_vertices(), target);
  EXPECT_GT(level.num_vertices(), target / 2);
  ASSERT_EQ(level.shapes.size(), 2u);
  for (int i = 0; i < level.num_vertices(); ++i) {
    const int v = level.survivors[i];
    EXPECT_EQ(level.shapes[0].row(i), a.positions.row(v));
    EXPECT_EQ(level.shapes[1].row(i), b.positions.row(v));
  }
  for (int v : locked) {
    EXPECT_NE(std::find(level.survivors.begin(), level.survivors.end(), v),
              level.survivors.end())
        << v;
  }
  // A valid shell on both shapes: manifold, consistently oriented, no
  // degenerate triangle; Euler characteristic of the disc kept.
  Mesh coarse{level.shapes[0], level.faces};
  const Topology topology = Topology::Build(coarse);
  EXPECT_EQ(level.num_vertices() - int(topology.edges.size()) +
                int(level.faces.rows()),
            1);
  EXPECT_GT(MinFaceArea(level.faces, level.shapes[0]), 0);
  EXPECT_GT(MinFaceArea(level.faces, level.shapes[1]), 0);
  // Same orientation as the fine mesh: the flat plate's normals agree.
  const Eigen::Vector3d fine_normal =
      (a.positions.row(a.faces(0, 1)) - a.positions.row(a.faces(0, 0)))
          .transpose()
          .cross(
              (a.positions.row(a.faces(0, 2)) - a.positions.row(a.faces(0, 0)))
                  .transpose());
  for (int f = 0; f < level.faces.rows(); ++f) {
    const Positions& x = level.shapes[0];
    const Eigen::Vector3d n =
        (x.row(level.faces(f, 1)) - x.row(level.faces(f, 0)))
            .transpose()
            .cross((x.row(level.faces(f, 2)) - x.row(level.faces(f, 0)))
                       .transpose());
    EXPECT_GT(n.dot(fine_normal), 0) << f;
  }
}

TEST(ProlongationTest, IdentityAndRigidMotionsAreReproducedExactly) {
  const Mesh a = testing::LoadData("sphere/unitSphere1.ply");
  const SharedDecimation level =
      DecimateShared(a.faces, {a.positions}, a.num_vertices() / 4);
  const Prolongation prolong(a.faces, a.positions, level, level.shapes[0]);
  const double scale = a.positions.cwiseAbs().maxCoeff();
  EXPECT_LT(
      (prolong.Apply(level.shapes[0]) - a.positions).cwiseAbs().maxCoeff(),
      1e-12 * scale);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized())
          .toRotationMatrix();
  const Eigen::RowVector3d t(0.3, -1.2, 2.0);
  auto move = [&](const Positions& p) {
    Positions q = (p * r.transpose()).rowwise() + t;
    return q;
  };
  EXPECT_LT((prolong.Apply(move(level.shapes[0])) - move(a.positions))
                .cwiseAbs()
                .maxCoeff(),
            1e-10 * scale);
}

// On a problem where both run fast the multiresolution geodesic is the
// single-level optimum: the same E_K to 1e-8 and the same shapes to 1e-6
// (relative, up to a rigid motion), with the masked vertices in place.
TEST(MultiresolutionGeodesicTest, EqualsTheSingleLevelOptimum) {
  // The default material: eta = 0.01.
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  for (bool masked : {false, true}) {
    GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
    if (masked) {
      const double x0 = a.positions.col(0).minCoeff();
      for (int v = 0; v < a.num_vertices(); ++v) {
        if (a.positions(v, 0) < x0 + 1e-9) input.fixed_vertices.push_back(v);
      }
    }
    const SolverSettings settings = testing::TightSettings(1e-10);
    const GeodesicResult single = SolveGeodesic(space, input, settings);
    MultiresolutionSettings multires;
    multires.levels = 2;  // 121 -> 30 vertices; a third level would have 8
    multires.min_vertices = 20;
    const MultiresolutionResult multi =
        SolveGeodesicMultiresolution(space, input, settings, multires);
    ASSERT_EQ(multi.levels.size(), 2u) << masked;
    EXPECT_LE(multi.levels[0].vertices, 30);
    EXPECT_EQ(multi.levels[1].vertices, a.num_vertices());
    EXPECT_TRUE(multi.levels[1].converged);
    EXPECT_NEAR(multi.geodesic.path_energy, single.path_energy,
                1e-8 * single.path_energy)
        << masked;
    for (int k = 1; k < input.steps; ++k) {
      EXPECT_LT(RelativeDistanceUpToRigidMotion(multi.geodesic.path[k],
                                                single.path[k]),
                1e-6)
          << masked << " " << k;
      for (int v : input.fixed_vertices) {
        EXPECT_EQ(multi.geodesic.path[k].row(v), single.path[k].row(v));
      }
    }
  }
}

}  // namespace
}  // namespace shellspace
