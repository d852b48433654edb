// Geodesic calculus (docs/math.md, "Path energy and discrete geodesics" ff.):
// geodesics, EXP, LOG, convex combinations, transport, gauge, convergence.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <iostream>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/connected_components.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/rigid_gauge.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

SolverSettings Tight() { return testing::TightSettings(1e-12); }

class GeodesicCalculusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    start_ = testing::LoadData("plate/plate121.ply");
    end_ = testing::LoadData("plate/plate121_rolledA.ply");
    space_ = testing::MakeSpace(start_);
  }
  GeodesicResult Geodesic(int steps) const {
    GeodesicInput input =
        GeodesicInput::Between(start_.positions, end_.positions, steps);
    return SolveGeodesic(space_, input, Tight());
  }
  Mesh start_, end_;
  ShellSpace space_;
};

TEST_F(GeodesicCalculusTest, ConvergedGeodesicIsStationaryWithEqualSteps) {
  const GeodesicResult linear = [&] {
    GeodesicResult r;
    r.path = LinearPath(start_.positions, end_.positions, 4);
    return r;
  }();
  const GeodesicResult g = Geodesic(4);
  ASSERT_TRUE(g.summary.IsSolutionUsable());
  // The path energy drops below that of the linear path.
  EXPECT_LT(g.path_energy, PathEnergy(space_, linear.path));
  // Interior Euler-Lagrange residual D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}].
  for (int k = 1; k < 4; ++k) {
    const Eigen::VectorXd initial =
        testing::InteriorPathGradient(space_, linear.path, k);
    const Eigen::VectorXd gradient =
        testing::InteriorPathGradient(space_, g.path, k);
    EXPECT_LT(gradient.cwiseAbs().maxCoeff(),
              1e-8 * initial.cwiseAbs().maxCoeff())
        << k;
  }
  const auto [lo, hi] =
      std::minmax_element(g.step_energies.begin(), g.step_energies.end());
  EXPECT_LT(*hi / *lo - 1, 0.1);  // equal to O(tau)
}

TEST_F(GeodesicCalculusTest, ShootingReproducesGeodesic) {
  const GeodesicResult g = Geodesic(4);
  const ShellPath forward = Shoot(space_, g.path[0], g.path[1], 4,
                                  StepDirection::kForward, {}, Tight());
  for (int k = 2; k <= 4; ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(forward[k], g.path[k]), 1e-5)
        << k;
  }
  const ShellPath backward = Shoot(space_, g.path[3], g.path[4], 4,
                                   StepDirection::kBackward, {}, Tight());
  ASSERT_EQ(backward.size(), 5u);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(backward[0], g.path[0]), 1e-5);
}

// With a Dirichlet mask that moves (one edge strip of the plate, rolled
// with the rest), geodesic interpolation moves the masked vertices linearly
// and shooting continues them linearly: forward and backward shots of a
// masked geodesic reproduce it (no rigid motion to factor out here).
TEST_F(GeodesicCalculusTest, ShootingReproducesAMaskedGeodesic) {
  std::vector<int> mask;
  const double x0 = start_.positions.col(0).minCoeff();
  const double width = start_.positions.col(0).maxCoeff() - x0;
  for (int v = 0; v < start_.num_vertices(); ++v) {
    if (start_.positions(v, 0) < x0 + 0.15 * width) mask.push_back(v);
  }
  ASSERT_GT(mask.size(), 5u);
  GeodesicInput input =
      GeodesicInput::Between(start_.positions, end_.positions, 4);
  input.fixed_vertices = mask;
  const GeodesicResult g = SolveGeodesic(space_, input, Tight());
  const double size = (start_.positions.colwise().maxCoeff() -
                       start_.positions.colwise().minCoeff())
                          .norm();
  const ShellPath forward = Shoot(space_, g.path[0], g.path[1], 4,
                                  StepDirection::kForward, mask, Tight());
  for (int k = 2; k <= 4; ++k) {
    EXPECT_LT((forward[k] - g.path[k]).cwiseAbs().maxCoeff(), 1e-5 * size) << k;
  }
  const ShellPath backward = Shoot(space_, g.path[3], g.path[4], 4,
                                   StepDirection::kBackward, mask, Tight());
  EXPECT_LT((backward[0] - g.path[0]).cwiseAbs().maxCoeff(), 1e-5 * size);
}

