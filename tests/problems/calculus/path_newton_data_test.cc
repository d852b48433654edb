// The Newton stage of geodesic interpolation on the shared plate and
// finger: Newton-polished geodesics against pure Levenberg-Marquardt ones
// and the engine's LM against Ceres', the shifted and the early Newton
// finish, the block-Jacobi CG finish against the direct space-time
// Cholesky, the same digits in repeated runs and on 1 or 2 threads, and
// the automatic choice of the linear solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_newton.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "tests/testing/shell_paths.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::RelativePathDistance;

// The engine's LM (Gauss-Newton matrix, the Newton finish's linear solvers)
// and Ceres' LM reach the same geodesic: E_K to 1e-10 relative and shapes to
// 1e-6 up to rigid motion, with and without a mask, both linear solvers. The
// LM stage of the engine is reported as such ("block-jacobi" / "direct"
// solver) and monotone: E_K of the stage's result below the linear path's.
TEST(PathNewtonTest, EngineLevenbergMarquardtAgreesWithCeres) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  const SolverSettings settings = testing::TightSettings(1e-10);
  for (const bool masked : {false, true}) {
    GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
    if (masked) input.fixed_vertices = {0, 1, 2, 11, 12};
    input.lm = GeodesicLm::kCeres;
    const GeodesicResult ceres = SolveGeodesic(space, input, settings);
    ASSERT_TRUE(ceres.converged);
    EXPECT_EQ(ceres.stages.front().solver, "ceres");
    for (const PathLinearSolver solver :
         {PathLinearSolver::kDirect, PathLinearSolver::kBlockJacobi}) {
      input.lm = GeodesicLm::kEngine;
      input.linear_solver = solver;
      const GeodesicResult engine = SolveGeodesic(space, input, settings);
      ASSERT_TRUE(engine.converged) << engine.stages.back().termination;
      ASSERT_FALSE(engine.stages.empty());
      EXPECT_EQ(engine.stages.front().method,
                GeodesicStage::Method::kLevenbergMarquardt);
      EXPECT_EQ(engine.stages.front().solver,
                solver == PathLinearSolver::kDirect ? "direct" : "block-jacobi");
      EXPECT_GT(engine.stages.front().iterations, 0);
      EXPECT_TRUE(engine.failure.empty());
      EXPECT_NEAR(engine.path_energy, ceres.path_energy,
                  1e-10 * ceres.path_energy)
          << masked;
      for (int k = 1; k < 4; ++k) {
        EXPECT_LT(RelativeDistanceUpToRigidMotion(engine.path[k], ceres.path[k]),
                  1e-6)
            << k << " masked " << masked;
      }
      int total = 0;
      for (const GeodesicStage& stage : engine.stages) total += stage.iterations;
      EXPECT_EQ(engine.iterations, total);
    }
  }
  // kAuto picks the engine where the linear solver is block-Jacobi.
  EXPECT_EQ(ChooseGeodesicLm(GeodesicLm::kAuto, PathLinearSolver::kAuto,
                             kBlockJacobiFromUnknowns),
            GeodesicLm::kEngine);
  EXPECT_EQ(ChooseGeodesicLm(GeodesicLm::kAuto, PathLinearSolver::kAuto,
                             kBlockJacobiFromUnknowns - 1),
            GeodesicLm::kCeres);
  EXPECT_EQ(ChooseGeodesicLm(GeodesicLm::kAuto, PathLinearSolver::kBlockJacobi,
                             10),
            GeodesicLm::kEngine);
  EXPECT_EQ(ChooseGeodesicLm(GeodesicLm::kCeres, PathLinearSolver::kBlockJacobi,
                             10),
            GeodesicLm::kCeres);
}

