// The robust start of a geodesic and its safeguards (problems/calculus/
// geodesic_initial_path.h, multiresolution.h, the trust-region finish and
// the step limit of geodesic.h), on procedural meshes: the rigid motion
// removed before interpolating, the LΘA path, a prolongation worse than the
// fine start rejected, Newton steps that do not grow under refinement, a
// sliver input.
#include "shellspace/problems/calculus/geodesic_initial_path.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/geometry/stress_deformations.h"
#include "shellspace/geometry/subdivision.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/ltheta_reconstruction.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/rotation_blend_path.h"

namespace shellspace {
namespace {

Positions Rotate(const Positions& x, double degrees,
                 const Eigen::Vector3d& axis) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized())
          .toRotationMatrix();
  return (x * r.transpose()).eval();
}

SolverSettings Tight() {
  SolverSettings s;
  s.gradient_tolerance = 1e-8;
  s.max_iterations = 200;
  s.num_threads = 1;
  return s;
}

class InitialPathTest : public ::testing::Test {
 protected:
  InitialPathTest()
      : finger_(MakeFinger(0.5, 3.0, 10, 8, 3)),
        space_(finger_, Topology::Build(finger_), ShellMaterial{1, 1, 0.01}) {}
  Mesh finger_;
  ShellSpace space_;
};

// A rotation by 170 degrees: the plain linear path passes near a flat
// shape (its midpoint is a projection), the path without the rigid motion
// is rigid motions of the start, to round-off.
TEST_F(InitialPathTest, RemovingTheRigidMotionKeepsEveryShapeRigid) {
  const Positions end = Rotate(finger_.positions, 170, {1, 0.2, 0});
  double degrees = 0;
  const ShellPath path =
      LinearPathWithoutRigidMotion(finger_.positions, end, 4, {}, &degrees);
  EXPECT_NEAR(degrees, 170, 1e-9);
  for (int k = 0; k <= 4; ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(path[k], finger_.positions),
              1e-12)
        << k;
  }
  EXPECT_FALSE(FindPathDegeneracy(finger_.faces, path).degenerate());
  // The twin: the plain linear path degenerates, and the check says where.
  const PathDegeneracy plain =
      FindPathDegeneracy(finger_.faces, LinearPath(finger_.positions, end, 4));
  EXPECT_TRUE(plain.degenerate());
  EXPECT_LT(plain.smallest_area_ratio, kDegenerateAreaRatio);
  EXPECT_NE(plain.Describe().find("triangle"), std::string::npos);
  // With a mask the shapes keep their linear positions.
  const ShellPath masked = LinearPathWithoutRigidMotion(
      finger_.positions, end, 4, FingerBaseVertices(10, 1));
  EXPECT_EQ(masked[2], LinearPath(finger_.positions, end, 4)[2]);
}

// A bend plus a rotation by 150 degrees: the plain linear path is
// degenerate, the default start (auto) is not, and the geodesic converges
// from it with no collapsing triangle and even steps.
TEST_F(InitialPathTest, APathThroughADegenerateLinearInterpolationConverges) {
  const Positions end = Rotate(BendAlongY(finger_.positions, 3.0, 1.2), 150,
                               {1, 0, 0.3});
  ASSERT_TRUE(FindPathDegeneracy(finger_.faces,
                                 LinearPath(finger_.positions, end, 4))
                  .degenerate());
  GeodesicInput input = GeodesicInput::Between(finger_.positions, end, 4);
  const GeodesicResult result = SolveGeodesic(space_, input, Tight());
  EXPECT_TRUE(result.init.rigid_motion_removed);
  EXPECT_NEAR(result.init.rotation_degrees, 150, 15);
  EXPECT_TRUE(result.converged) << result.final_gradient;
  EXPECT_FALSE(result.collapsing_faces);
  EXPECT_FALSE(result.uneven_steps);
}

