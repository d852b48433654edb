// Pieces of the Newton stage of geodesic interpolation on procedural sheets
// and matrices built here: a path Hessian assembler reused for several
// paths gives a fresh one's Hessians bit for bit, the one-pass path
// gradient gives the one-sided digits, the space-time ordering keeps each
// vertex's slices together, the reusable Cholesky/CG solver factorises once
// for nearby matrices, ParallelFor runs every index once, and a solve in
// the space renumbered for locality is the caller's solve.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/shell_space_renumbering.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/problems/calculus/path_newton.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/space_time_ordering.h"
#include "tests/testing/shell_paths.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::PerturbedLinearPath;
using testing::RelativePathDistance;

// One assembler used for several paths (as a Newton solve uses it) gives
// the Hessians of a fresh assembler, bit for bit: for another path, for
// the first one again, and for the elastic-mean sum (whose diagonal blocks,
// like the path's, receive only the vertex pairs on and below the
// diagonal). Procedural: a sheet rolled onto a cylinder.
bool SameMatrix(const SparseMatrix& a, const SparseMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1,
                    b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(),
                    b.innerIndexPtr()) &&
         std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr());
}

// A 10 x 6 sheet (h = 0.15) and its shell space (eta = 0.01), for the
// procedural tests below; Path: a perturbed linear path of K steps to the
// sheet rolled onto a cylinder of `radius`.
struct RolledSheet {
  const Mesh sheet = MakeEquilateralSheet(10, 6, 0.15);
  const ShellSpace space{sheet, Topology::Build(sheet),
                         ShellMaterial{1, 1, 0.01}};
  ShellPath Path(double radius, int K, int seed) const {
    return PerturbedLinearPath(sheet.positions,
                               RollOntoCylinder(sheet.positions, radius), K,
                               1e-3, seed);
  }
};

TEST(PathHessianReuseTest, AReusedAssemblerGivesTheFreshHessians) {
  const RolledSheet rolled;
  const ShellSpace& space = rolled.space;
  const int K = 4;
  const ShellPath a = rolled.Path(0.8, K, 1), b = rolled.Path(1.3, K, 2);
  const std::vector<SparseMatrix> bases(
      K - 1, FreeVertexBasis(rolled.sheet.num_vertices(), {0, 1, 2}));
  const PathHessianAssembler kept(space);
  for (int threads : {1, 2}) {
    const SparseMatrix first = kept.Assemble(a, bases, threads);
    const SparseMatrix second = kept.Assemble(b, bases, threads);
    const SparseMatrix again = kept.Assemble(a, bases, threads);
    EXPECT_TRUE(SameMatrix(
        second, PathHessianAssembler(space).Assemble(b, bases, threads)));
    EXPECT_TRUE(SameMatrix(again, first));
    // The check tells the two paths' Hessians apart.
    EXPECT_FALSE(SameMatrix(second, first));
    const SparseMatrix sum =
        kept.AssembleDeformedSum({a[0], b[2]}, a[1], bases[0], threads);
    EXPECT_TRUE(SameMatrix(sum, PathHessianAssembler(space).AssembleDeformedSum(
                                    {a[0], b[2]}, a[1], bases[0], threads)));
  }
}

// The path gradient evaluates each term W[s_k, s_{k+1}] once for both of
// its shells (TryEnergyGradients); its G_k are those of
// TryInnerShapeGradient (two one-sided passes), bit for bit, and so are the
// one-pass gradients of one W against TryEnergyGradient side by side.
// Procedural: a rolled sheet.
TEST(PathGradientTest, OnePassPerTermGivesTheOneSidedDigits) {
  const RolledSheet rolled;
  const ShellSpace& space = rolled.space;
  const int K = 5;
  const ShellPath path = rolled.Path(0.9, K, 3);
  Eigen::VectorXd of_reference, of_deformed, reference_only, deformed_only;
  ASSERT_TRUE(
      TryEnergyGradients(space, path[1], path[2], &of_reference, &of_deformed));
  ASSERT_TRUE(TryEnergyGradient(space, path[1], path[2], ShellSide::kReference,
                                &reference_only));
  ASSERT_TRUE(TryEnergyGradient(space, path[1], path[2], ShellSide::kDeformed,
                                &deformed_only));
  EXPECT_EQ(of_reference, reference_only);
  EXPECT_EQ(of_deformed, deformed_only);
  std::vector<Eigen::VectorXd> fused(K - 1);
  for (int threads : {1, 2}) {
    ASSERT_TRUE(ForEachInnerShapeGradient(
        space, path, threads,
        [&](int i, const Eigen::VectorXd& g) { fused[i] = g; }));
    for (int k = 1; k < K; ++k) {
      Eigen::VectorXd separate;
      ASSERT_TRUE(TryInnerShapeGradient(space, path, k, &separate));
      EXPECT_EQ(fused[k - 1], separate) << k;
      // The comparison tells neighbouring shapes' gradients apart.
      if (k > 1) {
        EXPECT_NE(fused[k - 2], separate) << k;
      }
    }
  }
}

