// The nonlinear elimination of stiff vertices on a procedural sheet with one
// cap (a triangle whose apex sits at 1 % of its height from its long edge):
// the stiff vertices are the cap's; the elimination's gradient in them is
// the whole path's (three face rings; one ring or, for the shape operator,
// two are not enough); it lowers E_K, moves only the stiff rows and leaves
// a path whose stiff vertices are in equilibrium as it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_energy.h"
#include "shellspace/problems/calculus/stiff_vertex_elimination.h"
#include "tests/testing/shell_paths.h"

namespace shellspace {
namespace {

// A `columns` x `rows` sheet (h = 0.2) whose vertex `apex` is moved 99 % of the way to
// the midpoint of the opposite edge of one of its faces: that face is a cap
// (angles about 1, 1 and 178 degrees), no face turns over.
struct CappedSheet {
  Mesh mesh;
  int apex = -1;
  std::vector<int> cap;  // the cap's vertices, increasing

  explicit CappedSheet(int columns = 6, int rows = 4) {
    mesh = MakeEquilateralSheet(columns, rows, 0.2);
    const Topology topology = Topology::Build(mesh);
    // The interior vertex nearest the centre.
    const Eigen::RowVector3d centre = mesh.positions.colwise().mean();
    double nearest = HUGE_VAL;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const double d = (mesh.positions.row(v) - centre).norm();
      if (topology.vertex_faces[v].size() == 6 && d < nearest) {
        nearest = d;
        apex = v;
      }
    }
    const int f = topology.vertex_faces[apex][0];
    std::vector<int> others;
    for (int a = 0; a < 3; ++a) {
      if (mesh.faces(f, a) != apex) others.push_back(mesh.faces(f, a));
    }
    const Eigen::RowVector3d mid =
        0.5 * (mesh.positions.row(others[0]) + mesh.positions.row(others[1]));
    mesh.positions.row(apex) += 0.99 * (mid - mesh.positions.row(apex));
    cap = {apex, others[0], others[1]};
    std::sort(cap.begin(), cap.end());
  }
  ShellSpace Space(BendingModel model) const {
    ShellMaterial material{1, 1, 0.01};
    material.bending_model = model;
    return ShellSpace(mesh, Topology::Build(mesh), material);
  }
  // A perturbed linear path of K steps to the sheet rolled onto a cylinder
  // of radius 2.
  ShellPath Path(int K) const {
    return testing::PerturbedLinearPath(
        mesh.positions, RollOntoCylinder(mesh.positions, 2.0), K, 1e-3, 7);
  }
};

// max over the inner shapes and the `vertices` of |G_k(v)|, G the whole
// path's gradient.
double GradientAt(const ShellSpace& space, const ShellPath& path,
                  const std::vector<int>& vertices) {
  double largest = 0;
  EXPECT_TRUE(ForEachInnerShapeGradient(
      space, path, 1, [&](int, const Eigen::VectorXd& g) {
        for (int v : vertices) {
          largest = std::max(largest, g.segment<3>(3 * v).cwiseAbs().maxCoeff());
        }
      }));
  return largest;
}

TEST(StiffVertexEliminationTest, TheStiffVerticesAreTheCapsOwn) {
  const CappedSheet sheet;
  EXPECT_EQ(FindStiffVertices(sheet.mesh.faces, sheet.mesh.positions, {},
                              kStiffAngleDegrees),
            sheet.cap);
  // A fixed vertex is not stiff; below the cap's smallest angle (about 1
  // degree) nothing is.
  std::vector<int> rest = sheet.cap;
  rest.erase(std::find(rest.begin(), rest.end(), sheet.apex));
  EXPECT_EQ(FindStiffVertices(sheet.mesh.faces, sheet.mesh.positions,
                              {sheet.apex}, kStiffAngleDegrees),
            rest);
  EXPECT_TRUE(FindStiffVertices(sheet.mesh.faces, sheet.mesh.positions, {},
                                0.5)
                  .empty());
}

// The solve drives the gradient of its sub-space to the tolerance; the
// whole path's gradient at the stiff vertices follows only if the sub-space
// holds every element of a stiff vertex, whole.
double GradientAfterSolve(BendingModel model, int rings) {
  const CappedSheet sheet;
  const ShellSpace space = sheet.Space(model);
  ShellPath path = sheet.Path(3);
  StiffVertexElimination elimination(space, sheet.cap, 0.1, rings);
  const StiffEliminationReport report = elimination.Solve(50, 1e-10, &path);
  EXPECT_TRUE(report.solved);
  EXPECT_GT(report.gradient_before, 1e-3);
  EXPECT_LE(report.gradient_after, 1e-10);
  return GradientAt(space, path, sheet.cap);
}

TEST(StiffVertexEliminationTest, ItsGradientIsThePathsInTheStiffVertices) {
  EXPECT_LE(GradientAfterSolve(BendingModel::kDiscreteShells,
                               kEliminationFaceRings),
            1e-9);
  EXPECT_LE(GradientAfterSolve(BendingModel::kShapeOperator,
                               kEliminationFaceRings),
            1e-9);
  // A hinge reaches two faces: two rings are enough for Discrete Shells.
  EXPECT_LE(GradientAfterSolve(BendingModel::kDiscreteShells, 2), 1e-9);
}

TEST(StiffVertexEliminationTest, TooFewRingsMissElementsOfTheStiffVertices) {
  // The twins: one ring drops the hinges across the ring's edge, two drop
  // the shape-operator elements of the faces next to the cap's.
  EXPECT_GT(GradientAfterSolve(BendingModel::kDiscreteShells, 1), 1e-6);
  EXPECT_GT(GradientAfterSolve(BendingModel::kShapeOperator, 2), 1e-6);
}

TEST(StiffVertexEliminationTest, ItLowersEnergyAndMovesOnlyTheStiffRows) {
  const CappedSheet sheet;
  const ShellSpace space = sheet.Space(BendingModel::kDiscreteShells);
  const ShellPath before = sheet.Path(4);
  ShellPath path = before;
  StiffVertexElimination elimination(space, sheet.cap, 0.1);
  const StiffEliminationReport report = elimination.Solve(50, 1e-10, &path);
  EXPECT_GT(report.steps, 0);
  EXPECT_LT(PathEnergy(space, path), PathEnergy(space, before));
  for (size_t k = 0; k < path.size(); ++k) {
    for (int v = 0; v < space.num_vertices; ++v) {
      const bool stiff = std::binary_search(sheet.cap.begin(),
                                            sheet.cap.end(), v);
      const bool inner = k > 0 && k + 1 < path.size();
      if (!stiff || !inner) {
        EXPECT_EQ(path[k].row(v), before[k].row(v)) << k << " " << v;
      }
    }
  }
  // Its stiff vertices in equilibrium, a path is left as it is.
  const ShellPath settled = path;
  const StiffEliminationReport again = elimination.Solve(50, 1e-8, &path);
  EXPECT_EQ(again.steps, 0);
  for (size_t k = 0; k < path.size(); ++k) EXPECT_EQ(path[k], settled[k]);
}

// The geodesic from a 12 x 8 capped sheet (117 vertices: the cap's three
// are below kMaxStiffFraction) to the sheet rolled onto a cylinder of
// radius 0.6 (the cap's apex lifted off its long edge by several heights):
// with and without elimination.
GeodesicResult CappedGeodesic(bool eliminate) {
  const CappedSheet sheet(12, 8);
  const ShellSpace space = sheet.Space(BendingModel::kDiscreteShells);
  GeodesicInput input;
  input.start = sheet.mesh.positions;
  input.end = RollOntoCylinder(sheet.mesh.positions, 0.6);
  input.steps = 4;
  input.lm = GeodesicLm::kEngine;
  input.eliminate_stiff_vertices = eliminate;
  SolverSettings settings;
  settings.gradient_tolerance = 1e-8;
  settings.max_iterations = 200;
  settings.num_threads = 1;
  return SolveGeodesic(space, input, settings);
}

// Both reach the same geodesic (up to a rigid motion of each shape); eliminating the cap's vertices takes 6
// global iterations instead of 10 (and 22 small Newton steps on the cap).
TEST(StiffVertexEliminationTest, AGeodesicWithACapConvergesToTheSamePath) {
  const GeodesicResult with = CappedGeodesic(true);
  const GeodesicResult without = CappedGeodesic(false);
  EXPECT_TRUE(with.converged);
  EXPECT_TRUE(without.converged);
  EXPECT_NEAR(with.path_energy, without.path_energy,
              1e-10 * without.path_energy);
  // Each inner shape is free up to a rigid motion (no mask): the steps'
  // energies, which do not see it, agree.
  ASSERT_EQ(with.step_energies.size(), without.step_energies.size());
  for (size_t k = 0; k < with.step_energies.size(); ++k) {
    EXPECT_NEAR(with.step_energies[k], without.step_energies[k],
                1e-8 * without.path_energy);
  }
  EXPECT_LT(with.iterations, without.iterations);
  EXPECT_EQ(with.stiff_vertices, 3);
  EXPECT_GT(with.elimination_newton_steps, 0);
  EXPECT_EQ(without.stiff_vertices, 0);
  EXPECT_EQ(without.elimination_newton_steps, 0);
}

}  // namespace
}  // namespace shellspace