// The LΘA path: its inner shapes have (nearly) the interpolated edge
// lengths, and the geodesic from it is the geodesic from the linear path
// (the same E_K to 1e-8).
TEST_F(InitialPathTest, TheLThetaPathInterpolatesLengthsAndLeadsToTheGeodesic) {
  const Positions end = BendAlongY(finger_.positions, 3.0, 1.5);
  InitialPathReport report;
  const ShellPath path = MakeGeodesicInitialPath(
      space_, finger_.positions, end, 4, {}, GeodesicInit::kLTheta, Tight(),
      &report);
  EXPECT_EQ(report.used, GeodesicInit::kLTheta);
  EXPECT_GT(report.ltheta_iterations, 0);
  const LThetaQuantities q0 = ComputeLThetaQuantities(space_, path[0]);
  const LThetaQuantities q4 = ComputeLThetaQuantities(space_, path[4]);
  const LThetaQuantities q2 = ComputeLThetaQuantities(space_, path[2]);
  const Eigen::VectorXd target = 0.5 * (q0.lengths + q4.lengths);
  EXPECT_LT(((q2.lengths - target).array() / target.array()).abs().maxCoeff(),
            0.05);
  GeodesicInput ltheta = GeodesicInput::Between(finger_.positions, end, 4);
  ltheta.init = GeodesicInit::kLTheta;
  GeodesicInput linear = ltheta;
  linear.init = GeodesicInit::kLinear;
  const GeodesicResult a = SolveGeodesic(space_, ltheta, Tight());
  const GeodesicResult b = SolveGeodesic(space_, linear, Tight());
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_NEAR(a.path_energy, b.path_energy, 1e-8 * b.path_energy);
  EXPECT_EQ(b.init.used, GeodesicInit::kLinear);
}

// A finger twisted by 300 degrees: the linear path and the rotation blend
// degenerate, so auto takes the LΘA path, whose reconstruction stops short
// in a frame. Auto stops each frame after kAutoLThetaFrameIterations LM
// iterations and names the frames stopped short; the twin, an explicit
// ltheta start, spends the settings' iterations (200) instead.
TEST(AutoLThetaStartTest, EachFrameStopsAtTheAutoCap) {
  const Mesh finger = MakeFinger(0.5, 3.0, 24, 8, 3);
  const ShellSpace space(finger, Topology::Build(finger),
                         ShellMaterial{1, 1, 0.01});
  const Positions end =
      DeformForCorpus(finger.positions, "twist", 300, false, 1);
  constexpr int kSteps = 4;
  InitialPathReport automatic, explicit_ltheta;
  MakeGeodesicInitialPath(space, finger.positions, end, kSteps, {},
                          GeodesicInit::kAuto, Tight(), &automatic);
  MakeGeodesicInitialPath(space, finger.positions, end, kSteps, {},
                          GeodesicInit::kLTheta, Tight(), &explicit_ltheta);
  ASSERT_EQ(automatic.used, GeodesicInit::kLTheta) << automatic.reason;
  EXPECT_FALSE(automatic.ltheta_unconverged.empty());
  EXPECT_LE(automatic.ltheta_iterations,
            (kSteps - 1) * kAutoLThetaFrameIterations);
  EXPECT_GT(explicit_ltheta.ltheta_iterations,
            (kSteps - 1) * kAutoLThetaFrameIterations);
}

// The largest |l_e(s) - l_e(target)| / l_e(target) over the edges e.
double LargestRelativeLengthError(const Topology& topology, const Positions& s,
                                  const Eigen::VectorXd& target) {
  double worst = 0;
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const auto [a, b] = topology.edges[e];
    const double length = (s.row(a) - s.row(b)).norm();
    worst = std::max(worst, std::abs(length - target[e]) / target[e]);
  }
  return worst;
}

Eigen::VectorXd EdgeLengths(const Topology& topology, const Positions& s) {
  Eigen::VectorXd lengths(topology.edges.size());
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    lengths[e] = (s.row(topology.edges[e][0]) - s.row(topology.edges[e][1]))
                     .norm();
  }
  return lengths;
}