// One EXP step is solved by Newton on F (exact mixed-Hessian Jacobian,
// sparse LU) in a handful of steps, without falling back to LM.
TEST_F(GeodesicCalculusTest, ExpStepConvergesByNewton) {
  const GeodesicResult g = Geodesic(4);
  for (StepDirection direction :
       {StepDirection::kForward, StepDirection::kBackward}) {
    const bool forward = direction == StepDirection::kForward;
    const ExpStepResult step =
        forward ? ExpStep(space_, g.path[1], g.path[2], direction, {}, Tight())
                : ExpStep(space_, g.path[3], g.path[2], direction, {}, Tight());
    const double scale = (forward ? EnergyGradient(space_, g.path[1], g.path[2],
                                                   ShellSide::kDeformed)
                                  : EnergyGradient(space_, g.path[2], g.path[3],
                                                   ShellSide::kReference))
                             .cwiseAbs()
                             .maxCoeff();
    // Quadratic convergence from 2 b - a, then a stop at the round-off
    // floor (not 20 steps shuffling round-off).
    EXPECT_GE(step.newton_steps, 1);
    EXPECT_LE(step.newton_steps, 5);
    EXPECT_TRUE(step.summary.iterations.empty());  // no LM
    EXPECT_LT(step.residual_norm, 1e-8 * scale);
    EXPECT_LT(RelativeDistanceUpToRigidMotion(step.shape,
                                              forward ? g.path[3] : g.path[1]),
              1e-5);
  }
}

TEST_F(GeodesicCalculusTest, ExpOfLogIsIdentity) {
  const Positions log =
      LogK(space_, start_.positions, end_.positions, 4, {}, Tight());
  const Positions b = ExpK(space_, start_.positions, log, 4, {}, Tight());
  EXPECT_LT(RelativeDistanceUpToRigidMotion(b, end_.positions), 1e-5);
}

TEST_F(GeodesicCalculusTest, HalfTimeCombinationIsMidpoint) {
  const GeodesicResult g2 = Geodesic(2);
  const Positions half = GeodesicAtTime(
      space_, {start_.positions, end_.positions}, 0.5, {}, Tight());
  EXPECT_LT(RelativeDistanceUpToRigidMotion(half, g2.path[1]), 1e-7);
}

TEST_F(GeodesicCalculusTest, PathEnergyDoesNotDependOnGauge) {
  const GeodesicResult pinned = Geodesic(3);
  GeodesicInput input =
      GeodesicInput::Between(start_.positions, end_.positions, 3);
  input.pin_gauge = false;
  const GeodesicResult free_gauge = SolveGeodesic(space_, input, Tight());
  EXPECT_NEAR(free_gauge.path_energy / pinned.path_energy, 1.0, 1e-8);
  // And with moved end shapes (another gauge for every shape).
  input.pin_gauge = true;
  input.start = testing::RandomRigidMotion(start_.positions, 11);
  input.end = testing::RandomRigidMotion(end_.positions, 12);
  const GeodesicResult moved = SolveGeodesic(space_, input, Tight());
  EXPECT_NEAR(moved.path_energy / pinned.path_energy, 1.0, 1e-8);
}

TEST_F(GeodesicCalculusTest, TransportOfZeroAndAlongConstantPath) {
  const GeodesicResult g = Geodesic(3);
  const Positions zero = Positions::Zero(start_.num_vertices(), 3);
  const TransportResult none =
      ParallelTransport(space_, g.path, zero, 1.0, {}, Tight());
  const double scale =
      (end_.positions - start_.positions).cwiseAbs().maxCoeff();
  // Every rung: the transported shape p_k = s_k + xi_k is s_k up to a rigid
  // motion (zero variation up to the gauge of each EXP step).
  ASSERT_EQ(none.shapes.size(), g.path.size());
  for (size_t k = 0; k < none.shapes.size(); ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(none.shapes[k], g.path[k]), 1e-6)
        << k;
    EXPECT_LT((none.shapes[k] - (g.path[k] + none.variations[k]))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12 * scale)
        << k;
  }
  EXPECT_LT((AlignRigidly(none.shapes.back(), g.path.back()) - g.path.back())
                .cwiseAbs()
                .maxCoeff(),
            1e-6 * scale);
  // Constant path: transport is the identity up to O(eps) (W is not
  // symmetric, so the ladder's reflection is exact only as eps -> 0).
  const ShellPath constant(4, start_.positions);
  const Positions variation = 0.05 * (end_.positions - start_.positions);
  auto error = [&](double eps) {
    const TransportResult same =
        ParallelTransport(space_, constant, variation, eps, {}, Tight());
    const Positions target = start_.positions + eps * variation;
    const Positions moved = AlignRigidly(same.shapes.back(), target);
    return (moved - target).cwiseAbs().maxCoeff() /
           (eps * variation.cwiseAbs().maxCoeff());
  };
  const double coarse = error(1.0), fine = error(0.1);
  EXPECT_LT(fine, 1e-3);
  EXPECT_LT(fine, 0.3 * coarse);
}

