// What keeps geodesic solves and EXP steps from going astray on ordinary
// deformations:
//   - EXP along a rigid motion is the rigid motion, exactly and with no
//     iteration (the step beyond b of a rigid step a -> b is M(b)), also
//     along a motion of its own for each piece of a shell in pieces;
//   - the best-iterate rule: an exact Newton stage that stops short ends on
//     the iterate with its smallest gradient, and an unconverged solve
//     reports the path with the smallest gradient it met, not its last.
// Each with a negative twin.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/stress_deformations.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/rotation_blend_path.h"
#include "shellspace/problems/calculus/vertex_relaxation.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// max_v |p_v - q_v| / the diameter of q's bounding box.
double RelativeDistance(const Positions& p, const Positions& q) {
  const double diameter =
      (q.colwise().maxCoeff() - q.colwise().minCoeff()).norm();
  return (p - q).rowwise().norm().maxCoeff() / diameter;
}

// A rotation by 30 degrees about an oblique axis and a translation.
RigidMotion ThirtyDegrees() {
  RigidMotion m;
  m.rotation = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d(1, 2, 2).normalized())
                   .toRotationMatrix();
  m.translation = Eigen::RowVector3d(0.3, -0.2, 0.5);
  return m;
}

TEST(RigidExpTest, TheStepBeyondARigidStepIsTheRigidMotionWithNoIteration) {
  const Mesh finger = MakeFinger(0.5, 4.0, 16, 12, 4);
  const ShellSpace space = testing::MakeSpace(finger);
  const RigidMotion m = ThirtyDegrees();
  const Positions a = finger.positions;
  const Positions b = m.Apply(a);
  for (const StepDirection direction :
       {StepDirection::kForward, StepDirection::kBackward}) {
    const ExpStepResult step =
        ExpStep(space, a, b, direction, {}, testing::TightSettings(1e-10));
    EXPECT_TRUE(step.solved);
    EXPECT_EQ(step.newton_steps, 0);
    EXPECT_EQ(step.lm_iterations, 0);
    EXPECT_LE(RelativeDistance(step.shape, m.Apply(b)), 1e-10);
  }
  // Twin: the linear extrapolation 2 b - a, the old first guess, is not.
  EXPECT_GT(RelativeDistance(2 * b - a, m.Apply(b)), 1e-2);
}

// Two copies of `finger` (a shell in two pieces), the second moved by 3
// along x: 2 #V x 3 positions, the faces of each copy on its own vertices.
Mesh SideBySide(const Mesh& finger) {
  const int n = finger.num_vertices();
  Mesh two;
  two.positions.resize(2 * n, 3);
  two.positions.topRows(n) = finger.positions;
  two.positions.bottomRows(n) = finger.positions;
  two.positions.bottomRows(n).col(0).array() += 3.0;
  two.faces.resize(2 * finger.num_faces(), 3);
  two.faces.topRows(finger.num_faces()) = finger.faces;
  two.faces.bottomRows(finger.num_faces()) = finger.faces.array() + n;
  return two;
}

// A shell in two pieces (two fingers side by side), each moved by a rigid
// motion of its own: a rigid step too, continued exactly with no iteration.
// Twin: no single rigid motion of the whole shell fits a -> b.
TEST(RigidExpTest, EachPieceOfATwoPieceShellContinuesItsOwnMotion) {
  const Mesh finger = MakeFinger(0.5, 4.0, 16, 12, 4);
  const int n = finger.num_vertices();
  const Mesh two = SideBySide(finger);
  const ShellSpace space = testing::MakeSpace(two);
  RigidMotion other;
  other.rotation =
      Eigen::AngleAxisd(-M_PI / 5, Eigen::Vector3d(0, 1, 0)).toRotationMatrix();
  other.translation = Eigen::RowVector3d(-0.4, 0.1, 0.2);
  const RigidMotion m = ThirtyDegrees();
  const auto move = [&](const Positions& x) {
    Positions y(x.rows(), 3);
    y.topRows(n) = m.Apply(x.topRows(n));
    y.bottomRows(n) = other.Apply(x.bottomRows(n));
    return y;
  };
  const Positions a = two.positions;
  const Positions b = move(a);
  const ExpStepResult step = ExpStep(space, a, b, StepDirection::kForward, {},
                                     testing::TightSettings(1e-10));
  EXPECT_TRUE(step.solved);
  EXPECT_EQ(step.newton_steps, 0);
  EXPECT_EQ(step.lm_iterations, 0);
  EXPECT_LE(RelativeDistance(step.shape, move(b)), 1e-10);
  EXPECT_GT(RelativeDistanceUpToRigidMotion(a, b), 1e-2);
}

