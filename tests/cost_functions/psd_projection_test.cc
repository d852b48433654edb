// Projected Hessians (psd_projection.h, HessianModel::kProjected):
//   - a projected matrix is positive semidefinite and is the nearest such
//     matrix (its distance to the input is the norm of the input's negative
//     eigenvalues, computed independently);
//   - a positive semidefinite matrix is left exactly as it is;
//   - the projected path Hessian of PathHessianAssembler is the sum, over
//     the terms W[s_{k-1}, s_k] and their elements, of each term's Hessian
//     in its free shapes projected on its own (assembled here densely, from
//     the exact element blocks and a dense eigen-decomposition); it is
//     positive semidefinite where the exact one is indefinite, and equal to
//     the exact one on a path whose terms are all convex (every shape the
//     same: each term at its minimum);
// each with a negative twin through the same helper (an unprojected matrix,
// the exact path Hessian in place of the projected one).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/psd_projection.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using Dense = Eigen::MatrixXd;

// How far `m` (symmetric) is from positive semidefinite: max(0, -lambda_min)
// relative to max |lambda|.
double PsdViolation(const Dense& m) {
  const Eigen::SelfAdjointEigenSolver<Dense> eigen(m);
  const double scale = eigen.eigenvalues().cwiseAbs().maxCoeff();
  return std::max(0.0, -eigen.eigenvalues().minCoeff()) / scale;
}

// max |a - b| / max |b|.
double RelativeDifference(const Dense& a, const Dense& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// A random symmetric 24 x 24 matrix with eigenvalues in [-1, 3].
Eigen::Matrix<double, 24, 24> RandomIndefinite(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<double, 24, 24> a;
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j) a(i, j) = u(rng);
  const Eigen::HouseholderQR<Eigen::Matrix<double, 24, 24>> qr(a);
  const Eigen::Matrix<double, 24, 24> q = qr.householderQ();
  Eigen::Matrix<double, 24, 1> lambda;
  for (int i = 0; i < 24; ++i) lambda(i) = -1 + 4.0 * i / 23;
  return q * lambda.asDiagonal() * q.transpose();
}

TEST(PsdProjectionTest, ProjectionIsPositiveSemidefiniteAndNearest) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::Matrix<double, 24, 24> a = RandomIndefinite(seed);
    ASSERT_GT(PsdViolation(a), 0.1);  // the twin: the input fails the check
    Eigen::Matrix<double, 24, 24> p = a;
    EXPECT_TRUE(ProjectToPositiveSemidefinite(&p));
    EXPECT_LE(PsdViolation(p), 1e-13);
    // The nearest: |A - P(A)|_F = sqrt(sum of the negative eigenvalues^2).
    const Eigen::SelfAdjointEigenSolver<Dense> eigen{Dense(a)};
    double negative = 0;
    for (int i = 0; i < 24; ++i) {
      negative += std::pow(std::min(0.0, eigen.eigenvalues()(i)), 2);
    }
    EXPECT_NEAR((a - p).norm(), std::sqrt(negative), 1e-12);
    // And P(A) - A is positive semidefinite (only the negative part moved).
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Dense>(Dense(p - a))
                  .eigenvalues()
                  .minCoeff(),
              -1e-12);
  }
}

TEST(PsdProjectionTest, PositiveSemidefiniteMatricesAreLeftExactly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<double, 12, 9> b;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 9; ++j) b(i, j) = u(rng);
  // Rank 9 of 12: singular, as an element at rest (its rigid motions).
  const Eigen::Matrix<double, 12, 12> psd = b * b.transpose();
  Eigen::Matrix<double, 12, 12, Eigen::RowMajor> p = psd;
  EXPECT_FALSE(ProjectToPositiveSemidefinite(&p));
  EXPECT_EQ(Dense(p), Dense(psd));  // bit for bit
  // Its negative is not: projected to (nearly) zero.
  Eigen::Matrix<double, 12, 12, Eigen::RowMajor> n = -psd;
  EXPECT_TRUE(ProjectToPositiveSemidefinite(&n));
  EXPECT_LE(n.cwiseAbs().maxCoeff(), 1e-12 * psd.cwiseAbs().maxCoeff());
}