// g_0 without Ceres (LinearPathGradient) against the gradient_max_norm of
// the Ceres problem of the same path, built here from the residuals: mask,
// rigid gauge (PinRigidMotions' manifolds), and no gauge. The twin: the
// gauge-pinned norm differs from the plain max norm on this path, so a
// norm that ignored the gauge would fail the second comparison.
TEST_F(GeodesicCalculusTest, LinearPathGradientIsCeresGradientMaxNorm) {
  const int K = 4;
  const auto ceres_norm = [&](const std::vector<int>& fixed, bool gauge) {
    ShellPath path = LinearPath(start_.positions, end_.positions, K);
    ceres::Problem problem;
    for (int k = 1; k <= K; ++k) {
      AddDeformationEnergy(
          space_,
          k == 1 ? ShellArgument::Fixed(path[0])
                 : ShellArgument::Variable(&path[k - 1]),
          k == K ? ShellArgument::Fixed(path[K])
                 : ShellArgument::Variable(&path[k]),
          K, &problem);
    }
    for (int k = 1; k < K; ++k) {
      for (int v : fixed) {
        problem.SetParameterBlockConstant(path[k].data() + 3 * v);
      }
      if (fixed.empty() && gauge) PinRigidMotions(&path[k], &problem);
    }
    return GradientMaxNorm(&problem);
  };
  GeodesicInput input =
      GeodesicInput::Between(start_.positions, end_.positions, K);
  const double gauge_norm = ceres_norm({}, true);
  EXPECT_NEAR(LinearPathGradient(space_, input), gauge_norm,
              1e-12 * gauge_norm);
  input.pin_gauge = false;
  const double free_norm = ceres_norm({}, false);
  EXPECT_NEAR(LinearPathGradient(space_, input), free_norm, 1e-12 * free_norm);
  input.pin_gauge = true;
  // The mask holds every vertex whose gradient entries come within 1 % of
  // the largest (the rolled plate is symmetric: several do), so its norm is
  // smaller than the free one: a norm over all vertices would fail here.
  const ShellPath linear = LinearPath(start_.positions, end_.positions, K);
  std::vector<double> vertex_max(space_.num_vertices, 0.0);
  for (int k = 1; k < K; ++k) {
    const Eigen::VectorXd g =
        double(K) * testing::InteriorPathGradient(space_, linear, k);
    for (int v = 0; v < space_.num_vertices; ++v) {
      vertex_max[v] =
          std::max(vertex_max[v], g.segment<3>(3 * v).cwiseAbs().maxCoeff());
    }
  }
  const double largest =
      *std::max_element(vertex_max.begin(), vertex_max.end());
  EXPECT_NEAR(largest, free_norm, 1e-12 * free_norm);
  input.fixed_vertices.clear();
  for (int v = 0; v < space_.num_vertices; ++v) {
    if (vertex_max[v] >= 0.99 * largest) input.fixed_vertices.push_back(v);
  }
  const double mask_norm = ceres_norm(input.fixed_vertices, true);
  EXPECT_NEAR(LinearPathGradient(space_, input), mask_norm, 1e-12 * mask_norm);
  EXPECT_LT(mask_norm, (1 - 1e-3) * free_norm);
}