// A 1D Laplacian in time (3 slices) of 2D grid Laplacians, shifted to be SPD:
// the structure of a path Hessian.
SparseMatrix SpaceTimeLaplacian(int side, int slices, double shift,
                                std::vector<int>* vertex_of) {
  const int n = side * side;
  std::vector<Eigen::Triplet<double>> t;
  auto id = [&](int s, int x, int y) { return s * n + y * side + x; };
  for (int s = 0; s < slices; ++s) {
    for (int y = 0; y < side; ++y) {
      for (int x = 0; x < side; ++x) {
        const int i = id(s, x, y);
        vertex_of->push_back(y * side + x);
        t.emplace_back(i, i, 6.0 + shift * (1 + x % 3));
        if (x + 1 < side) t.emplace_back(id(s, x + 1, y), i, -1.0);
        if (y + 1 < side) t.emplace_back(id(s, x, y + 1), i, -1.0);
        if (s + 1 < slices) t.emplace_back(id(s + 1, x, y), i, -1.0);
      }
    }
  }
  SparseMatrix lower(slices * n, slices * n);
  lower.setFromTriplets(t.begin(), t.end());
  return lower;
}

TEST(SpaceTimeOrderingTest, PermutationKeepsEachVertexTogether) {
  std::vector<int> vertex_of;
  const SparseMatrix lower = SpaceTimeLaplacian(12, 3, 0.1, &vertex_of);
  const auto p = SpaceTimeOrdering(lower, vertex_of, 144);
  std::vector<int> seen(lower.rows(), 0);
  for (int i = 0; i < lower.rows(); ++i) ++seen[p.indices()[i]];
  for (int count : seen) ASSERT_EQ(count, 1);
  // The three slices of a vertex are adjacent in the new order.
  std::vector<int> first(144, 1 << 30), last(144, -1);
  for (int i = 0; i < lower.rows(); ++i) {
    first[vertex_of[i]] = std::min(first[vertex_of[i]], p.indices()[i]);
    last[vertex_of[i]] = std::max(last[vertex_of[i]], p.indices()[i]);
  }
  for (int v = 0; v < 144; ++v) EXPECT_EQ(last[v] - first[v], 2) << v;
}

TEST(ReusableCholeskyTest, FactorisesOnceThenReusesTheFactorForNearbyMatrices) {
  std::vector<int> vertex_of;
  const SparseMatrix h1 = SpaceTimeLaplacian(15, 4, 0.1, &vertex_of);
  const SparseMatrix h2 = SpaceTimeLaplacian(15, 4, 0.12, &vertex_of);
  const int n = static_cast<int>(h1.rows());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  ReusableCholesky solver;
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.Solve(h1, vertex_of, 225, b, 1e-10, &x));
  EXPECT_LT((h1.selfadjointView<Eigen::Lower>() * x - b).norm(),
            1e-10 * b.norm());
  EXPECT_EQ(solver.stats().factorizations, 1);
  ASSERT_TRUE(solver.Solve(h2, vertex_of, 225, b, 1e-8, &x));
  EXPECT_LT((h2.selfadjointView<Eigen::Lower>() * x - b).norm(),
            1e-8 * b.norm());
  EXPECT_EQ(solver.stats().factorizations, 1);  // CG on the old factor
  EXPECT_EQ(solver.stats().cg_solves, 1);
  EXPECT_GT(solver.stats().cg_iterations, 0);
  // Far away and with no CG budget: a new factorisation, still exact.
  const SparseMatrix h3 = SpaceTimeLaplacian(15, 4, 5.0, &vertex_of);
  solver.max_cg_iterations = 0;
  ASSERT_TRUE(solver.Solve(h3, vertex_of, 225, b, 1e-10, &x));
  EXPECT_LT((h3.selfadjointView<Eigen::Lower>() * x - b).norm(),
            1e-10 * b.norm());
  EXPECT_EQ(solver.stats().factorizations, 2);
}