// Newton-polished and pure-LM geodesics are the same critical point.
TEST(PathNewtonTest, NewtonPolishAgreesWithPureLevenbergMarquardt) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  const SolverSettings settings = testing::TightSettings(1e-11);
  GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
  input.newton_from = 1e-3;
  const GeodesicResult newton = SolveGeodesic(space, input, settings);
  input.newton_from = 0;
  const GeodesicResult lm = SolveGeodesic(space, input, settings);
  EXPECT_GT(newton.newton.steps, 0);
  EXPECT_TRUE(newton.newton.converged) << newton.newton.stop_reason;
  EXPECT_LE(newton.newton.steps, 8);
  EXPECT_EQ(lm.newton.steps, 0);
  EXPECT_NEAR(newton.path_energy, lm.path_energy, 1e-10 * lm.path_energy);
  // The two stages pin the rigid motions at different vertices.
  for (int k = 1; k < 4; ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(newton.path[k], lm.path[k]), 1e-6)
        << k;
  }
  // The reported final gradient is the true one.
  double g = 0;
  for (int k = 1; k < 4; ++k) {
    const Eigen::VectorXd gk =
        testing::InteriorPathGradient(space, newton.path, k);
    const Eigen::VectorXd reduced =
        RigidGaugeBasis(newton.path[k]).transpose() * gk;
    g = std::max(g, 4.0 * reduced.cwiseAbs().maxCoeff());
  }
  // (Plus the round-off of a gradient evaluation at E_K ~ 1, about 1e-12:
  // the trust-region finish ends near 1e-11.)
  EXPECT_NEAR(g, newton.final_gradient, 1e-3 * newton.final_gradient + 5e-12);
}

// Far from the geodesic (the linear path of the plate, K = 4) plain Newton
// cannot continue (Hessian not positive definite, or no step length lowers
// E_K); with the shifted Hessian H + lambda I the polish goes on, never
// raising E_K, to the geodesic of LM.
TEST(PathNewtonTest, ShiftedNewtonFromTheLinearPathDecreasesTheEnergy) {
  const Mesh a = testing::LoadData("plate/plate121.ply");
  const Mesh b = testing::LoadData("plate/plate121_rolledA.ply");
  const ShellSpace space = testing::MakeSpace(a);
  const ShellPath linear = LinearPath(a.positions, b.positions, 4);
  const double linear_energy = PathEnergy(space, linear);
  PathNewtonSettings settings;
  settings.max_steps = 60;
  settings.gradient_tolerance = 1e-9;
  settings.max_shifts = 0;
  ShellPath plain = linear;
  const PathNewtonReport p = PolishPathNewton(space, {}, settings, &plain);
  std::cout << "plain: " << p.steps << " steps, " << p.stop_reason << "\n";
  EXPECT_FALSE(p.converged);
  EXPECT_NE(p.stop, NewtonStop::kMaxSteps);
  settings.max_shifts = kPathNewtonMaxShifts;
  ShellPath shifted = linear;
  const PathNewtonReport r = PolishPathNewton(space, {}, settings, &shifted);
  std::cout << "shifted: " << r.steps << " steps (" << r.shifted_steps
            << " shifted, largest lambda " << r.max_shift << "), "
            << r.stop_reason << ", E_K " << r.final_merit << "\n";
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_GE(r.shifted_steps, 1);
  EXPECT_LT(r.final_merit, linear_energy);
  EXPECT_LE(r.final_merit, p.final_merit);
  GeodesicInput input;
  input.start = a.positions;
  input.end = b.positions;
  input.steps = 4;
  input.newton_from = 0;  // LM alone
  const GeodesicResult lm =
      SolveGeodesic(space, input, testing::TightSettings(1e-10));
  EXPECT_NEAR(PathEnergy(space, shifted), lm.path_energy,
              1e-8 * lm.path_energy);
}

