// A shell with a folded edge (its two triangles turned 178 degrees against
// each other, the dihedral angle near pi, as in some public meshes): the
// fold is named up front (FindSliverFaces), and a geodesic that turns the
// fold further, across atan2's branch cut, is the same short path as one
// that opens it by as much (BendingElement's DihedralAngleChange): both
// converge to the closed form of a hinge turned at constant speed.
#include <gtest/gtest.h>

#include <cmath>

#include "shellspace/geometry/topology.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {
namespace {

constexpr double kDegree = M_PI / 180.0;

// The hinge (0, 1, 2), (1, 0, 3) along the x axis, vertex 3 turned by phi
// about the edge from vertex 2's side (phi = pi: flat, phi -> 0: shut).
Mesh Hinge(double phi) {
  Mesh m;
  m.positions.resize(4, 3);
  m.positions << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, std::cos(phi),
      -std::sin(phi);
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 1, 0, 3;
  return m;
}

SolverSettings Tight() {
  SolverSettings s;
  s.gradient_tolerance = 1e-10;
  s.max_iterations = 100;
  s.num_threads = 1;
  return s;
}

TEST(FoldedInputTest, AFoldIsNamedUpFront) {
  const SliverFaces folded = FindSliverFaces(Hinge(2 * kDegree));
  ASSERT_EQ(folded.folds.size(), 1u);
  EXPECT_EQ(folded.folds[0], std::make_pair(0, 1));
  EXPECT_NEAR(folded.largest_fold_degrees, 178, 1e-9);
  EXPECT_NE(folded.Describe().find("1 folded edge"), std::string::npos);
  // The twin: the hinge opened to 90 degrees has none.
  const SliverFaces open = FindSliverFaces(Hinge(90 * kDegree));
  EXPECT_TRUE(open.empty());
  EXPECT_NEAR(open.largest_fold_degrees, 90, 1e-9);
}

// Vertices 0, 1, 2 fixed, vertex 3 turned by dphi = +-4 degrees from a
// fold of 2 degrees: through phi = 0 (the dihedral angle from 178 to -178
// degrees) or open to 6 degrees. The geodesic turns the hinge at constant
// speed on its circle (each shape an isometric copy: no membrane energy;
// each step's bending energy eta (dphi / K)^2 |E|^2 / dbar, |E| = 1,
// dbar = (1/2 + 1/2) / 3), so E_K = K sum_k W_k = 3 eta dphi^2; the two
// directions are mirror images, so they agree to rounding.
TEST(FoldedInputTest, TurningAFoldAcrossTheCutIsAShortGeodesic) {
  const double eta = 0.01;
  const Mesh start = Hinge(2 * kDegree);
  const ShellSpace space(start, Topology::Build(start),
                         ShellMaterial{1, 1, eta});
  double energy[2];
  const double turns[2] = {-4 * kDegree, 4 * kDegree};
  for (int t = 0; t < 2; ++t) {
    GeodesicInput input = GeodesicInput::Between(
        start.positions, Hinge(2 * kDegree + turns[t]).positions, 4);
    input.fixed_vertices = {0, 1, 2};
    const GeodesicResult r = SolveGeodesic(space, input, Tight());
    ASSERT_TRUE(r.failure.empty()) << r.failure;
    EXPECT_TRUE(r.converged) << r.final_gradient;
    energy[t] = r.path_energy;
    const double closed_form = 3 * eta * turns[t] * turns[t];
    EXPECT_NEAR(r.path_energy, closed_form, 1e-6 * closed_form) << t;
  }
  EXPECT_NEAR(energy[0], energy[1], 1e-9 * energy[1]);
}

}  // namespace
}  // namespace shellspace