// A rigid motion by 130 degrees: every shape of the rotation blend is a
// rigid motion of the start (to round-off), turned by k/K of the angle, and
// the path ends on the given shapes. The twin: the plain linear path's
// midpoint is not rigid.
TEST_F(InitialPathTest, TheRotationBlendOfARigidMotionIsRigid) {
  Positions end = Rotate(finger_.positions, 130, {0.3, 1, 0.2});
  end.rowwise() += Eigen::RowVector3d(1, -2, 0.5);
  const ShellPath path = RotationBlendPath(finger_.faces, space_.topology,
                                           finger_.positions, end, 4, {});
  ASSERT_EQ(path.size(), 5u);
  EXPECT_LT((path[0] - finger_.positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((path[4] - end).cwiseAbs().maxCoeff(), 1e-12);
  for (int k = 0; k <= 4; ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(path[k], finger_.positions),
              1e-12)
        << k;
    const RigidMotion m = FitRigidMotion(finger_.positions, path[k]);
    EXPECT_NEAR(Eigen::AngleAxisd(m.rotation).angle() * 180 / M_PI,
                130.0 * k / 4, 1e-9)
        << k;
  }
  EXPECT_GT(RelativeDistanceUpToRigidMotion(
                LinearPath(finger_.positions, end, 4)[2], finger_.positions),
            0.1);
}

// A bend by 240 degrees of the finger held at its base (the inner side
// shortened to 0.6 of its length): the linear path turns triangles over
// and cuts the edges short; the rotation blend turns none and its midpoint
// has (nearly) the mean edge lengths of the ends -- an edge along a
// principal direction of the stretch has exactly the interpolated length.
// Auto takes it, and the geodesic from it is the geodesic from the LΘA
// path (E_K to 1e-8).
TEST_F(InitialPathTest, TheRotationBlendFollowsABendTheLinearPathCutsShort) {
  const Positions end = BendAlongY(finger_.positions, 3.0, 240 * M_PI / 180);
  const std::vector<int> mask = FingerBaseVertices(10, 1);
  const ShellPath linear =
      LinearPathWithoutRigidMotion(finger_.positions, end, 4, mask);
  const ShellPath blend = RotationBlendPath(finger_.faces, space_.topology,
                                            finger_.positions, end, 4, mask);
  const Eigen::VectorXd mean_lengths =
      0.5 * (EdgeLengths(space_.topology, finger_.positions) +
             EdgeLengths(space_.topology, end));
  const double blend_error =
      LargestRelativeLengthError(space_.topology, blend[2], mean_lengths);
  const double linear_error =
      LargestRelativeLengthError(space_.topology, linear[2], mean_lengths);
  std::cout << "midpoint edge lengths off by " << blend_error
            << " (rotation blend), " << linear_error << " (linear)\n";
  EXPECT_LT(blend_error, 0.1);
  EXPECT_GT(linear_error, 0.3);  // the twin
  EXPECT_FALSE(FindPathDegeneracy(finger_.faces, blend).degenerate());
  ASSERT_TRUE(FindPathDegeneracy(finger_.faces, linear).degenerate());

  GeodesicInput input = GeodesicInput::Between(finger_.positions, end, 4);
  input.fixed_vertices = mask;
  const GeodesicResult from_blend = SolveGeodesic(space_, input, Tight());
  EXPECT_EQ(from_blend.init.used, GeodesicInit::kRotations)
      << from_blend.init.reason;
  input.init = GeodesicInit::kLTheta;
  const GeodesicResult from_ltheta = SolveGeodesic(space_, input, Tight());
  ASSERT_TRUE(from_blend.converged) << from_blend.final_gradient;
  ASSERT_TRUE(from_ltheta.converged) << from_ltheta.final_gradient;
  std::cout << "iterations from the rotation blend " << from_blend.iterations
            << " (" << from_blend.init.seconds << " s), from the LTheta path "
            << from_ltheta.iterations << " (" << from_ltheta.init.seconds
            << " s)\n";
  EXPECT_NEAR(from_blend.path_energy, from_ltheta.path_energy,
              1e-8 * from_ltheta.path_energy);
}

// With a mask the masked vertices keep their linear positions and nothing
// is moved rigidly: the ends are the given shapes.
TEST_F(InitialPathTest, TheRotationBlendHoldsTheMaskOnTheLinearPath) {
  const Positions end = BendAlongY(finger_.positions, 3.0, 120 * M_PI / 180);
  const std::vector<int> mask = FingerBaseVertices(10, 1);
  const ShellPath blend = RotationBlendPath(finger_.faces, space_.topology,
                                            finger_.positions, end, 4, mask);
  const ShellPath linear = LinearPath(finger_.positions, end, 4);
  for (int k = 0; k <= 4; ++k) {
    for (int v : mask) {
      EXPECT_LT((blend[k].row(v) - linear[k].row(v)).norm(), 1e-14) << k;
    }
  }
  EXPECT_LT((blend[4] - end).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_FALSE(FindPathDegeneracy(finger_.faces, blend).degenerate());
}

// Guided by the rotations of a rigid motion (every face turned by k/K of
// it at s_k) and anchored on the rigidly moved shapes, the guided path is
// that rigid motion: its shape to round-off; its translation, which only
// the fit's eps term fixes, to 1e-5.
TEST_F(InitialPathTest, ARotationGuidedPathFollowsARigidGuideExactly) {
  const Eigen::Vector3d axis(0.3, 1, 0.2);
  const Positions end = Rotate(finger_.positions, 130, axis);
  std::vector<std::vector<Eigen::Matrix3d>> guide(5);
  std::vector<Positions> anchors(5);
  for (int k = 0; k <= 4; ++k) {
    anchors[k] = Rotate(finger_.positions, 130.0 * k / 4, axis);
    guide[k] = FaceRotations(finger_.faces, finger_.positions, anchors[k]);
  }
  const ShellPath path = RotationGuidedPath(finger_.faces, finger_.positions,
                                            end, guide, anchors, {});
  ASSERT_EQ(path.size(), 5u);
  for (int k = 1; k < 4; ++k) {
    const Eigen::RowVector3d shift =
        (path[k] - anchors[k]).colwise().mean();
    EXPECT_LT(shift.norm(), 1e-5) << k;
    EXPECT_LT((path[k] - anchors[k]).rowwise().operator-(shift)
                  .cwiseAbs().maxCoeff(),
              1e-10)
        << k;
  }
}

// Guided by the rotations of a bent finger's geodesic (what a coarse level
// hands on) the guided path lies near that geodesic: E_K within 20 % of
// it, where the linear path's is several times larger, and no triangle
// turns over. The twin: a guide that does not turn the faces before the
// end (identities, and the geodesic's own rotations at s_K, so that no
// face rotation is left to blend in) cuts the bend short.
TEST_F(InitialPathTest, ARotationGuidedPathFollowsTheGuidesBend) {
  const Positions end = BendAlongY(finger_.positions, 3.0, 150 * M_PI / 180);
  const GeodesicResult geodesic = SolveGeodesic(
      space_, GeodesicInput::Between(finger_.positions, end, 4), Tight());
  ASSERT_TRUE(geodesic.converged);
  std::vector<std::vector<Eigen::Matrix3d>> guide(5), still(5);
  for (int k = 0; k <= 4; ++k) {
    guide[k] = FaceRotations(finger_.faces, finger_.positions,
                             geodesic.path[k]);
    still[k].assign(finger_.faces.rows(), Eigen::Matrix3d::Identity());
  }
  still[4] = guide[4];
  const ShellPath guided = RotationGuidedPath(
      finger_.faces, finger_.positions, end, guide, geodesic.path, {});
  const ShellPath unguided = RotationGuidedPath(
      finger_.faces, finger_.positions, end, still, geodesic.path, {});
  const double e_guided = PathEnergy(space_, guided);
  const double e_linear =
      PathEnergy(space_, LinearPath(finger_.positions, end, 4));
  std::cout << "E_K guided " << e_guided << ", geodesic "
            << geodesic.path_energy << ", linear " << e_linear << "\n";
  EXPECT_LT(e_guided, 1.2 * geodesic.path_energy);
  EXPECT_GT(e_linear, 3 * geodesic.path_energy);
  EXPECT_EQ(FindPathDegeneracy(finger_.faces, guided).turned_faces, 0);
  EXPECT_GT(PathEnergy(space_, unguided), 3 * geodesic.path_energy);
}

// A prolongation that turns a triangle over, or whose E_K exceeds the fine
// start's, is rejected; the geodesic itself is accepted.
TEST_F(InitialPathTest, AProlongationWorseThanTheFineStartIsRejected) {
  const Positions end = BendAlongY(finger_.positions, 3.0, 1.0);
  InitialPathReport init;
  const ShellPath start = MakeGeodesicInitialPath(
      space_, finger_.positions, end, 4, {}, GeodesicInit::kAuto, Tight(),
      &init);
  const GeodesicResult geodesic = SolveGeodesic(
      space_, GeodesicInput::Between(finger_.positions, end, 4), Tight());
  const ProlongationCheck good =
      CheckProlongation(space_, geodesic.path, start, init);
  EXPECT_TRUE(good.used) << good.reason;
  EXPECT_LT(good.prolongated_energy, good.initial_energy);
  // Mirrored inner shape: every triangle turns over.
  ShellPath mirrored = geodesic.path;
  mirrored[2].col(0) *= -1;
  const ProlongationCheck turned =
      CheckProlongation(space_, mirrored, start, init);
  EXPECT_FALSE(turned.used);
  EXPECT_GT(turned.turned_faces, 0);
  EXPECT_NE(turned.reason.find("rejected"), std::string::npos);
  // A wrinkled path of higher energy, no triangle turned.
  ShellPath wrinkled = start;
  for (int k = 1; k < 4; ++k) {
    for (int v = 0; v < wrinkled[k].rows(); ++v) {
      wrinkled[k](v, 2) += 0.02 * std::sin(7.0 * v);
    }
  }
  const ProlongationCheck worse =
      CheckProlongation(space_, wrinkled, start, init);
  EXPECT_GT(worse.prolongated_energy, worse.initial_energy);
  EXPECT_FALSE(worse.used) << worse.reason;
}

// The trust-region Newton finish takes about the same number of steps on
// refinements of one problem (a sheet rolled onto a cylinder, one row
// masked): the count does not grow with the mesh.
TEST(TrustRegionNewtonTest, StepCountDoesNotGrowOnRefinementsOfThePlate) {
  Mesh sheet = MakeEquilateralSheet(12, 8, 0.125);
  std::vector<int> row;
  for (int v = 0; v < 13; ++v) row.push_back(v);
  std::vector<int> newton_steps;
  for (int level = 0; level < 3; ++level) {
    if (level > 0) {
      const MidpointSubdivision sub(sheet.faces, sheet.num_vertices());
      sheet = Mesh{sub.Apply(sheet.positions), sub.faces};
      row = sub.CarryMask(row);
    }
    const ShellSpace space(sheet, Topology::Build(sheet),
                           ShellMaterial{1, 1, 0.01});
    const Positions end = RollOntoCylinder(sheet.positions, 0.6);
    GeodesicInput input = GeodesicInput::Between(sheet.positions, end, 4);
    input.fixed_vertices = row;
    input.lm = GeodesicLm::kEngine;
    const GeodesicResult r = SolveGeodesic(space, input, Tight());
    ASSERT_TRUE(r.converged) << "level " << level;
    newton_steps.push_back(r.newton.steps);
  }
  const auto [lo, hi] =
      std::minmax_element(newton_steps.begin(), newton_steps.end());
  EXPECT_LE(*hi - *lo, 2) << newton_steps[0] << " " << newton_steps[1] << " "
                          << newton_steps[2];
  EXPECT_GE(*lo, 1);
}

// A sheet rolled onto a cylinder, stretched along x by 80 % with a small
// ripple: from the linear start an LM step cuts the gradient more than
// tenfold, Newton takes over right there (the LM stage ends "gradient
// contracting: handed over") and converges, with fewer LM steps than
// without the early hand-over and the same E_K.
TEST(NewtonHandOverTest, AStretchedCylinderHandsOverAtAContractingLmStep) {
  const Mesh sheet = MakeEquilateralSheet(12, 8, 0.125);
  std::vector<int> row;
  for (int v = 0; v < 13; ++v) row.push_back(v);
  const ShellSpace space(sheet, Topology::Build(sheet),
                         ShellMaterial{1, 1, 0.01});
  const Positions rolled = RollOntoCylinder(sheet.positions, 1.0);
  Positions stretched = rolled;
  for (int v = 0; v < rolled.rows(); ++v) {
    const double x = rolled(v, 0), y = rolled(v, 1);
    stretched(v, 0) = 1.8 * x;
    stretched(v, 2) += 0.24 * std::sin(2 * x) * std::cos(3 * y);
  }
  GeodesicInput input = GeodesicInput::Between(rolled, stretched, 4);
  input.fixed_vertices = row;
  input.lm = GeodesicLm::kEngine;
  const GeodesicResult early = SolveGeodesic(space, input, Tight());
  input.newton_contraction = 0;
  const GeodesicResult late = SolveGeodesic(space, input, Tight());
  ASSERT_TRUE(early.converged);
  ASSERT_TRUE(late.converged);
  ASSERT_EQ(early.stages.size(), 2u);
  EXPECT_EQ(early.stages[0].termination, "gradient contracting: handed over");
  EXPECT_EQ(early.stages[1].method, GeodesicStage::Method::kNewton);
  ASSERT_FALSE(late.stages.empty());
  EXPECT_NE(late.stages[0].termination, "gradient contracting: handed over");
  std::cout << "LM + Newton steps: early hand-over "
            << early.stages[0].iterations << " + " << early.newton.steps
            << ", without " << late.stages[0].iterations << " + "
            << late.newton.steps << "\n";
  EXPECT_LT(early.stages[0].iterations, late.stages[0].iterations);
  EXPECT_NEAR(early.path_energy, late.path_energy, 1e-10 * late.path_energy);
}

// An input sliver (a vertex moved next to the opposite edge of one
// triangle): named up front, and the geodesic converges without crushing
// it.
TEST(SliverTest, ASliverInputIsNamedAndConverges) {
  Mesh sheet = MakeEquilateralSheet(6, 4, 0.25);
  const MidpointSubdivision sub(sheet.faces, sheet.num_vertices());
  sheet = Mesh{sub.Apply(sheet.positions), sub.faces};
  // Vertex 20 towards the midpoint of the opposite edge (a, b) of its first
  // triangle: inside that triangle, so nothing turns over (the hexagonal
  // star of an interior vertex is convex).
  const int v = 20;
  int a = -1, b = -1;
  for (int f = 0; f < sheet.num_faces() && a < 0; ++f) {
    for (int c = 0; c < 3; ++c) {
      if (sheet.faces(f, c) == v) {
        a = sheet.faces(f, (c + 1) % 3);
        b = sheet.faces(f, (c + 2) % 3);
      }
    }
  }
  ASSERT_GE(a, 0);
  const Eigen::RowVector3d mid =
      0.5 * (sheet.positions.row(a) + sheet.positions.row(b));
  sheet.positions.row(v) = mid + 0.004 * (sheet.positions.row(v) - mid);
  const SliverFaces slivers = FindSliverFaces(sheet);
  ASSERT_FALSE(slivers.faces.empty());
  EXPECT_TRUE(slivers.folds.empty());
  EXPECT_LT(slivers.smallest_area_fraction, kSliverAreaFraction);
  EXPECT_NE(slivers.Describe().find("sliver"), std::string::npos);
  // The twin: the sheet without the moved vertex has none.
  EXPECT_TRUE(FindSliverFaces(MakeEquilateralSheet(6, 4, 0.25)).faces.empty());
  const ShellSpace space(sheet, Topology::Build(sheet),
                         ShellMaterial{1, 1, 0.01});
  const Positions end = RollOntoCylinder(sheet.positions, 0.5);
  GeodesicInput input = GeodesicInput::Between(sheet.positions, end, 4);
  input.fixed_vertices = {0, 1, 2, 3};
  // Auto: the engine's LM (with the step limit), as for every input with
  // slivers.
  const GeodesicResult r = SolveGeodesic(space, input, Tight());
  EXPECT_NE(r.stages.front().solver, "ceres");
  EXPECT_TRUE(r.converged) << r.final_gradient << " " << r.stages.back().termination;
  EXPECT_GT(r.smallest_face_area.ratio, kCollapsingFaceAreaRatio);
}

// The corpus deformations: a bend keeps the axis length (an isometry of the
// principal axis), a twist keeps distances to the axis, a rigid motion all
// pairwise distances; the same seed gives the same pose.
TEST(StressDeformationsTest, InvariantsOfTheCorpusPoses) {
  const Mesh finger = MakeFinger(0.5, 3.0, 10, 8, 3);
  const Positions& x = finger.positions;
  const Positions rigid = RandomRigidMotion(x, 77, 5);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(rigid, x), 1e-12);
  EXPECT_EQ(rigid, RandomRigidMotion(x, 77, 5));
  EXPECT_NE(rigid, RandomRigidMotion(x, 77, 6));
  const PrincipalFrame f = ComputePrincipalFrame(x);
  const Positions twisted = TwistAboutLongestAxis(x, 90);
  for (int v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d d = x.row(v).transpose() - f.centroid;
    const Eigen::Vector3d e = twisted.row(v).transpose() - f.centroid;
    const Eigen::Vector3d a = f.axes.col(0);
    EXPECT_NEAR((d - d.dot(a) * a).norm(), (e - e.dot(a) * a).norm(), 1e-12);
  }
  const Positions bent = BendAlongLongestAxis(x, 75);
  EXPECT_GT(RelativeDistanceUpToRigidMotion(bent, x), 0.05);
  // Every edge on the axis side keeps its length to first order: the mean
  // relative edge-length change is small for a moderate bend.
  const Topology topology = Topology::Build(finger);
  double change = 0;
  for (const auto& e : topology.edges) {
    const double l0 = (x.row(e[0]) - x.row(e[1])).norm();
    const double l1 = (bent.row(e[0]) - bent.row(e[1])).norm();
    change += std::abs(l1 - l0) / l0 / topology.edges.size();
  }
  EXPECT_LT(change, 0.1);
  EXPECT_THROW(DeformForCorpus(x, "shear", 1, true, 1), InputError);
}

}  // namespace
}  // namespace shellspace