// The gauge's free coordinates: a spike on vertex a, on b across its line
// and on c along the plane's normal is not seen; along the line and in the
// plane it is.
TEST(RigidGaugeTest, GaugeFreeMaxNormSkipsThePinnedDirections) {
  const Mesh mesh = testing::LoadData("plate/plate121_rolledA.ply");
  const RigidGauge gauge = MakeRigidGauge(mesh.positions);
  const auto [a, b, c] = gauge.vertices;
  const Eigen::Vector3d normal = gauge.plane.col(0).cross(gauge.plane.col(1));
  const Eigen::Vector3d across = gauge.plane.col(1);  // orthogonal to line
  Eigen::VectorXd g = Eigen::VectorXd::Constant(mesh.positions.size(), 0.5);
  g.segment<3>(3 * a) << 10, -20, 30;
  g.segment<3>(3 * b) = 0.25 * gauge.line + 40 * across;
  g.segment<3>(3 * c) = 0.25 * gauge.plane.col(0) + 50 * normal;
  EXPECT_NEAR(GaugeFreeMaxNorm(gauge, g), 0.5, 1e-14);
  g.segment<3>(3 * b) += 7 * gauge.line;
  EXPECT_NEAR(GaugeFreeMaxNorm(gauge, g), 7.25, 1e-12);
  g.segment<3>(3 * c) += 9 * across;
  EXPECT_NEAR(GaugeFreeMaxNorm(gauge, g), 9.0, 1e-12);
}

// Two copies of a shell side by side (the second moved by 1.5 of its
// bounding-box diagonal along x): a mesh of two connected components.
Mesh TwoPieces(const Mesh& first, const Mesh& second) {
  const int n = first.num_vertices();
  const double shift =
      1.5 * (first.positions.colwise().maxCoeff() -
             first.positions.colwise().minCoeff()).norm();
  Mesh two;
  two.positions.resize(2 * n, 3);
  two.positions.topRows(n) = first.positions;
  two.positions.bottomRows(n) = second.positions;
  two.positions.bottomRows(n).col(0).array() += shift;
  two.faces.resize(2 * first.num_faces(), 3);
  two.faces.topRows(first.num_faces()) = first.faces;
  two.faces.bottomRows(first.num_faces()) = first.faces.array() + n;
  return two;
}

// The smallest LDL^T pivot of T^T H T over the largest, H = D_2^2 W[x, x]
// at rest (positive semi-definite, null on the rigid motions of each
// component).
double RelativeSmallestPivot(const SparseMatrix& h, const SparseMatrix& t) {
  const SparseMatrix reduced = t.transpose() * h * t;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(reduced);
  const Eigen::VectorXd d = ldlt.vectorD();
  return d.cwiseAbs().minCoeff() / d.cwiseAbs().maxCoeff();
}

// A shell in two pieces moves rigidly in each: one gauge triple per
// component leaves a definite rest Hessian; the twin, one triple for the
// whole mesh, leaves the second piece's six rigid motions in its null space.
TEST(RigidGaugeTest, OneGaugePerComponentMakesTheRestHessianDefinite) {
  const Mesh plate = testing::LoadData("plate/plate121.ply");
  const Mesh two = TwoPieces(plate, plate);
  const std::vector<std::vector<int>> components =
      ConnectedComponents(two.faces, two.num_vertices());
  ASSERT_EQ(components.size(), 2u);
  EXPECT_EQ(components[0].front(), 0);
  EXPECT_EQ(components[1].front(), plate.num_vertices());
  EXPECT_EQ(components[1].size(), static_cast<size_t>(plate.num_vertices()));
  const ShellSpace space = testing::MakeSpace(two);
  const SparseMatrix h = EnergyHessian(space, two.positions, two.positions,
                                       ShellSide::kDeformed,
                                       ShellSide::kDeformed);
  const SparseMatrix per_component = RigidGaugeBasis(
      two.positions, ChooseGaugeVertices(two.positions, components));
  const SparseMatrix whole = RigidGaugeBasis(two.positions);
  EXPECT_EQ(per_component.cols(), 3 * two.num_vertices() - 12);
  EXPECT_EQ(whole.cols(), 3 * two.num_vertices() - 6);
  EXPECT_GT(RelativeSmallestPivot(h, per_component), 1e-8);
  EXPECT_LT(RelativeSmallestPivot(h, whole), 1e-12);
  // One component: the same basis as before.
  const std::vector<std::vector<int>> one =
      ConnectedComponents(plate.faces, plate.num_vertices());
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(Eigen::MatrixXd(RigidGaugeBasis(
                plate.positions, ChooseGaugeVertices(plate.positions, one))),
            Eigen::MatrixXd(RigidGaugeBasis(plate.positions)));
}

