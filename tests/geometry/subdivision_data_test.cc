// Midpoint subdivision and vertex rings: counts, Euler characteristic, area
// and energy invariants, carried masks.
#include "shellspace/geometry/subdivision.h"

#include <gtest/gtest.h>

#include <set>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/geometry/topology.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

double Area(const Mesh& m) {
  double a = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d e1 = m.vertex(m.faces(f, 1)) - m.vertex(m.faces(f, 0));
    const Eigen::Vector3d e2 = m.vertex(m.faces(f, 2)) - m.vertex(m.faces(f, 0));
    a += 0.5 * e1.cross(e2).norm();
  }
  return a;
}

TEST(SubdivisionTest, CountsEulerCharacteristicAndArea) {
  const Mesh m = testing::LoadData("sphere/unitSphere1.ply");
  const Topology topology = Topology::Build(m);
  const MidpointSubdivision sub(m.faces, m.num_vertices());
  EXPECT_EQ(sub.num_vertices(), m.num_vertices() + int(topology.edges.size()));
  EXPECT_EQ(sub.faces.rows(), 4 * m.num_faces());
  const Mesh fine{sub.Apply(m.positions), sub.faces};
  const Topology fine_topology = Topology::Build(fine);  // manifold, oriented
  EXPECT_EQ(fine.num_vertices() - int(fine_topology.edges.size()) +
                fine.num_faces(),
            2);
  // Each triangle splits into four of a quarter of its area.
  EXPECT_NEAR(Area(fine), Area(m), 1e-12 * Area(m));
  // W of a uniform stretch by s: membrane density depends only on s, so
  // W_mem scales like the area (which is unchanged) and bending vanishes.
  const ShellSpace coarse_space = testing::MakeSpace(m);
  const ShellSpace fine_space = testing::MakeSpace(fine);
  const Positions stretched = 1.1 * m.positions;
  const double w_coarse =
      EvaluateDeformationEnergy(coarse_space, m.positions, stretched).membrane;
  const double w_fine = EvaluateDeformationEnergy(
                            fine_space, fine.positions, sub.Apply(stretched))
                            .membrane;
  EXPECT_NEAR(w_fine, w_coarse, 1e-10 * w_coarse);
}

TEST(SubdivisionTest, MasksAndRings) {
  const Mesh m = testing::LoadData("plate/plate121.ply");
  const Topology topology = Topology::Build(m);
  // The 1-ring of every vertex: itself and its edge neighbours.
  for (int v = 0; v < m.num_vertices(); ++v) {
    std::set<int> expected = {v};
    for (const auto& e : topology.edges) {
      if (e[0] == v) expected.insert(e[1]);
      if (e[1] == v) expected.insert(e[0]);
    }
    const std::vector<int> ring = VertexRing(m.faces, m.num_vertices(), v, 1);
    EXPECT_EQ(std::set<int>(ring.begin(), ring.end()), expected) << v;
  }
  // Rings grow monotonically and reach the whole (connected) plate.
  size_t previous = 0;
  for (int r = 0; r <= 30; ++r) {
    const size_t size = VertexRing(m.faces, m.num_vertices(), 60, r).size();
    EXPECT_GE(size, previous);
    previous = size;
  }
  EXPECT_EQ(previous, size_t(m.num_vertices()));
  // A mask of one edge's endpoints carries to them and their midpoint only.
  const MidpointSubdivision sub(m.faces, m.num_vertices());
  const auto& e = topology.edges[0];
  const std::vector<int> carried = sub.CarryMask({e[0], e[1]});
  ASSERT_EQ(carried.size(), 3u);
  EXPECT_EQ(carried[0], std::min(e[0], e[1]));
  EXPECT_EQ(carried[1], std::max(e[0], e[1]));
  const auto& parents = sub.parents[carried[2] - m.num_vertices()];
  EXPECT_EQ(std::set<int>(parents.begin(), parents.end()),
            std::set<int>({e[0], e[1]}));
  EXPECT_THROW(VertexRing(m.faces, m.num_vertices(), -1, 1), InputError);
}

}  // namespace
}  // namespace shellspace