// Newton tried far from the geodesic (at half the initial gradient): the
// line-search finish meets an indefinite Hessian, LM goes on, and a later
// attempt converges to the same geodesic; the trust-region finish (the
// default) follows the negative curvature and converges in its first
// attempt.
TEST(PathNewtonTest, EarlyNewtonRetriesAfterMoreLm) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  SolverSettings settings;
  settings.gradient_tolerance = 1e-10;
  GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
  input.newton_from = 0.5;
  const GeodesicResult trust_region = SolveGeodesic(space, input, settings);
  EXPECT_EQ(trust_region.newton.attempts, 1);
  EXPECT_TRUE(trust_region.newton.converged);
  input.newton = GeodesicNewton::kLineSearch;
  const GeodesicResult early = SolveGeodesic(space, input, settings);
  EXPECT_NEAR(trust_region.path_energy, early.path_energy,
              1e-9 * early.path_energy);
  input.newton_from = 0;
  const GeodesicResult lm = SolveGeodesic(space, input, settings);
  std::cout << "attempts " << early.newton.attempts << ", steps "
            << early.newton.steps << ", " << early.newton.stop_reason << "\n";
  EXPECT_GE(early.newton.attempts, 2);
  EXPECT_TRUE(early.newton.converged);
  EXPECT_NEAR(early.path_energy, lm.path_energy, 1e-9 * lm.path_energy);
}

// Deterministic numerics: the Newton polish (assembly on 1 or 2 threads, CG
// budget by flop estimates) gives the same steps, factorisations, CG
// iterations and bit-identical shapes in repeated runs and for 1 and 2
// threads.
// Polishes the same rough plate geodesic (K = 4, LM to 1e-4) four times,
// on 1, 2, 1, 2 threads, with `solver`; EXPECTs equal steps,
// factorisations, CG iterations, final gradients and bit-identical shapes,
// and returns the first report.
PathNewtonReport ExpectDeterministicPolish(PathLinearSolver solver) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
  input.newton_from = 0;
  const ShellPath start =
      SolveGeodesic(space, input, testing::TightSettings(1e-4)).path;
  std::vector<ShellPath> paths;
  std::vector<PathNewtonReport> reports;
  for (int threads : {1, 2, 1, 2}) {
    ShellPath path = start;
    PathNewtonSettings settings;
    settings.linear_solver = solver;
    settings.gradient_tolerance = 1e-11;
    settings.num_threads = threads;
    reports.push_back(PolishPathNewton(space, {}, settings, &path));
    paths.push_back(path);
  }
  for (size_t i = 1; i < reports.size(); ++i) {
    EXPECT_EQ(reports[i].steps, reports[0].steps) << i;
    EXPECT_EQ(reports[i].factorizations, reports[0].factorizations) << i;
    EXPECT_EQ(reports[i].cg_iterations, reports[0].cg_iterations) << i;
    EXPECT_EQ(reports[i].final_gradient, reports[0].final_gradient) << i;
    for (int k = 0; k <= 4; ++k) EXPECT_EQ(paths[i][k], paths[0][k]) << i;
  }
  return reports[0];
}

TEST(PathNewtonTest, PolishIsDeterministicAcrossRunsAndThreads) {
  const PathNewtonReport report =
      ExpectDeterministicPolish(PathLinearSolver::kDirect);
  ASSERT_TRUE(report.converged) << report.stop_reason;
  EXPECT_GT(report.steps, 1);
  EXPECT_GT(report.cg_iterations, 0);  // the reuse path is exercised
}

