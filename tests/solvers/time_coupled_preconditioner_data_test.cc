// The time-coupled preconditioner of path Hessians: exact on the Kronecker
// model K T (x) G (and not on a model it does not represent), symmetric and
// positive definite on slices with different metrics, independent of the
// thread count; its CG against a direct solve of a real path Hessian, with
// fewer iterations than block Jacobi; the fallback where the slices differ.
#include "shellspace/solvers/time_coupled_preconditioner.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <iostream>
#include <random>
#include <utility>

#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/block_jacobi_cg.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "tests/testing/kronecker_model.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// The lower triangles of the diagonal blocks of `lower` (slices of size m).
std::vector<SparseMatrix> DiagonalBlocks(const SparseMatrix& lower, int m) {
  std::vector<SparseMatrix> blocks;
  for (int begin = 0; begin < lower.rows(); begin += m) {
    SparseMatrix block = lower.block(begin, begin, m, m);
    block.makeCompressed();
    blocks.push_back(block);
  }
  return blocks;
}

Eigen::VectorXd TestVector(int size, double phase) {
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) v(i) = std::sin(0.37 * i + phase) + 0.1;
  return v;
}

using Precision = TimeCoupledPreconditioner::FactorPrecision;

// max |M^-1 H x - x| / |x| for the preconditioner of H's diagonal blocks,
// its couplings fitted to H if `fit`, its factors kept in `precision`.
double ModelError(const SparseMatrix& lower, int m, bool fit = false,
                  Precision precision = Precision::kDouble) {
  TimeCoupledPreconditioner p;
  p.set_factor_precision(precision);
  EXPECT_EQ(p.Factorize(DiagonalBlocks(lower, m), 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  if (fit) p.FitCouplings(lower, 2);
  const Eigen::VectorXd x = TestVector(static_cast<int>(lower.rows()), 0.3);
  const Eigen::VectorXd hx = lower.selfadjointView<Eigen::Lower>() * x;
  return (p.Apply(hx, 2) - x).cwiseAbs().maxCoeff() / x.cwiseAbs().maxCoeff();
}

TEST(TimeCoupledPreconditionerTest, IsTheInverseOfTheKroneckerModel) {
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  for (int K : {2, 3, 8, 16}) {
    const SparseMatrix lower = testing::KroneckerPathModel(g, K);
    EXPECT_LT(ModelError(lower, m), 1e-10) << K;
    // The default, factors in float: exact for the rounded factors, so
    // within float round-off of the model (2^-24 = 6e-8 per entry, times
    // the conditioning of the metric's factor), and not exact.
    const double single = ModelError(lower, m, false, Precision::kSingle);
    EXPECT_LT(single, 1e-5) << K;
    EXPECT_GT(single, 1e-12) << K;
  }
  // Float factors of matrices far outside float's range (entries 1e-60 and
  // 1e60): scaled by a power of two before rounding, they lose nothing more.
  for (double size : {1e-60, 1e60}) {
    const SparseMatrix lower = size * testing::KroneckerPathModel(g, 3);
    EXPECT_LT(ModelError(lower, m, false, Precision::kSingle), 1e-5) << size;
  }
  // The twin: with the diagonal blocks scaled by 1.5 the couplings are not
  // -C_i C_i+1^T / 2 any more, and the same check sees it.
  EXPECT_GT(ModelError(testing::KroneckerPathModel(g, 8, 1.5), m), 1e-2);
}

// With the diagonal blocks 2 s K G and couplings -K G the whitened coupling
// is -I / (2 s): the fit gives theta = 1 / s exactly (Rademacher probes:
// z^T z = m), and the fitted model is exact again.
TEST(TimeCoupledPreconditionerTest, FittedCouplingsOfScaledKroneckerModels) {
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  for (double scale : {1.0, 1.5, 4.0}) {
    const SparseMatrix lower = testing::KroneckerPathModel(g, 6, scale);
    TimeCoupledPreconditioner p;
    p.set_factor_precision(Precision::kDouble);
    ASSERT_EQ(p.Factorize(DiagonalBlocks(lower, m), 2),
              TimeCoupledPreconditioner::Status::kFactorized);
    p.FitCouplings(lower, 2);
    ASSERT_EQ(p.couplings().size(), 4u);
    for (double theta : p.couplings()) {
      EXPECT_NEAR(theta, 1 / scale, 1e-12) << scale;
    }
    EXPECT_LT(ModelError(lower, m, /*fit=*/true), 1e-10) << scale;
  }
  // Couplings of the wrong sign are not modelled: theta is clamped to 0
  // (block Jacobi).
  SparseMatrix flipped = testing::KroneckerPathModel(g, 4);
  for (int c = 0; c < flipped.outerSize(); ++c) {
    for (SparseMatrix::InnerIterator it(flipped, c); it; ++it) {
      if (it.row() / m != c / m) it.valueRef() = -it.value();
    }
  }
  TimeCoupledPreconditioner p;
  ASSERT_EQ(p.Factorize(DiagonalBlocks(flipped, m), 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  p.FitCouplings(flipped, 2);
  for (double theta : p.couplings()) EXPECT_EQ(theta, 0.0);
}

// A path model of 3 slices of m = 101^2 unknowns (a grid Laplacian plus I
// as the metric G) whose couplings are not the model's: -K (0.8 G + 0.3 R),
// R with G's off-diagonal pattern and random signs (fixed seed). By default
// (FitProbes: one probe from 10,000 unknowns) the fitted thetas are those
// of 64 probes within 0.01 (the bound of FitProbes' comment: 3 standard
// deviations are 0.013 x theta / 2), and 64 probes give theta near 0.8
// (the pairs are kept and the fit measures something). Below 10,000
// unknowns the default is two probes.
TEST(TimeCoupledPreconditionerTest, OneProbeFitsTheCouplingsOfLargeSlices) {
  EXPECT_EQ(FitProbes(kOneFitProbeFromUnknowns - 1), 2);
  EXPECT_EQ(FitProbes(kOneFitProbeFromUnknowns), 1);
  const int side = 101, m = side * side, K = 4;
  ASSERT_GE(m, kOneFitProbeFromUnknowns);
  std::vector<Eigen::Triplet<double>> g_entries, r_entries;
  std::mt19937 generator(7);
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const int v = y * side + x;
      int degree = 0;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        if (x + dx < 0 || x + dx >= side || y + dy < 0 || y + dy >= side) {
          continue;
        }
        const int w = (y + dy) * side + x + dx;
        g_entries.emplace_back(v, w, -1.0);
        r_entries.emplace_back(v, w, (generator() & 1u) ? 1.0 : -1.0);
        ++degree;
      }
      g_entries.emplace_back(v, v, degree + 1.0);
    }
  }
  SparseMatrix g(m, m), r(m, m);
  g.setFromTriplets(g_entries.begin(), g_entries.end());
  r.setFromTriplets(r_entries.begin(), r_entries.end());
  const SparseMatrix diagonal = SparseMatrix(2.0 * K * g);
  const SparseMatrix coupling = SparseMatrix(-K * (0.8 * g + 0.3 * r));
  std::vector<Eigen::Triplet<double>> h;
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < m; ++c) {
      for (SparseMatrix::InnerIterator it(diagonal, c); it; ++it) {
        if (it.row() >= c)
          h.emplace_back(i * m + it.row(), i * m + c, it.value());
      }
      if (i == 2) continue;  // rows of slice i + 1, columns of slice i
      for (SparseMatrix::InnerIterator it(coupling, c); it; ++it) {
        h.emplace_back((i + 1) * m + it.row(), i * m + c, it.value());
      }
    }
  }
  SparseMatrix lower(3 * m, 3 * m);
  lower.setFromTriplets(h.begin(), h.end());
  const auto fitted = [&](int probes) {
    TimeCoupledPreconditioner p;
    EXPECT_EQ(p.Factorize(DiagonalBlocks(lower, m), 2),
              TimeCoupledPreconditioner::Status::kFactorized);
    p.FitCouplings(lower, 2, probes);
    return p.couplings();
  };
  const std::vector<double> one = fitted(0), many = fitted(64);
  ASSERT_EQ(one.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(many[i], 0.8, 0.05) << i;
    EXPECT_NEAR(one[i], many[i], 0.01) << i;
    EXPECT_NE(one[i], many[i]) << i;  // it is an estimate
  }
}