TEST(ReusableCholeskyTest, IndefiniteMatrixIsReported) {
  std::vector<int> vertex_of;
  const SparseMatrix h = SpaceTimeLaplacian(6, 2, -5.0, &vertex_of);
  ReusableCholesky solver;
  Eigen::VectorXd x;
  EXPECT_FALSE(solver.Solve(h, vertex_of, 36, Eigen::VectorXd::Ones(h.rows()),
                            1e-8, &x));
}

TEST(ParallelForTest, RunsEveryIndexOnceAndRethrows) {
  std::vector<std::atomic<int>> hits(100);
  ParallelFor(100, 3, [&](int i) { ++hits[i]; });
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
  EXPECT_THROW(ParallelFor(50, 2,
                           [](int i) {
                             if (i == 7) throw InputError("element 7");
                           }),
               InputError);
}

// kAuto: the direct solver below kBlockJacobiFromUnknowns unknowns (the
// plate paths), block-Jacobi from it on; forced choices stay.
// A solve in the space renumbered for locality (RenumberForLocality) is the
// caller's solve to round-off: on an icosphere stretched into an ellipsoid
// (numbered at random; no mask, so the rigid gauge is pinned) three LM steps
// and a Newton finish in both numberings give the same path, mapped back --
// not only up to a rigid motion. The twin: without
// PathNewtonSettings::renumbering the renumbered solve picks its gauge
// vertices among the ellipsoid's tied farthest vertices in its own
// numbering, pins others, and its path lands elsewhere.
TEST(RenumberedSolveTest, IsTheCallersSolve) {
  // (With this random numbering the tie between the two ends of the long
  // axis goes to the other end than in the Cuthill-McKee numbering; so it
  // does for 6 of the seeds 1-12.)
  const Mesh sphere = testing::ShuffledNumbering(MakeIcosphere(2), 1);
  const ShellSpace space = testing::MakeSpace(sphere);
  Positions end = sphere.positions;
  end.col(0) *= 1.4;
  end.col(2) *= 0.8;
  const ShellPath start = LinearPath(sphere.positions, end, 4);
  const RenumberedShellSpace renumbered = RenumberForLocality(space);
  // LM, then Newton, from `path` (in the numbering of `in`).
  const auto solve = [](const ShellSpace& in, const RenumberedShellSpace* map,
                        ShellPath path) {
    PathNewtonSettings lm;
    lm.globalisation = NewtonSettings::Globalisation::kLevenbergMarquardt;
    lm.model = HessianModel::kGaussNewton;
    lm.linear_solver = PathLinearSolver::kDirect;
    lm.gradient_tolerance = 1e-12;
    lm.max_steps = 3;
    lm.renumbering = map;
    EXPECT_EQ(PolishPathNewton(in, {}, lm, &path).steps, 3);
    PathNewtonSettings newton;
    newton.globalisation = NewtonSettings::Globalisation::kTrustRegion;
    newton.model = HessianModel::kExact;
    newton.linear_solver = PathLinearSolver::kDirect;
    newton.gradient_tolerance = 1e-9;
    newton.renumbering = map;
    const PathNewtonReport report = PolishPathNewton(in, {}, newton, &path);
    EXPECT_TRUE(report.converged) << report.stop_reason;
    return path;
  };
  const auto to_renumbered = [&](const ShellPath& path) {
    ShellPath out;
    for (const Positions& shape : path) {
      out.push_back(renumbered.ToRenumbered(shape));
    }
    return out;
  };
  const auto to_original = [&](const ShellPath& path) {
    ShellPath out;
    for (const Positions& shape : path) {
      out.push_back(renumbered.ToOriginal(shape));
    }
    return out;
  };
  const ShellPath callers = solve(space, nullptr, start);
  const ShellPath mapped =
      to_original(solve(renumbered.space, &renumbered, to_renumbered(start)));
  EXPECT_LT(RelativePathDistance(mapped, callers), 1e-8);
  EXPECT_NEAR(PathEnergy(space, mapped), PathEnergy(space, callers),
              1e-12 * PathEnergy(space, callers));
  // Twin: the renumbered space without the map for its gauge.
  const ShellPath unmapped =
      to_original(solve(renumbered.space, nullptr, to_renumbered(start)));
  EXPECT_GT(RelativePathDistance(unmapped, callers), 1e-3);
}

}  // namespace
}  // namespace shellspace
