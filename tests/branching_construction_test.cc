// The reduced sharp-interface model: generic cell evaluator vs the KM closed
// form, the lens reduced formula, and the lens optimisation.
#include <cmath>

#include <gtest/gtest.h>

#include "problems/branching/cell_pattern.h"
#include "problems/branching/construction_optimizer.h"
#include "problems/branching/km_family.h"
#include "problems/branching/lens_family.h"
#include "problems/branching/self_similar_series.h"

namespace shellspace::branching {
namespace {

TEST(BranchingKm, CellCoefficientsMatchClosedForm) {
  const CellCoefficients c = EvaluateCell(KmCellPattern());
  EXPECT_NEAR(c.A, 1.0 / 32.0, 1e-14);
  EXPECT_NEAR(c.B, 8.0, 1e-14);
}

TEST(BranchingKm, ThetaRootOfCubic) {
  const double t = KmOptimalTheta();
  EXPECT_NEAR(8 * t * t * t - 12 * t * t + 1, 0.0, 1e-14);
  EXPECT_NEAR(OptimalTheta(2), t, 1e-7);
}

TEST(BranchingKm, EvaluatorEqualsClosedFormConstant) {
  const ConstructionResult km = DefaultKm(1e-3, 2.0);
  const double closed = KmClosedFormConstant();
  EXPECT_NEAR(km.constant, closed, 1e-8 * closed);
  // The general series formula agrees with the KM closed form at any theta.
  for (double theta : {0.26, 0.3, 0.4, 0.49}) {
    EXPECT_NEAR(SeriesConstant(1.0 / 32.0, 8.0, 2, theta), KmConstantAt(theta),
                1e-12 * KmConstantAt(theta));
  }
  // At the optimum the elastic part is a third.
  EXPECT_NEAR(km.elastic / (km.elastic + km.interfacial), 1.0 / 3.0, 1e-10);
  std::printf("C_KM closed form %.12f evaluator %.12f theta %.12f\n", closed,
              km.constant, km.theta);
}

TEST(BranchingKm, LmReachesClosedForm) {
  const ConstructionResult km = OptimizeKm(1e-3, 1.0, 0.1, 0.3);
  EXPECT_NEAR(km.constant, KmClosedFormConstant(), 1e-8 * km.constant);
  EXPECT_NEAR(km.theta, KmOptimalTheta(), 1e-4);
}

TEST(BranchingLens, GenericEvaluatorMatchesReducedFormula) {
  for (const LensShape shape : {LensShape{0.0, 0.0, 0.0}, LensShape{0.3, 0.2, -0.4},
                                LensShape{0.6, -0.5, 0.7}}) {
    const CellCoefficients c = EvaluateCell(LensCellPattern(shape), 16);
    EXPECT_NEAR(c.A, LensReducedA(shape), 1e-12);
    EXPECT_NEAR(c.B, LensReducedB(shape), 1e-12);
  }
}

TEST(BranchingLens, OptimizedConstantBelowKm) {
  const ConstructionResult start = DefaultLens(1e-3, 1.0);
  const ConstructionResult lens =
      OptimizeLens(1e-3, 1.0, start.h0, start.theta, LensShape{0.2, 0.0, 0.0});
  std::printf("lens default %.10f optimised %.10f h0 %.6g theta %.8f tau %.8f "
              "a1 %.8f a2 %.8f iters %d %s\n",
              start.constant, lens.constant, lens.h0, lens.theta,
              lens.shape.tau, lens.shape.a1, lens.shape.a2, lens.iterations,
              lens.termination.c_str());
  EXPECT_LT(lens.constant, KmClosedFormConstant());
  EXPECT_LE(lens.constant, start.constant);
}

}  // namespace
}  // namespace shellspace::branching