TEST(TimeCoupledPreconditionerTest, SymmetricPositiveAndThreadIndependent) {
  // Slices with different metrics: G scaled by 1, 1.5, 2, ... and shifted.
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  SparseMatrix identity(m, m);
  identity.setIdentity();
  std::vector<SparseMatrix> blocks;
  for (int i = 0; i < 5; ++i) {
    SparseMatrix block =
        SparseMatrix((1.0 + 0.5 * i) * g + 0.2 * i * identity)
            .triangularView<Eigen::Lower>();
    block.makeCompressed();
    blocks.push_back(block);
  }
  TimeCoupledPreconditioner p;
  ASSERT_EQ(p.Factorize(blocks, 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  EXPECT_EQ(p.slices(), 5);
  const Eigen::VectorXd u = TestVector(5 * m, 0.1), v = TestVector(5 * m, 2.0);
  const Eigen::VectorXd pu = p.Apply(u, 2), pv = p.Apply(v, 2);
  EXPECT_NEAR(v.dot(pu), u.dot(pv), 1e-12 * std::abs(u.dot(pv)));
  EXPECT_GT(u.dot(pu), 0);
  EXPECT_GT(v.dot(pv), 0);
  // The same digits with one thread.
  EXPECT_EQ(p.Apply(u, 1), pu);
}

TEST(TimeCoupledPreconditionerTest, ReportsDifferentPatternsAndIndefiniteBlocks) {
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  std::vector<SparseMatrix> blocks =
      DiagonalBlocks(testing::KroneckerPathModel(g, 4), m);
  TimeCoupledPreconditioner p;
  std::vector<SparseMatrix> other = blocks;
  other[1] = other[1].block(0, 0, m - 3, m - 3);  // one vertex fewer
  EXPECT_EQ(p.Factorize(other, 2),
            TimeCoupledPreconditioner::Status::kDifferentPatterns);
  other = blocks;
  other[2] = -other[2];
  EXPECT_EQ(p.Factorize(other, 2),
            TimeCoupledPreconditioner::Status::kNotPositive);
  // The same answers from blocks made on demand (each by the task that
  // factorises it, the pattern checked there), and each block asked for
  // once (block 0 for the analysis).
  const int count = static_cast<int>(blocks.size());
  other = blocks;
  other[count - 1] = other[count - 1].block(0, 0, m - 3, m - 3);
  std::vector<int> calls(count, 0);
  const auto source = [&](const std::vector<SparseMatrix>& from) {
    return [&calls, &from](int i, SparseMatrix* block) {
      ++calls[i];
      *block = from[i];
    };
  };
  EXPECT_EQ(p.Factorize(count, source(other), 2),
            TimeCoupledPreconditioner::Status::kDifferentPatterns);
  std::fill(calls.begin(), calls.end(), 0);
  ASSERT_EQ(p.Factorize(count, source(blocks), 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  EXPECT_EQ(calls, std::vector<int>(count, 1));
  // From the vector on one thread (one slice at a time instead of the
  // memory-bounded waves): the same factors, bit for bit.
  TimeCoupledPreconditioner q;
  ASSERT_EQ(q.Factorize(blocks, 1),
            TimeCoupledPreconditioner::Status::kFactorized);
  const Eigen::VectorXd u = TestVector(count * m, 0.3);
  EXPECT_EQ(p.Apply(u, 2), q.Apply(u, 2));
}

// The symbolic analysis is kept from one Factorize to the next of the same
// pattern, and made afresh for another pattern: a preconditioner that has
// factorised other values, and then another pattern, applies the same
// digits as a fresh one, bit for bit, at each stage.
TEST(TimeCoupledPreconditionerTest, AKeptAnalysisGivesTheFreshFactors) {
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  const std::vector<SparseMatrix> blocks =
      DiagonalBlocks(testing::KroneckerPathModel(g, 4), m);
  const int count = static_cast<int>(blocks.size());
  std::vector<SparseMatrix> scaled;  // the same pattern, other values
  for (int i = 0; i < count; ++i) {
    SparseMatrix block = (1.0 + 0.25 * i) * blocks[i];
    block.diagonal().array() += 0.5;
    scaled.push_back(block);
  }
  std::vector<SparseMatrix> smaller;  // another pattern: one vertex fewer
  for (const SparseMatrix& block : blocks) {
    SparseMatrix cut = block.block(0, 0, m - 3, m - 3);
    cut.makeCompressed();
    smaller.push_back(cut);
  }
  const auto fresh_apply = [](const std::vector<SparseMatrix>& b,
                              const Eigen::VectorXd& u) {
    TimeCoupledPreconditioner fresh;
    EXPECT_EQ(fresh.Factorize(b, 2),
              TimeCoupledPreconditioner::Status::kFactorized);
    return fresh.Apply(u, 2);
  };
  TimeCoupledPreconditioner kept;
  const Eigen::VectorXd u = TestVector(count * m, 0.7);
  ASSERT_EQ(kept.Factorize(blocks, 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  ASSERT_EQ(kept.Factorize(scaled, 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  EXPECT_EQ(kept.Apply(u, 2), fresh_apply(scaled, u));
  // Not the factors of the first values: the check can tell them apart.
  EXPECT_NE(kept.Apply(u, 2), fresh_apply(blocks, u));
  const Eigen::VectorXd w = TestVector(count * (m - 3), 0.2);
  ASSERT_EQ(kept.Factorize(smaller, 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  EXPECT_EQ(kept.Apply(w, 2), fresh_apply(smaller, w));
  ASSERT_EQ(kept.Factorize(blocks, 2),
            TimeCoupledPreconditioner::Status::kFactorized);
  EXPECT_EQ(kept.Apply(u, 2), fresh_apply(blocks, u));
}

// CG iterations to 1e-10 with block Jacobi [0] and the fitted time-coupled
// preconditioner [1] on the Hessian of the plate geodesic (two rows masked,
// as in block_jacobi_cg_data_test.cc, K = 8) to `roll` times the roll of
// plate121_rolledA, each checked against a direct solve; `theta` receives
// the fitted couplings.
std::array<int, 2> PlateCgIterations(double roll, std::vector<double>* theta) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  const int K = 8;
  std::vector<int> mask;
  for (int v = 0; v < 15; ++v) mask.push_back(v);
  const Positions end = (1 - roll) * a.positions + roll * b.positions;
  GeodesicInput input = GeodesicInput::Between(a.positions, end, K);
  input.fixed_vertices = mask;
  const ShellPath path = SolveGeodesic(space, input, SolverSettings{}).path;
  const SparseMatrix basis = FreeVertexBasis(a.num_vertices(), mask);
  const SparseMatrix lower = PathHessianAssembler(space).Assemble(
      path, std::vector<SparseMatrix>(K - 1, basis), 2);
  const int m = static_cast<int>(basis.cols());
  const Eigen::VectorXd rhs = TestVector(static_cast<int>(lower.rows()), 1.0);
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> direct(lower);
  EXPECT_EQ(direct.info(), Eigen::Success);
  const Eigen::VectorXd expected = direct.solve(rhs);
  std::array<int, 2> iterations = {0, 0};
  for (int coupled = 0; coupled < 2; ++coupled) {
    BlockJacobiCg cg;
    cg.set_time_coupling(coupled == 1);
    EXPECT_TRUE(cg.Factorize(lower, testing::SliceOffsets(K - 1, m)));
    EXPECT_EQ(cg.time_coupled(), coupled == 1);
    if (coupled == 1) *theta = cg.couplings();
    Eigen::VectorXd x;
    EXPECT_EQ(cg.Solve(lower, rhs, 1e-10, 2000, &x, &iterations[coupled]),
              BlockJacobiCg::Status::kSolved);
    EXPECT_LT((x - expected).norm(), 1e-7 * expected.norm()) << coupled;
  }
  std::cout << "plate, roll " << roll << ": CG iterations block Jacobi "
            << iterations[0] << ", time-coupled " << iterations[1]
            << "; theta";
  for (double t : *theta) std::cout << " " << t;
  std::cout << "\n";
  return iterations;
}

// A quarter roll: neighbouring slices have nearly the same metric, the
// couplings are fitted close to 1 and CG needs far fewer iterations.
TEST(TimeCoupledPreconditionerTest, FewerCgIterationsOnAGentlePath) {
  std::vector<double> theta;
  const std::array<int, 2> iterations = PlateCgIterations(0.25, &theta);
  for (double t : theta) EXPECT_GT(t, 0.9);
  EXPECT_LT(iterations[1], 0.6 * iterations[0]);
}

// The whole roll in 8 steps: the stiff directions turn between slices and
// two middle pairs are poorly modelled; they are left uncoupled and CG is
// no slower than block Jacobi (fully coupled it took 78 against 43).
TEST(TimeCoupledPreconditionerTest, NoWorseThanBlockJacobiOnARollingPath) {
  std::vector<double> theta;
  const std::array<int, 2> iterations = PlateCgIterations(1.0, &theta);
  EXPECT_EQ(std::count(theta.begin(), theta.end(), 0.0), 2);
  EXPECT_LE(iterations[1], iterations[0]);
}

TEST(TimeCoupledPreconditionerTest, BlockCgFallsBackWhereSlicesDiffer) {
  // Slices of different sizes: block Jacobi runs, and still solves.
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  const SparseMatrix lower = testing::KroneckerPathModel(g, 4);
  const std::vector<int> offsets = {0, m - 3, 2 * m, 3 * m};
  BlockJacobiCg cg;
  cg.set_time_coupling(true);
  ASSERT_TRUE(cg.Factorize(lower, offsets));
  EXPECT_FALSE(cg.time_coupled());
  Eigen::VectorXd x;
  const Eigen::VectorXd b = TestVector(static_cast<int>(lower.rows()), 0.5);
  ASSERT_EQ(cg.Solve(lower, b, 1e-10, 500, &x), BlockJacobiCg::Status::kSolved);
  EXPECT_LT((lower.selfadjointView<Eigen::Lower>() * x - b).norm(),
            1e-9 * b.norm());
}

}  // namespace
}  // namespace shellspace
