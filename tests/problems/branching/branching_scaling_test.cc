// The scaling law from the relaxed simulation on a small, fast ladder: the
// fitted exponent of eps lies within 0.1 of 2/3 (rule: scaling_ladder.h).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "shellspace/problems/branching/scaling_ladder.h"

namespace shellspace::branching {
namespace {

TEST(BranchingScaling, PowerLawFitRecoversKnownExponent) {
  // Independent check of the fit itself on synthetic data.
  std::vector<double> eps = {1e-3, 3e-3, 1e-2}, energy;
  for (double e : eps) energy.push_back(4.2 * std::pow(e, 0.6) * std::cbrt(2.0));
  double p = 0, c = 0;
  FitPowerLaw(eps, energy, 2.0, &p, &c);
  EXPECT_NEAR(p, 0.6, 1e-12);
  EXPECT_NEAR(c, 4.2, 1e-10);
}

TEST(BranchingScaling, FittedExponentNearTwoThirds) {
  LadderSettings s;
  for (int k = 0; k < 5; ++k) s.epsilons.push_back(1e-3 * std::pow(10.0, k / 4.0));
  s.height = 0.5;
  s.nx = 20;
  s.delta_over_lambda = 0.15;
  s.continuation = 2;
  const LadderResult r = RunLadder(s, [](const LadderRung& rung) {
    std::printf("eps %.4g delta %.4g ny %d periods %d E %.6g (%.2f s)\n",
                rung.epsilon, rung.delta, rung.ny, rung.periods, rung.energy,
                rung.seconds);
  });
  std::printf("exponent %.4f constant %.4f\n", r.exponent, r.constant);
  EXPECT_NEAR(r.exponent, 2.0 / 3.0, 0.1);
  // The relaxed constant lies below the sharp needle (T2) upper bound 6.856
  // (and so below C_KM = 7.546 / 8.638).
  EXPECT_GT(r.constant, 1.0);
  EXPECT_LT(r.constant, 6.86);
}

}  // namespace
}  // namespace shellspace::branching