TEST(PsdProjectionTest, ModuloTranslationsEqualsTheFullProjection) {
  // A random indefinite matrix of two 4-vertex stencils that annihilates
  // each stencil's translations: Z S Z^T, Z the complement basis.
  const auto z = TranslationComplementBasis<4, 2>();
  ASSERT_LE((z.transpose() * z - Eigen::Matrix<double, 18, 18>::Identity())
                .cwiseAbs()
                .maxCoeff(),
            1e-15);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<double, 18, 18> s;
  for (int i = 0; i < 18; ++i)
    for (int j = 0; j <= i; ++j) s(i, j) = s(j, i) = u(rng);
  const Eigen::Matrix<double, 24, 24> a = z * s * z.transpose();
  Eigen::Matrix<double, 24, 24> full = a, reduced = a;
  ASSERT_TRUE(ProjectToPositiveSemidefinite(&full));
  EXPECT_TRUE((ProjectToPositiveSemidefiniteModuloTranslations<4, 2>(&reduced)));
  EXPECT_LE(RelativeDifference(reduced, full), 1e-13);
  // Twin: a matrix that moves a translation is not projected alike.
  Eigen::Matrix<double, 24, 24> b = a, b_full = a;
  b(0, 0) += 1;
  b_full(0, 0) += 1;
  ProjectToPositiveSemidefinite(&b_full);
  ProjectToPositiveSemidefiniteModuloTranslations<4, 2>(&b);
  EXPECT_GT(RelativeDifference(b, b_full), 1e-3);
}

// The Hessian of E_K in the inner shapes (all 3n coordinates each) with
// every term's Hessian projected on its own: each element of each term
// W[s_{k-1}, s_k] (weight K) differentiated in both arguments (the exact
// element blocks), restricted to its free arguments (the ends are data),
// projected by a dense eigen-decomposition, added.
Dense ProjectedPathHessianByTerms(const ShellSpace& space,
                                  const std::vector<Positions>& path) {
  const int K = static_cast<int>(path.size()) - 1;
  const int n = 3 * space.num_vertices;
  Dense h = Dense::Zero((K - 1) * n, (K - 1) * n);
  space.elements().ForEachGroup([&](const auto& group) {
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    constexpr int m = 3 * kV;
    for (int k = 1; k <= K; ++k) {
      for (const auto& stencil : group.stencils) {
        double a[m], b[m];
        GatherCoordinates(path[k - 1], stencil, a);
        GatherCoordinates(path[k], stencil, b);
        ElementSecondDerivatives<kV> ref_active, def_active;
        ASSERT_TRUE(ref_active.Compute(group.element, a, b,
                                       ShellSide::kReference, K));
        ASSERT_TRUE(def_active.Compute(group.element, a, b,
                                       ShellSide::kDeformed, K));
        Dense term(2 * m, 2 * m);
        term << Dense(ref_active.d_grad_reference),
            Dense(def_active.d_grad_reference),
            Dense(ref_active.d_grad_deformed),
            Dense(def_active.d_grad_deformed);
        // The free arguments: the shapes 1 .. K - 1 (slot 0 of the term is
        // s_{k-1}, slot 1 is s_k).
        std::vector<int> slots;
        if (k - 1 >= 1) slots.push_back(0);
        if (k <= K - 1) slots.push_back(1);
        const int free = static_cast<int>(slots.size()) * m;
        Dense sub(free, free);
        for (size_t i = 0; i < slots.size(); ++i)
          for (size_t j = 0; j < slots.size(); ++j)
            sub.block(i * m, j * m, m, m) =
                term.block(slots[i] * m, slots[j] * m, m, m);
        const Eigen::SelfAdjointEigenSolver<Dense> eigen(sub);
        const Dense projected =
            eigen.eigenvectors() *
            eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
            eigen.eigenvectors().transpose();
        for (size_t i = 0; i < slots.size(); ++i) {
          for (size_t j = 0; j < slots.size(); ++j) {
            const int si = k - 1 + slots[i] - 1, sj = k - 1 + slots[j] - 1;
            for (int va = 0; va < kV; ++va)
              for (int vb = 0; vb < kV; ++vb)
                h.block<3, 3>(si * n + 3 * stencil[va],
                              sj * n + 3 * stencil[vb]) +=
                    projected.block<3, 3>(i * m + 3 * va, j * m + 3 * vb);
          }
        }
      }
    }
  });
  return h;
}