// The rotation blend at t = 2 carries a twist on as a twist: from a finger
// and the finger twisted by 40 degrees about its axis, close to the finger
// twisted by 80; the twin, the linear extrapolation 2 b - a, swells the
// cross-sections (by sqrt(5 - 4 cos 40 deg) - 1 = 33 % at the top) and is
// much farther. As the EXP step's second initial guess it is the one taken
// (its residual is smaller), and the step is solved.
TEST(RotationExtrapolationTest, TheRotationBlendAtTwoContinuesATwist) {
  const Mesh finger = MakeFinger(0.5, 4.0, 16, 12, 4);
  const ShellSpace space = testing::MakeSpace(finger);
  const Positions a = finger.positions;
  const Positions b = TwistAboutLongestAxis(a, 40);
  const Positions twice = TwistAboutLongestAxis(a, 80);
  const std::vector<Positions> turned =
      RotationBlendShapes(finger.faces, space.topology, a, b, {2.0}, {});
  ASSERT_EQ(turned.size(), 1u);
  const double blend_error = RelativeDistance(turned[0], twice);
  const double linear_error = RelativeDistance(2 * b - a, twice);
  std::cout << "distance to the 80-degree twist: rotation blend "
            << blend_error << ", linear " << linear_error << "\n";
  EXPECT_LT(blend_error, 0.1 * linear_error);
  EXPECT_GT(linear_error, 0.03);  // of the diagonal: a third of the radius
  const ExpStepResult step =
      ExpStep(space, a, b, StepDirection::kForward, {},
              testing::TightSettings(1e-10), &turned[0]);
  EXPECT_TRUE(step.solved);
  EXPECT_EQ(step.lm_iterations, 0);
}

// The elastic mean of a shell in two pieces (two fingers side by side, each
// bent by its own angle in the two inputs): Newton with a rigid gauge in
// each piece takes it to a tight gradient quadratically, as on a shell in
// one piece (with one gauge the second piece's motions stay in the reduced
// Hessian's null space).
TEST(TwoPieceMeanTest, NewtonFinishesTheMeanOfAShellInTwoPieces) {
  const Mesh finger = MakeFinger(0.5, 4.0, 12, 10, 3);
  const int n = finger.num_vertices();
  const Mesh two = SideBySide(finger);
  const ShellSpace space = testing::MakeSpace(two);
  Positions bent = two.positions;
  bent.topRows(n) = BendAlongY(finger.positions, 4.0, 0.6);
  bent.bottomRows(n) = BendAlongY(finger.positions, 4.0, -0.4);
  bent.bottomRows(n).col(0).array() += 3.0;
  SolverSettings settings;
  settings.gradient_tolerance = 1e-11;
  settings.max_iterations = 1000;
  const ElasticMeanResult mean =
      ComputeElasticMean(space, {two.positions, bent}, settings);
  EXPECT_TRUE(mean.converged) << mean.gradient_norm;
  EXPECT_FALSE(mean.newton_fell_back);
  EXPECT_GE(mean.newton_iterations, 1);
  EXPECT_LE(mean.newton_iterations, 6);
  EXPECT_LE(mean.gradient_norm,
            1e-11 * std::max(1.0, mean.initial_gradient_norm));
}

