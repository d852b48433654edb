// One EXP step where Newton from the plain guess 2 b - a misses the root:
// the continuation in the load (exp_step_continuation.h) follows the roots
// of t c + D_1 W[b, .] from b, and its end is the step of a discrete
// geodesic (a, b, s): the 2-step geodesic from a to s passes through b.
// The shell: a finger whose middle band is squeezed along its axis in the
// step a -> b, so that 2 b - a squeezes it past zero.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/calculus/exp_step_continuation.h"
#include "shellspace/problems/calculus/exp_step_newton.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

constexpr double kLength = 4.0;

// The finger's band 1.5 <= y <= 2.5 scaled along y by `factor`, the part
// above it moved down to stay attached.
Positions SqueezeBand(const Positions& shape, double factor) {
  Positions out = shape;
  for (int v = 0; v < shape.rows(); ++v) {
    const double y = shape(v, 1);
    out(v, 1) = y < 1.5   ? y
                : y < 2.5 ? 1.5 + factor * (y - 1.5)
                          : y - (1 - factor);
  }
  return out;
}

// One forward EXP step's equation F(s) = D_2 W[a, b] + D_1 W[b, s] for the
// finger squeezed by `factor`; holds what the equation refers to.
struct SqueezedStep {
  explicit SqueezedStep(double factor)
      : finger(MakeFinger(0.5, kLength, 12, 12, 3)),
        space(testing::MakeSpace(finger)),
        a(finger.positions),
        b(SqueezeBand(a, factor)),
        constant(EnergyGradient(space, a, b, ShellSide::kDeformed)),
        scale(constant.cwiseAbs().maxCoeff()) {}
  ExpStepEquation Equation() const {
    return {space, b, ShellSide::kDeformed, constant, no_mask};
  }
  // max |F(s)| / max |D_2 W[a, b]|: 0 at the step's root.
  double RelativeResidual(const Positions& s) const {
    return ExpResidualMaxNorm(Equation(), s) / scale;
  }
  ExpContinuationSettings Settings() const {
    ExpContinuationSettings settings;
    settings.tolerance = 1e-11 * scale;
    settings.accept = 1e-8 * scale;
    settings.intermediate_tolerance = 1e-8 * scale;
    return settings;
  }
  Mesh finger;
  ShellSpace space;
  Positions a, b;
  Eigen::VectorXd constant;
  double scale;
  std::vector<int> no_mask;
};

// max over 6 random directions d (unit max-norm) of
// |dE/dd| / |dW[a, .]/dd| at x = b, E(x) = W[a, x] + W[x, s], both by
// central differences of the path energy (not the analytic gradient).
double StationarityAtB(const SqueezedStep& step, const Positions& s) {
  std::srand(7);
  double worst = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Positions d = Positions::Random(step.b.rows(), 3);
    const double h = 1e-6;
    const auto energy = [&](const Positions& x, bool with_s) {
      return with_s ? PathEnergy(step.space, {step.a, x, s})
                    : PathEnergy(step.space, {step.a, x});
    };
    const double path_slope =
        (energy(step.b + h * d, true) - energy(step.b - h * d, true)) / (2 * h);
    const double first_slope =
        (energy(step.b + h * d, false) - energy(step.b - h * d, false)) /
        (2 * h);
    // (E_K = K sum W: the 2-step energy is 2 (W[a, x] + W[x, s]).)
    worst = std::max(worst, std::abs(path_slope / 2) / std::abs(first_slope));
  }
  return worst;
}

TEST(ExpContinuationTest, FollowsTheLoadToTheRootNewtonFromTheGuessMisses) {
  const SqueezedStep step(0.4);  // 2 b - a squeezes the band to -0.2
  // Newton from the plain guess stops far from any root ...
  Positions plain = 2 * step.b - step.a;
  const ExpNewtonReport newton = SolveExpStepNewton(
      step.Equation(),
      ExpNewtonStopping{1e-11 * step.scale, 1e-8 * step.scale, 20}, &plain);
  EXPECT_FALSE(newton.converged);
  EXPECT_GT(step.RelativeResidual(plain), 0.1);  // the twin of the check below
  // ... the continuation reaches one, in a few load steps.
  Positions root;
  const ExpContinuationReport report = SolveExpStepByContinuation(
      step.Equation(), 2 * step.b - step.a, step.Settings(), &root);
  ASSERT_TRUE(report.solved) << report.stop_reason;
  EXPECT_EQ(report.load, 1.0);
  EXPECT_LE(report.substeps, 8);
  EXPECT_LE(step.RelativeResidual(root), 1e-8);
  // Independently: (a, b, root) is a discrete geodesic, b a critical point
  // of x -> W[a, x] + W[x, root]: the central differences of that path
  // energy at b vanish in every direction, relative to those of W[a, x]
  // alone. The twin: at the point where plain Newton stopped they do not.
  EXPECT_LE(StationarityAtB(step, root), 1e-5);
  EXPECT_GT(StationarityAtB(step, plain), 1e-2);
}

TEST(ExpContinuationTest, WithoutItsLoadStepsTheContinuationIsNewtonFromB) {
  // The twin of the load steps: one load step of 1 is Newton from b at the
  // full load, which takes more Newton steps than each load step needs; it
  // still finds the same root here, so the results must agree.
  const SqueezedStep step(0.4);
  Positions continued, single;
  ExpContinuationSettings settings = step.Settings();
  const ExpContinuationReport stepped = SolveExpStepByContinuation(
      step.Equation(), 2 * step.b - step.a, settings, &continued);
  settings.first_load_step = settings.min_load_step = 1;
  const ExpContinuationReport one = SolveExpStepByContinuation(
      step.Equation(), 2 * step.b - step.a, settings, &single);
  ASSERT_TRUE(stepped.solved);
  ASSERT_TRUE(one.solved);
  EXPECT_EQ(one.substeps, 1);
  EXPECT_GT(stepped.substeps, 1);
  // (Roots are defined up to a rigid motion: F ignores one of s.)
  EXPECT_LE(RelativeDistanceUpToRigidMotion(continued, single), 1e-8);
}

TEST(ExpContinuationTest, ADegenerateGuessIsNotASolvedStep) {
  // Squeezed to half, 2 b - a flattens the band's triangles to zero area:
  // F cannot be evaluated there. Newton from it reports an infinite
  // residual (not 0) ...
  const SqueezedStep step(0.5);
  Positions plain = 2 * step.b - step.a;
  EXPECT_EQ(step.RelativeResidual(plain), HUGE_VAL);
  const ExpNewtonReport newton = SolveExpStepNewton(
      step.Equation(),
      ExpNewtonStopping{1e-11 * step.scale, 1e-8 * step.scale, 20}, &plain);
  EXPECT_EQ(newton.stop, NewtonStop::kInfeasibleStart);
  EXPECT_FALSE(newton.final_gradient <= 1e-8 * step.scale);
  // ... and the EXP step finds the root by the continuation, not the
  // degenerate guess.
  const ExpStepResult result =
      ExpStep(step.space, step.a, step.b, StepDirection::kForward, {},
              testing::TightSettings(1e-10));
  EXPECT_TRUE(result.solved);
  EXPECT_GT(result.continuation_substeps, 0);
  EXPECT_LE(step.RelativeResidual(result.shape), 1e-8);
}

}  // namespace
}  // namespace shellspace