// The assembler's Hessian of `model` on `path`, dense and symmetric, in all
// coordinates of the inner shapes.
Dense AssembledPathHessian(const ShellSpace& space,
                           const std::vector<Positions>& path,
                           HessianModel model) {
  const int K = static_cast<int>(path.size()) - 1;
  const std::vector<Eigen::SparseMatrix<double>> bases(
      K - 1, FreeVertexBasis(space.num_vertices, {}));
  const PathHessianAssembler assembler(space, model);
  const Dense lower = Dense(assembler.Assemble(path, bases, 2));
  return lower.selfadjointView<Eigen::Lower>();
}

struct Fixture {
  testing::BumpySheetPair pair = testing::MakeBumpySheetPair();
  ShellSpace space = testing::MakeSpace(pair.mesh);
  // K = 3 on the linear path between the two bumpy sheets, whose terms
  // are far from their rest state.
  std::vector<Positions> path{pair.reference,
                              (2 * pair.reference + pair.deformed) / 3,
                              (pair.reference + 2 * pair.deformed) / 3,
                              pair.deformed};
};

TEST(ProjectedPathHessianTest, IsTheSumOfTheProjectedTerms) {
  const Fixture f;
  const Dense projected =
      AssembledPathHessian(f.space, f.path, HessianModel::kProjected);
  const Dense by_terms = ProjectedPathHessianByTerms(f.space, f.path);
  EXPECT_LE(RelativeDifference(projected, by_terms), 1e-11);
  // Twin: the exact Hessian is not that sum.
  const Dense exact =
      AssembledPathHessian(f.space, f.path, HessianModel::kExact);
  EXPECT_GT(RelativeDifference(exact, by_terms), 1e-3);
}

TEST(ProjectedPathHessianTest, IsPositiveSemidefiniteWhereTheExactIsNot) {
  const Fixture f;
  const Dense exact =
      AssembledPathHessian(f.space, f.path, HessianModel::kExact);
  const Dense projected =
      AssembledPathHessian(f.space, f.path, HessianModel::kProjected);
  EXPECT_GT(PsdViolation(exact), 1e-5);  // the twin: indefinite
  EXPECT_LE(PsdViolation(projected), 1e-12);
}

TEST(ProjectedPathHessianTest, EqualsTheExactHessianWhereTheTermsAreConvex) {
  const Fixture f;
  // Every shape the same, moved rigidly: each term at its minimum
  // (W = 0), its Hessian positive semidefinite.
  const std::vector<Positions> rest{
      f.pair.reference, testing::RandomRigidMotion(f.pair.reference, 1),
      testing::RandomRigidMotion(f.pair.reference, 2), f.pair.reference};
  const Dense exact = AssembledPathHessian(f.space, rest, HessianModel::kExact);
  const Dense projected =
      AssembledPathHessian(f.space, rest, HessianModel::kProjected);
  EXPECT_LE(RelativeDifference(projected, exact), 1e-12);
  // Twin: on the bumpy path they differ.
  EXPECT_GT(RelativeDifference(
                AssembledPathHessian(f.space, f.path, HessianModel::kProjected),
                AssembledPathHessian(f.space, f.path, HessianModel::kExact)),
            1e-3);
}

TEST(ProjectedElementHessianTest, OneSidedBlockIsProjectedMixedBlocksExact) {
  const Fixture f;
  int projected_somewhere = 0;
  f.space.elements().ForEachGroup([&](const auto& group) {
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    for (const auto& stencil : group.stencils) {
      double a[3 * kV], b[3 * kV];
      GatherCoordinates(f.pair.reference, stencil, a);
      GatherCoordinates(f.pair.deformed, stencil, b);
      ElementSecondDerivatives<kV> exact, projected;
      ASSERT_TRUE(exact.ComputeModel(HessianModel::kExact, group.element, a,
                                     b, ShellSide::kDeformed, 1.0));
      ASSERT_TRUE(projected.ComputeModel(HessianModel::kProjected,
                                         group.element, a, b,
                                         ShellSide::kDeformed, 1.0));
      EXPECT_LE(PsdViolation(Dense(projected.d_grad_deformed)), 1e-12);
      EXPECT_EQ(Dense(projected.d_grad_reference),
                Dense(exact.d_grad_reference));
      EXPECT_EQ(projected.grad_deformed, exact.grad_deformed);
      if (PsdViolation(Dense(exact.d_grad_deformed)) > 1e-6) {
        ++projected_somewhere;
      } else {
        EXPECT_EQ(Dense(projected.d_grad_deformed),
                  Dense(exact.d_grad_deformed));
      }
    }
  });
  EXPECT_GT(projected_somewhere, 0);  // the case is not trivial
}

}  // namespace
}  // namespace shellspace