TEST(RigidExpTest, ShootingAlongARigidMotionReproducesIt) {
  const Mesh finger = MakeFinger(0.5, 4.0, 16, 12, 4);
  const ShellSpace space = testing::MakeSpace(finger);
  const RigidMotion m = ThirtyDegrees();
  const ShellPath path =
      Shoot(space, finger.positions, m.Apply(finger.positions), 8,
            StepDirection::kForward, {}, testing::TightSettings(1e-10));
  ASSERT_EQ(path.size(), 9u);
  Positions expected = finger.positions;
  for (int k = 0; k <= 8; ++k) {
    EXPECT_LE(RelativeDistance(path[k], expected), 1e-10) << "frame " << k;
    expected = m.Apply(expected);
  }
}

TEST(RigidExpTest, ANearlyRigidStepStillSolvesItsEquation) {
  // A rigid motion plus a small bend: not rigid, so Newton runs to the
  // acceptance.
  const Mesh finger = MakeFinger(0.5, 4.0, 16, 12, 4);
  const ShellSpace space = testing::MakeSpace(finger);
  const RigidMotion m = ThirtyDegrees();
  const Positions a = finger.positions;
  const Positions b = m.Apply(BendAlongY(a, 4.0, 0.05));
  const ExpStepResult step = ExpStep(space, a, b, StepDirection::kForward, {},
                                     testing::TightSettings(1e-10));
  EXPECT_TRUE(step.solved);
  EXPECT_GT(step.newton_steps, 0);
  EXPECT_LE(step.relative_residual, kExpStepAcceptance);
}

// A finger bent by `degrees` at K = 4 from the linear path (no mask, the
// gauge pinned): far from the geodesic, where exact Newton's trust-region
// steps along negative curvature lower E_K and may raise the gradient.
struct BentFinger {
  Mesh mesh = MakeFinger(0.5, 4.0, 12, 10, 3);
  ShellSpace space = testing::MakeSpace(mesh);
  Positions end;
  ShellPath path;
  explicit BentFinger(double degrees) {
    end = BendAlongY(mesh.positions, 4.0, degrees * M_PI / 180);
    path = LinearPath(mesh.positions, end, 4);
  }
  GeodesicInput Input() const {
    GeodesicInput input = GeodesicInput::Between(mesh.positions, end, 4);
    input.initial = path;
    return input;
  }
};

// The exact trust-region Newton stage of `steps` steps from the finger's
// linear path (the best-iterate rule on or off); *path is its result.
PathNewtonReport ExactStage(const BentFinger& f, int steps, bool keep_best,
                            ShellPath* path, int stall_steps = 0) {
  PathNewtonSettings settings;
  settings.stall_steps = stall_steps;
  settings.globalisation = NewtonSettings::Globalisation::kTrustRegion;
  settings.model = HessianModel::kExact;
  settings.max_steps = steps;
  settings.gradient_tolerance = 1e-12;
  settings.keep_best_iterate = keep_best;
  *path = f.path;
  return PolishPathNewton(f.space, {}, settings, path);
}

TEST(BestIterateTest, AStageEndsOnItsSmallestGradient) {
  const BentFinger f(150);
  // The gradients of the stage's iterates, step by step (the rule off; the
  // engine's own measure: the reduced gradient's max norm).
  std::vector<double> norms;
  for (int steps = 0; steps <= 3; ++steps) {
    ShellPath path;
    norms.push_back(ExactStage(f, steps, false, &path).final_gradient);
  }
  const auto smallest = std::min_element(norms.begin(), norms.end());
  const int at = static_cast<int>(smallest - norms.begin());
  // The case is one the rule is for: the stage ends above an iterate it met
  // after its start (the twin, the rule off).
  ASSERT_GT(norms.back(), 1.5 * *smallest);
  ASSERT_GT(at, 0);
  ShellPath kept_path, best_path;
  const PathNewtonReport kept = ExactStage(f, 3, true, &kept_path);
  ExactStage(f, at, false, &best_path);
  EXPECT_TRUE(kept.restored_best);
  EXPECT_EQ(kept.final_gradient, *smallest);
  EXPECT_NE(kept.stop_reason.find("best iterate kept"), std::string::npos);
  for (int k = 0; k <= 4; ++k) EXPECT_EQ(kept_path[k], best_path[k]);
}