// The largest distance of a vertex of `p` from its place in `q` after the
// best rigid fit of each piece of p onto q.
double DistanceUpToRigidPieces(const Positions& p, const Positions& q,
                               const std::vector<std::vector<int>>& pieces) {
  return (FitRigidMotions(p, q, pieces).Apply(p) - q)
      .rowwise()
      .norm()
      .maxCoeff();
}

// Transport on a shell in two pieces along two solves of one geodesic, from
// the linear and from the rotation-blend start: the same E_K, the inner
// shapes' pieces placed differently (the energies do not see rigid motions
// of a piece). Every rung is solved by Newton at epsilon with a rigid gauge
// in each piece (one gauge for the whole shell leaves the second piece's
// motions in the EXP Jacobian's null space: Newton fails at once and the
// rungs are sub-stepped), and the two transports agree: the same rungs, the
// same shapes up to a rigid motion of each piece.
TEST_F(GeodesicCalculusTest, TransportOfTwoPiecesDoesNotDependOnPlacement) {
  const Mesh rolled_b = testing::LoadData("plate/plate121_rolledB.ply");
  const Mesh two_start = TwoPieces(start_, start_);
  const Mesh two_end = TwoPieces(end_, rolled_b);
  const Mesh two_bumped = TwoPieces(rolled_b, start_);
  const ShellSpace space = testing::MakeSpace(two_start);
  const std::vector<std::vector<int>> pieces =
      ConnectedComponents(two_start.faces, two_start.num_vertices());
  GeodesicInput input =
      GeodesicInput::Between(two_start.positions, two_end.positions, 4);
  input.init = GeodesicInit::kLinear;
  const GeodesicResult g = SolveGeodesic(space, input, Tight());
  input.init = GeodesicInit::kRotations;
  const GeodesicResult h = SolveGeodesic(space, input, Tight());
  ASSERT_TRUE(g.converged);
  ASSERT_TRUE(h.converged);
  EXPECT_NEAR(g.path_energy / h.path_energy, 1, 1e-10);
  double placement = 0;  // how far apart the two solves put a vertex
  for (size_t k = 1; k + 1 < g.path.size(); ++k) {
    placement = std::max(placement,
                         (g.path[k] - h.path[k]).rowwise().norm().maxCoeff());
    EXPECT_LT(DistanceUpToRigidPieces(g.path[k], h.path[k], pieces), 1e-6);
  }
  EXPECT_GT(placement, 1e-4);
  const Positions variation =
      0.1 * (two_bumped.positions - two_start.positions);
  const TransportResult t =
      ParallelTransport(space, g.path, variation, 1.0, {}, SolverSettings{});
  const TransportResult u =
      ParallelTransport(space, h.path, variation, 1.0, {}, SolverSettings{});
  ASSERT_TRUE(t.all_solved);
  ASSERT_TRUE(u.all_solved);
  ASSERT_EQ(t.rungs.size(), u.rungs.size());
  for (size_t k = 0; k < t.rungs.size(); ++k) {
    EXPECT_EQ(t.rungs[k].divisor, 1) << k;
    EXPECT_EQ(u.rungs[k].divisor, 1) << k;
    EXPECT_LE(t.rungs[k].newton_steps, 6) << k;
    EXPECT_EQ(t.rungs[k].lm_iterations, 0) << k;
    EXPECT_NEAR(t.rungs[k].newton_steps, u.rungs[k].newton_steps, 1) << k;
    EXPECT_NEAR(t.rungs[k].midpoint_iterations, u.rungs[k].midpoint_iterations,
                1)
        << k;
  }
  ASSERT_EQ(t.shapes.size(), u.shapes.size());
  for (size_t k = 1; k < t.shapes.size(); ++k) {
    EXPECT_LT(DistanceUpToRigidPieces(t.shapes[k], u.shapes[k], pieces), 1e-6)
        << k;
  }
}