// The geodesic with the Newton finish on block-Jacobi CG against the direct
// space-time Cholesky: the same E_K to 1e-8 relative and the same shapes to
// 1e-6, on the plate (rigid gauge) and the finger (a mask, 2046 vertices).
TEST(PathNewtonTest, BlockJacobiFinishMatchesTheDirectSolver) {
  struct Case {
    std::string a, b, mask;
    double eta;
  };
  for (const Case& c :
       {Case{"plate/plate121.ply", "plate/plate121_rolledA.ply", "", 0.01},
        Case{"finger/finger0.ply", "finger/finger1.ply",
             "finger/finger_mask.txt", 0.001}}) {
    const Mesh a = testing::LoadData(c.a);
    const Mesh b = testing::LoadData(c.b);
    ShellMaterial material;
    material.eta = c.eta;
    const ShellSpace space = testing::MakeSpace(a, material);
    GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
    if (!c.mask.empty()) {
      input.fixed_vertices =
          ReadMask(testing::DataPath(c.mask), a.num_vertices());
    }
    const SolverSettings settings = testing::TightSettings(1e-10);
    input.linear_solver = PathLinearSolver::kDirect;
    const GeodesicResult direct = SolveGeodesic(space, input, settings);
    input.linear_solver = PathLinearSolver::kBlockJacobi;
    const GeodesicResult jacobi = SolveGeodesic(space, input, settings);
    std::cout << c.a << ": direct " << direct.newton.steps << " steps, "
              << direct.newton.factorizations << " factorisations, "
              << direct.newton.cg_iterations << " CG; block-jacobi "
              << jacobi.newton.steps << " steps, "
              << jacobi.newton.factorizations << " factorisations, "
              << jacobi.newton.cg_iterations << " CG\n";
    EXPECT_EQ(direct.newton.linear_solver, "direct") << c.a;
    EXPECT_EQ(jacobi.newton.linear_solver, "block-jacobi") << c.a;
    ASSERT_GT(jacobi.newton.steps, 0) << c.a;
    EXPECT_TRUE(direct.converged) << c.a;
    EXPECT_TRUE(jacobi.converged) << c.a << " " << jacobi.newton.stop_reason;
    EXPECT_TRUE(jacobi.newton.converged) << c.a;
    EXPECT_GT(jacobi.newton.cg_iterations, 0) << c.a;
    EXPECT_GE(jacobi.newton.factorizations, 1) << c.a;
    EXPECT_EQ(jacobi.newton.cg_not_converged, 0) << c.a;
    EXPECT_NEAR(jacobi.path_energy, direct.path_energy,
                1e-8 * direct.path_energy)
        << c.a;
    if (c.mask.empty()) {
      // Without a mask each Newton step moves in the 3n - 6 directions
      // orthogonal to the rigid motions of the current shape: a different
      // number of steps leaves a different (arbitrary) gauge.
      for (int k = 1; k < 4; ++k) {
        EXPECT_LT(
            RelativeDistanceUpToRigidMotion(jacobi.path[k], direct.path[k]),
            1e-6)
            << c.a << " " << k;
      }
    } else {
      EXPECT_LT(RelativePathDistance(jacobi.path, direct.path), 1e-6) << c.a;
    }
  }
}

// The block-Jacobi Newton polish gives the same steps, factorisations, CG
// iterations and bit-identical shapes in repeated runs and on 1 or 2
// threads.
TEST(PathNewtonTest, BlockJacobiPolishIsDeterministicAcrossRunsAndThreads) {
  const PathNewtonReport report =
      ExpectDeterministicPolish(PathLinearSolver::kBlockJacobi);
  ASSERT_TRUE(report.converged) << report.stop_reason;
  EXPECT_EQ(report.linear_solver, "block-jacobi");
  EXPECT_GT(report.steps, 1);
  EXPECT_GT(report.cg_iterations, report.steps);
}

TEST(PathNewtonTest, AutomaticChoicePicksDirectOnSmallMeshes) {
  EXPECT_EQ(ChooseLinearSolver(PathLinearSolver::kAuto, 3 * 3 * 121 - 18),
            PathLinearSolver::kDirect);
  EXPECT_EQ(
      ChooseLinearSolver(PathLinearSolver::kAuto, kBlockJacobiFromUnknowns - 1),
      PathLinearSolver::kDirect);
  EXPECT_EQ(
      ChooseLinearSolver(PathLinearSolver::kAuto, kBlockJacobiFromUnknowns),
      PathLinearSolver::kBlockJacobi);
  EXPECT_EQ(ChooseLinearSolver(PathLinearSolver::kDirect, 1 << 30),
            PathLinearSolver::kDirect);
  EXPECT_EQ(ChooseLinearSolver(PathLinearSolver::kBlockJacobi, 10),
            PathLinearSolver::kBlockJacobi);
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, 4);
  ASSERT_EQ(input.linear_solver, PathLinearSolver::kAuto);
  const GeodesicResult result =
      SolveGeodesic(space, input, testing::TightSettings(1e-10));
  ASSERT_GT(result.newton.steps, 0);
  EXPECT_EQ(result.newton.linear_solver, "direct");
}

}  // namespace
}  // namespace shellspace