TEST(BestIterateTest, AnUnconvergedSolveReportsTheBestPathItMet) {
  const BentFinger f(150);
  for (const bool keep_best : {true, false}) {
    GeodesicInput input = f.Input();
    input.lm = GeodesicLm::kEngine;
    input.newton_from = 0.5;  // a Newton attempt far from the geodesic
    input.newton_contraction = 0;
    input.keep_best_iterate = keep_best;
    SolverSettings settings = testing::TightSettings(1e-8);
    settings.max_iterations = 2;  // one LM step, one Newton step
    const GeodesicResult r = SolveGeodesic(f.space, input, settings);
    ASSERT_EQ(r.stages.size(), 2u);
    ASSERT_FALSE(r.converged);
    // The Newton step raised the gradient the LM stage had reached.
    ASSERT_GT(r.stages[1].final_gradient, r.stages[0].final_gradient);
    if (keep_best) {
      EXPECT_TRUE(r.best_iterate_restored);
      EXPECT_EQ(r.final_gradient, r.stages[0].final_gradient);
    } else {  // the twin: the last path
      EXPECT_FALSE(r.best_iterate_restored);
      EXPECT_EQ(r.final_gradient, r.stages[1].final_gradient);
    }
  }
}

// An exact Newton attempt outside the basin ends once kNewtonStallSteps
// accepted steps have not halved its gradient, not at its step cap.
TEST(NewtonStallTest, AnAttemptOutsideTheBasinEndsWhenItsGradientStalls) {
  // At 170 degrees (150 converges in 14 steps, the rule never firing).
  const BentFinger f(170);
  constexpr int kCap = 4 * 8;  // the exact attempts' step cap
  ShellPath path;
  const PathNewtonReport stalled =
      ExactStage(f, kCap, false, &path, kNewtonStallSteps);
  ASSERT_FALSE(stalled.converged);
  EXPECT_EQ(stalled.stop, NewtonStop::kNoProgress) << stalled.stop_reason;
  const int n = stalled.steps;
  ASSERT_GT(n, kNewtonStallSteps);
  ASSERT_LT(n, kCap);
  // The criterion, from the same stage replayed without the rule: after n
  // steps the gradient is above half of its value kNewtonStallSteps steps
  // before, and every earlier window had halved it.
  std::vector<double> norms;
  for (int steps = 0; steps <= n; ++steps) {
    ShellPath replay;
    norms.push_back(ExactStage(f, steps, false, &replay).final_gradient);
  }
  EXPECT_EQ(norms[n], stalled.final_gradient);
  EXPECT_GT(norms[n], 0.5 * norms[n - kNewtonStallSteps]);
  for (int m = kNewtonStallSteps + 1; m < n; ++m) {
    EXPECT_LE(norms[m], 0.5 * norms[m - kNewtonStallSteps]) << m;
  }
  // The twin: without the rule the stage runs on to its cap.
  const PathNewtonReport capped = ExactStage(f, kCap, false, &path);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.steps, kCap) << capped.stop_reason;
}