// Closed forms: a middle shape scaled by 1/2 in x (the plate lies in a
// plane containing x, so every face keeps half its area) and one vertex
// moved onto a neighbour (its faces lose all area). The geodesic of the
// plate pair has no collapsing face.
TEST_F(GeodesicCalculusTest, SmallestFaceAreaRatioFindsTheCollapse) {
  ShellPath path = {start_.positions, start_.positions, start_.positions};
  path[1].col(0) *= 0.5;
  Positions flat = start_.positions;
  // The plate's normal: scale the two in-plane axes (x and the other one).
  const Eigen::RowVector3d extent =
      flat.colwise().maxCoeff() - flat.colwise().minCoeff();
  Eigen::Index thin = 0;
  extent.minCoeff(&thin);
  ASSERT_NE(thin, 0);
  FaceAreaRatio half = SmallestFaceAreaRatio(start_.faces, path);
  EXPECT_NEAR(half.ratio, 0.5, 1e-12);
  EXPECT_EQ(half.shape, 1);
  const int f = 17;
  path[1] = start_.positions;
  path[1].row(start_.faces(f, 0)) = path[1].row(start_.faces(f, 1));
  const FaceAreaRatio collapsed = SmallestFaceAreaRatio(start_.faces, path);
  EXPECT_EQ(collapsed.ratio, 0.0);
  EXPECT_EQ(collapsed.shape, 1);
  const GeodesicResult g = Geodesic(4);
  EXPECT_FALSE(g.collapsing_faces);
  EXPECT_GT(g.smallest_face_area.ratio, 0.1);
  EXPECT_LT(g.smallest_face_area.ratio, 1.5);
}

// A path whose inner shape sits at 5 % of the way (max_iterations 0: not
// solved) has far from equal steps and is flagged, and is not converged;
// the solved geodesic is neither.
TEST_F(GeodesicCalculusTest, UnevenStepsAreFlaggedAndNotConverged) {
  GeodesicInput input;
  input.start = start_.positions;
  input.end = end_.positions;
  input.steps = 2;
  input.initial = {start_.positions,
                   start_.positions + 0.05 * (end_.positions - start_.positions),
                   end_.positions};
  SolverSettings none = Tight();
  none.max_iterations = 0;
  const GeodesicResult raw = SolveGeodesic(space_, input, none);
  EXPECT_EQ(raw.iterations, 0);
  EXPECT_FALSE(raw.converged);
  ASSERT_EQ(raw.step_energies.size(), 2u);
  EXPECT_EQ(raw.step_energy_ratio,
            std::max(raw.step_energies[0], raw.step_energies[1]) /
                std::min(raw.step_energies[0], raw.step_energies[1]));
  EXPECT_GT(raw.step_energy_ratio, kUnevenStepEnergyRatio);
  EXPECT_TRUE(raw.uneven_steps);
  EXPECT_GT(raw.final_gradient, raw.gradient_target);

  const GeodesicResult solved = SolveGeodesic(space_, input, Tight());
  EXPECT_TRUE(solved.converged);
  EXPECT_LE(solved.final_gradient, solved.gradient_target);
  EXPECT_LT(solved.step_energy_ratio, 1.2);  // K = 2: 1.145
  EXPECT_FALSE(solved.uneven_steps);
}

// settings.max_iterations caps the LM iterations and Newton steps of all
// stages together.
TEST_F(GeodesicCalculusTest, MaxIterationsCapsAllStages) {
  GeodesicInput input;
  input.start = start_.positions;
  input.end = end_.positions;
  input.steps = 4;
  for (int cap : {1, 3, 6}) {
    SolverSettings capped = Tight();
    capped.max_iterations = cap;
    const GeodesicResult g = SolveGeodesic(space_, input, capped);
    int sum = 0;
    for (const GeodesicStage& stage : g.stages) sum += stage.iterations;
    EXPECT_EQ(g.iterations, sum) << cap;
    EXPECT_LE(g.iterations, cap) << cap;
    EXPECT_EQ(g.converged, g.final_gradient <= g.gradient_target) << cap;
  }
}

// The EXP step's own verdict: solved by Newton below kExpStepAcceptance.
TEST_F(GeodesicCalculusTest, ExpStepSaysItSolved) {
  const GeodesicResult g = Geodesic(4);
  const ExpStepResult step = ExpStep(space_, g.path[1], g.path[2],
                                     StepDirection::kForward, {}, Tight());
  const double scale =
      EnergyGradient(space_, g.path[1], g.path[2], ShellSide::kDeformed)
          .cwiseAbs()
          .maxCoeff();
  EXPECT_TRUE(step.solved);
  EXPECT_EQ(step.method, ExpStepResult::Method::kNewton);
  EXPECT_EQ(step.lm_iterations, 0);
  EXPECT_NEAR(step.residual_scale, scale, 1e-12 * scale);
  EXPECT_NEAR(step.relative_residual, step.residual_norm / scale, 1e-20);
  EXPECT_LE(step.relative_residual, kExpStepAcceptance);
}