// A vertex displaced from a converged geodesic, relaxed alone with every
// other vertex at the geodesic: its local minimiser is its geodesic
// position, and E_K returns to the geodesic's.
TEST(VertexRelaxationTest, ADisplacedVertexReturnsToTheGeodesic) {
  const BentFinger f(60);
  const GeodesicResult geodesic = SolveGeodesic(
      f.space, GeodesicInput::Between(f.mesh.positions, f.end, 4),
      testing::TightSettings(1e-11));
  ASSERT_TRUE(geodesic.converged);
  const int kVertex = f.space.num_vertices / 2, kShape = 2;
  ShellPath displaced = geodesic.path;
  displaced[kShape].row(kVertex) += Eigen::RowVector3d(0.01, -0.02, 0.015);
  ShellPath relaxed = displaced;
  std::vector<std::vector<int>> chosen(5);
  chosen[kShape] = {kVertex};
  const VertexRelaxationReport report =
      RelaxVertices(f.space, chosen, 20, 1, &relaxed);
  ASSERT_EQ(report.vertices, 1);
  EXPECT_GE(report.newton_steps, 2);
  EXPECT_LT(report.energy_after, report.energy_before);
  EXPECT_NEAR(report.energy_after, geodesic.path_energy,
              1e-9 * geodesic.path_energy);
  EXPECT_LT((relaxed[kShape].row(kVertex) - geodesic.path[kShape].row(kVertex))
                .norm(),
            1e-7);
  relaxed[kShape].row(kVertex) = displaced[kShape].row(kVertex);
  for (int k = 0; k <= 4; ++k) EXPECT_EQ(relaxed[k], displaced[k]) << k;
}

// RelaxPeakVertices moves the vertices whose gradient is near the path's
// largest: with fraction 0.999 the one LargestPathGradient names, alone.
TEST(VertexRelaxationTest, ThePeakVertexIsTheOneRelaxed) {
  const BentFinger f(60);
  ShellPath path = f.path;
  const GradientPeak peak = LargestPathGradient(f.space, {}, path, 1);
  ASSERT_GT(peak.vertex, -1);
  const VertexRelaxationReport report =
      RelaxPeakVertices(f.space, {}, 0.999, 10, 1, &path);
  ASSERT_EQ(report.vertices, 1);
  EXPECT_GE(report.newton_steps, 1);
  for (int k = 0; k <= 4; ++k) {
    for (int v = 0; v < path[k].rows(); ++v) {
      if (k == peak.shape && v == peak.vertex) {
        EXPECT_NE(path[k].row(v), f.path[k].row(v));
      } else {
        EXPECT_EQ(path[k].row(v), f.path[k].row(v)) << k << " " << v;
      }
    }
  }
  // The vertex is now stationary in its own coordinates (the path's largest
  // gradient may move to a neighbour: E_K falls, the max norm need not).
  Eigen::VectorXd before, after;
  ASSERT_TRUE(TryInnerShapeGradient(f.space, f.path, peak.shape, &before));
  ASSERT_TRUE(TryInnerShapeGradient(f.space, path, peak.shape, &after));
  EXPECT_LT(after.segment<3>(3 * peak.vertex).norm(),
            1e-8 * before.segment<3>(3 * peak.vertex).norm());
  EXPECT_LT(report.energy_after, report.energy_before);
}

// E_K never rises, and the sweep's digits do not depend on the threads.
TEST(VertexRelaxationTest, ASweepLowersTheEnergyWhateverTheThreads) {
  const BentFinger f(120);  // the linear path, far from the geodesic
  ShellPath one = f.path, two = f.path;
  const VertexRelaxationReport a = RelaxPeakVertices(f.space, {}, 0.1, 10, 1, &one);
  const VertexRelaxationReport b = RelaxPeakVertices(f.space, {}, 0.1, 10, 2, &two);
  ASSERT_GT(a.vertices, 10);
  EXPECT_LT(a.energy_after, a.energy_before);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.newton_steps, b.newton_steps);
  for (int k = 0; k <= 4; ++k) EXPECT_EQ(one[k], two[k]) << k;
  // The ends and a mask are never moved.
  ShellPath masked = f.path;
  const std::vector<int> mask = {0, 1, 2, 3, 4, 5};
  RelaxPeakVertices(f.space, mask, 0.0, 10, 2, &masked);
  EXPECT_EQ(masked.front(), f.path.front());
  EXPECT_EQ(masked.back(), f.path.back());
  for (int k = 1; k < 4; ++k) {
    for (int v : mask) EXPECT_EQ(masked[k].row(v), f.path[k].row(v));
  }
}

}  // namespace
}  // namespace shellspace