// Sub-stepping of transport rungs: along the plate geodesic (rolledA, K =
// 4) the variation rolledB - plate at epsilon = 1 has no EXP solution on the
// last rung (the first try fails: divisor > 1); at epsilon / 4 it has, and
// every rung reports solved, its residual and its method.
TEST_F(GeodesicCalculusTest, TransportSubstepsARungWithoutSolution) {
  const Mesh rolled_b = testing::LoadData("plate/plate121_rolledB.ply");
  GeodesicInput input;
  input.start = start_.positions;
  input.end = end_.positions;
  input.steps = 4;
  const GeodesicResult g = SolveGeodesic(space_, input, SolverSettings{});
  ASSERT_TRUE(g.converged);
  const TransportResult t =
      ParallelTransport(space_, g.path, rolled_b.positions - start_.positions,
                        1.0, {}, SolverSettings{});
  ASSERT_EQ(t.rungs.size(), 4u);
  EXPECT_TRUE(t.all_solved);
  for (size_t k = 0; k < t.rungs.size(); ++k) {
    EXPECT_TRUE(t.rungs[k].solved) << k;
    EXPECT_LE(t.rungs[k].relative_residual, kExpStepAcceptance) << k;
    EXPECT_GE(t.rungs[k].newton_steps, 1) << k;
  }
  std::cout << "divisors:";
  for (const auto& r : t.rungs) std::cout << " " << r.divisor;
  std::cout << "\n";
  EXPECT_GT(t.rungs.back().divisor, 1);
  EXPECT_LE(t.rungs.back().divisor, 1 << kMaxRungHalvings);
  // Each try of a rung (one per halving up to its divisor) runs at most
  // kRungFallbackLmIterations (0) of EXP LM fallback while a smaller
  // sub-step is left (the full settings' 200 on the last, epsilon / 16), and
  // its midpoint solve counts.
  for (size_t k = 0; k < t.rungs.size(); ++k) {
    int tries = 1;
    while ((1 << (tries - 1)) < t.rungs[k].divisor) ++tries;
    const bool last_try_full = t.rungs[k].divisor == 1 << kMaxRungHalvings;
    EXPECT_LE(t.rungs[k].lm_iterations,
              (tries - last_try_full) * kRungFallbackLmIterations +
                  last_try_full * SolverSettings{}.max_iterations)
        << k;
    EXPECT_GE(t.rungs[k].midpoint_iterations, tries) << k;
  }
  for (size_t k = 0; k < t.shapes.size(); ++k) {
    EXPECT_LT((t.shapes[k] - (g.path[k] + t.variations[k])).cwiseAbs().maxCoeff(),
              1e-12)
        << k;
  }
}

// E_K on the sphere pair for K = 2, 4, 8, 16: successive changes decrease.
TEST(GeodesicConvergenceTest, PathEnergyConvergesInK) {
  const auto [a, b, space] = testing::LoadPair("sphere/unitSphere1.ply",
                                               "sphere/unitSphere1_defX.ply");
  std::vector<double> energies;
  for (int K : {2, 4, 8, 16}) {
    GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, K);
    SolverSettings settings;
    settings.gradient_tolerance = 1e-10;
    energies.push_back(SolveGeodesic(space, input, settings).path_energy);
  }
  const double d1 = std::abs(energies[1] - energies[0]);
  const double d2 = std::abs(energies[2] - energies[1]);
  const double d3 = std::abs(energies[3] - energies[2]);
  EXPECT_GT(d1, d2);
  EXPECT_GT(d2, d3);
  std::cout << "E_K (K = 2, 4, 8, 16): " << energies[0] << " " << energies[1]
            << " " << energies[2] << " " << energies[3]
            << "; observed order log2(d1/d2) = " << std::log2(d1 / d2)
            << ", log2(d2/d3) = " << std::log2(d2 / d3) << "\n";
}

}  // namespace
}  // namespace shellspace
