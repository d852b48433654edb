// The Newton stage of geodesic interpolation: the directly assembled path
// Hessian against the independently tested blocks of EnergyHessian, the
// space-time ordering, the reusable Cholesky/CG solver, ParallelFor, and
// Newton-polished geodesics against pure Levenberg-Marquardt ones.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <atomic>
#include <random>
#include <stdexcept>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/shell_space_renumbering.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/space_time_ordering.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// Linear interpolation with a random perturbation of the inner
// shapes (so no block vanishes by symmetry).
ShellPath PerturbedLinearPath(const Positions& a, const Positions& b, int K,
                              double amplitude, unsigned seed) {
  ShellPath path = LinearPath(a, b, K);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (int k = 1; k < K; ++k) {
    for (int i = 0; i < path[k].size(); ++i) path[k].data()[i] += u(rng);
  }
  return path;
}

// T^T H T from EnergyHessian blocks (the reference the assembler must match).
SparseMatrix ReferenceReducedHessian(const ShellSpace& space,
                                     const ShellPath& path,
                                     const std::vector<SparseMatrix>& bases) {
  const int K = static_cast<int>(path.size()) - 1;
  std::vector<int> offset(K, 0);
  for (int i = 0; i + 1 < K; ++i) offset[i + 1] = offset[i] + bases[i].cols();
  const int size = offset[K - 1];
  std::vector<Eigen::Triplet<double>> t;
  auto add = [&](const SparseMatrix& block, int row0, int col0) {
    for (int c = 0; c < block.outerSize(); ++c) {
      for (SparseMatrix::InnerIterator it(block, c); it; ++it) {
        if (row0 + it.row() >= col0 + it.col()) {
          t.emplace_back(row0 + it.row(), col0 + it.col(), it.value());
        }
      }
    }
  };
  for (int k = 1; k < K; ++k) {  // inner shape s_k, slice k - 1
    const SparseMatrix& tk = bases[k - 1];
    const SparseMatrix d22 =
        EnergyHessian(space, path[k - 1], path[k], ShellSide::kDeformed,
                      ShellSide::kDeformed);
    const SparseMatrix d11 =
        EnergyHessian(space, path[k], path[k + 1], ShellSide::kReference,
                      ShellSide::kReference);
    add(SparseMatrix(double(K) * tk.transpose() * (d22 + d11) * tk),
        offset[k - 1], offset[k - 1]);
    if (k + 1 < K) {  // rows s_{k+1}, columns s_k
      const SparseMatrix mixed =
          EnergyHessian(space, path[k], path[k + 1], ShellSide::kDeformed,
                        ShellSide::kReference);
      add(SparseMatrix(double(K) * bases[k].transpose() * mixed * tk),
          offset[k], offset[k - 1]);
    }
  }
  SparseMatrix h(size, size);
  h.setFromTriplets(t.begin(), t.end());
  return h;
}

double RelativeDifference(const SparseMatrix& a, const SparseMatrix& b) {
  return SparseMatrix(a - b).norm() / b.norm();
}

TEST(PathHessianAssemblerTest, MatchesEnergyHessianBlocksWithMask) {
  ShellMaterial material;
  material.eta = 0.001;
  const auto [a, b, space] =
      testing::LoadPair("finger/finger0.ply", "finger/finger1.ply", material);
  const auto mask =
      ReadMask(testing::DataPath("finger/finger_mask.txt"), a.num_vertices());
  const int K = 4;
  const ShellPath path =
      PerturbedLinearPath(a.positions, b.positions, K, 1e-3, 1);
  const std::vector<SparseMatrix> bases(
      K - 1, FreeVertexBasis(a.num_vertices(), mask));
  const SparseMatrix reference = ReferenceReducedHessian(space, path, bases);
  for (int threads : {1, 2}) {
    const SparseMatrix h =
        PathHessianAssembler(space).Assemble(path, bases, threads);
    ASSERT_EQ(h.rows(), 3 * (K - 1) * (a.num_vertices() - int(mask.size())));
    EXPECT_LT(RelativeDifference(h, reference), 1e-13) << threads;
    // Only the lower triangle, with sorted rows.
    for (int c = 0; c < h.outerSize(); ++c) {
      int previous = -1;
      for (SparseMatrix::InnerIterator it(h, c); it; ++it) {
        ASSERT_GE(it.row(), c);
        ASSERT_GT(it.row(), previous);
        previous = it.row();
      }
    }
  }
}

// The assembled path Hessian against central differences of the path
// gradient G_k = K (D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}]) in the free
// coordinates of a mask (independent of EnergyHessian), and its negative
// twin through the same helper.
TEST(PathHessianAssemblerTest, MatchesCentralDifferencesOfThePathGradient) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  const int n = a.num_vertices();
  const std::vector<int> mask = {0, 1, 2, 3, 4};
  const int K = 4;
  const ShellPath path =
      PerturbedLinearPath(a.positions, b.positions, K, 1e-2, 4);
  const SparseMatrix basis = FreeVertexBasis(n, mask);
  const std::vector<SparseMatrix> bases(K - 1, basis);
  const int m = static_cast<int>(basis.cols());
  // x: the free coordinates of s_1 .. s_{K-1}, slice after slice.
  Eigen::VectorXd x(m * (K - 1));
  for (int k = 1; k < K; ++k) {
    x.segment((k - 1) * m, m) =
        basis.transpose() *
        Eigen::Map<const Eigen::VectorXd>(path[k].data(), path[k].size());
  }
  const testing::VectorFunction gradient = [&](const Eigen::VectorXd& q) {
    ShellPath moved = path;
    for (int k = 1; k < K; ++k) {
      Eigen::Map<Eigen::VectorXd> flat(moved[k].data(), moved[k].size());
      flat += basis * (q.segment((k - 1) * m, m) - x.segment((k - 1) * m, m));
    }
    Eigen::VectorXd g(q.size());
    for (int k = 1; k < K; ++k) {
      g.segment((k - 1) * m, m) =
          double(K) * basis.transpose() *
          testing::InteriorPathGradient(space, moved, k);
    }
    return g;
  };
  const SparseMatrix lower =
      PathHessianAssembler(space).Assemble(path, bases, 2);
  const SparseMatrix h = lower.selfadjointView<Eigen::Lower>();
  const testing::DerivativeColumn columns = [&h](int j) {
    return Eigen::VectorXd(h.col(j));
  };
  // Probes in every slice.
  std::vector<int> probes;
  for (int k = 0; k < K - 1; ++k) {
    for (int j : testing::ProbeCoordinates(m, 3, 10 + k))
      probes.push_back(k * m + j);
  }
  EXPECT_LT(testing::CentralDifferenceError(gradient, x, columns, probes, 1e-6),
            1e-6);
  // A wrong coupling block between slices is caught: entry of slice 2's rows
  // in a probed column of slice 1.
  const int col = probes[0];
  const double offset =
      1e-4 * Eigen::VectorXd(h.col(col)).cwiseAbs().maxCoeff();
  EXPECT_GT(
      testing::CentralDifferenceError(
          gradient, x, testing::WrongInOneEntry(columns, m + col, col, offset),
          probes, 1e-6),
      1e-6);
}

TEST(PathHessianAssemblerTest, MatchesEnergyHessianBlocksWithRigidGauge) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  const int K = 5;
  const ShellPath path =
      PerturbedLinearPath(a.positions, b.positions, K, 1e-2, 2);
  std::vector<SparseMatrix> bases;
  for (int k = 1; k < K; ++k) bases.push_back(RigidGaugeBasis(path[k]));
  const SparseMatrix h = PathHessianAssembler(space).Assemble(path, bases, 2);
  EXPECT_LT(RelativeDifference(h, ReferenceReducedHessian(space, path, bases)),
            1e-13);
  // Translating one inner shape changes no W: in full coordinates that is
  // a null vector of H, at any path.
  const std::vector<SparseMatrix> full(K - 1,
                                       FreeVertexBasis(a.num_vertices(), {}));
  const SparseMatrix h_full =
      PathHessianAssembler(space).Assemble(path, full, 2);
  const int n3 = 3 * a.num_vertices();
  Eigen::VectorXd translation = Eigen::VectorXd::Zero(h_full.rows());
  for (int v = 0; v < a.num_vertices(); ++v) {
    translation.segment<3>(n3 + 3 * v) = Eigen::Vector3d(0.3, -0.5, 0.8);
  }
  const Eigen::VectorXd image =
      h_full.selfadjointView<Eigen::Lower>() * translation;
  EXPECT_LT(image.norm(),
            1e-10 * SparseMatrix(h_full).norm() * translation.norm());
  // At rest (a constant path) the gauge-reduced Hessian is positive
  // definite: the gauge removes exactly the rigid null space.
  const ShellPath rest = LinearPath(a.positions, a.positions, K);
  std::vector<SparseMatrix> rest_bases;
  for (int k = 1; k < K; ++k) rest_bases.push_back(RigidGaugeBasis(rest[k]));
  const SparseMatrix h_rest =
      PathHessianAssembler(space).Assemble(rest, rest_bases, 2);
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> llt(h_rest);
  EXPECT_EQ(llt.info(), Eigen::Success);
}

TEST(PathHessianAssemblerTest, DeformedSumMatchesEnergyHessians) {
  std::vector<Positions> references;
  for (const char* name :
       {"sphere/unitSphere1_defX.ply", "sphere/unitSphere1_defY.ply",
        "sphere/unitSphere1_defZ.ply"}) {
    references.push_back(testing::LoadData(name).positions);
  }
  const Mesh s = testing::LoadData("sphere/unitSphere1.ply");
  const ShellSpace space = testing::MakeSpace(s);
  const SparseMatrix basis = RigidGaugeBasis(s.positions);
  SparseMatrix sum(3 * s.num_vertices(), 3 * s.num_vertices());
  for (const Positions& r : references) {
    sum += EnergyHessian(space, r, s.positions, ShellSide::kDeformed,
                         ShellSide::kDeformed);
  }
  const SparseMatrix reduced(basis.transpose() * sum * basis);
  const SparseMatrix expected = reduced.triangularView<Eigen::Lower>();
  for (int threads : {1, 2, 5}) {
    const SparseMatrix h = PathHessianAssembler(space).AssembleDeformedSum(
        references, s.positions, basis, threads);
    EXPECT_LT(RelativeDifference(h, expected), 1e-13) << threads;
  }
}

TEST(PathHessianAssemblerTest, MixedBlocksMatchEnergyHessians) {
  // The EXP Jacobians: R^T (D_1 D_2 W) C and R^T (D_1 D_2 W)^T C, with
  // different row and column bases (rigid gauges of the two shells, a
  // Dirichlet mask), against EnergyHessian's mixed blocks.
  const Mesh a = testing::LoadData("sphere/unitSphere1.ply");
  const Positions b =
      testing::LoadData("sphere/unitSphere1_defX.ply").positions;
  const ShellSpace space = testing::MakeSpace(a);
  const PathHessianAssembler assembler(space);
  const SparseMatrix mixed = EnergyHessian(
      space, a.positions, b, ShellSide::kReference, ShellSide::kDeformed);
  const SparseMatrix mixed_t = EnergyHessian(
      space, a.positions, b, ShellSide::kDeformed, ShellSide::kReference);
  const SparseMatrix ra = RigidGaugeBasis(a.positions);
  const SparseMatrix rb = RigidGaugeBasis(b);
  const SparseMatrix mask = FreeVertexBasis(a.num_vertices(), {0, 5, 9});
  EXPECT_LT(
      RelativeDifference(assembler.AssembleMixed(a.positions, b,
                                                 ShellSide::kReference, ra, rb),
                         SparseMatrix(ra.transpose() * mixed * rb)),
      1e-13);
  EXPECT_LT(
      RelativeDifference(
          assembler.AssembleMixed(a.positions, b, ShellSide::kDeformed, rb, ra),
          SparseMatrix(rb.transpose() * mixed_t * ra)),
      1e-13);
  EXPECT_LT(
      RelativeDifference(assembler.AssembleMixed(
                             a.positions, b, ShellSide::kReference, mask, mask),
                         SparseMatrix(mask.transpose() * mixed * mask)),
      1e-13);
}

// A constant path (K = 3) on `a` whose s_1 has triangle 0 collapsed to a
// point.
ShellPath CollapsedFirstTrianglePath(const Mesh& a) {
  ShellPath path = LinearPath(a.positions, a.positions, 3);
  const int v0 = a.faces(0, 0), v1 = a.faces(0, 1), v2 = a.faces(0, 2);
  path[1].row(v1) = path[1].row(v0);
  path[1].row(v2) = path[1].row(v0);
  return path;
}

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

TEST(PathHessianAssemblerTest, DegenerateTriangleThrowsInputError) {
  const Mesh a = testing::LoadData("plate/plate121.ply");
  const ShellSpace space = testing::MakeSpace(a);
  const ShellPath path = CollapsedFirstTrianglePath(a);
  const std::vector<SparseMatrix> bases(2, RigidGaugeBasis(a.positions));
  EXPECT_THROW(PathHessianAssembler(space).Assemble(path, bases, 2),
               InputError);
}

// The non-throwing twin: a status naming the element of the first step that
// contains the collapsed triangle (s_1 is the deformed shell of W[s_0, s_1]),
// and no exception.
TEST(PathHessianAssemblerTest, DegenerateTriangleIsAStatusOfTryAssemble) {
  const Mesh a = testing::LoadData("plate/plate121.ply");
  const ShellSpace space = testing::MakeSpace(a);
  const ShellPath path = CollapsedFirstTrianglePath(a);
  const std::vector<SparseMatrix> bases(2, RigidGaugeBasis(a.positions));
  const PathHessianAssembler assembler(space);
  SparseMatrix h;
  ElementFailure failure;
  bool ok = true;
  EXPECT_NO_THROW(ok = assembler.TryAssemble(path, bases, 2, &h, &failure));
  EXPECT_FALSE(ok);
  EXPECT_EQ(failure.element, 0);
  EXPECT_EQ(failure.description.rfind("W[s_0, s_1]: membrane element of "
                                      "triangle 0 ",
                                      0),
            0u)
      << failure.description;
  // The valid path assembles to the same matrix as Assemble.
  const ShellPath good = LinearPath(a.positions, a.positions, 3);
  ASSERT_TRUE(assembler.TryAssemble(good, bases, 2, &h));
  EXPECT_EQ(RelativeDifference(h, assembler.Assemble(good, bases, 2)), 0.0);
}

// Each inner shape's task sees two terms: W[s_{k-1}, s_k] (its deformed
// side) and W[s_k, s_{k+1}] (its reference side). The status names the
// first degenerate element of the lowest failing term, whichever side finds
// it. Collapsing a triangle degenerates it and its edge neighbours: the
// first of them is the one named. A triangle collapsed in s_1 near the end
// of the face list (term 0: found by slice 1's deformed side, which must go
// on past its reference side's failure at face 0, collapsed in s_2), and a
// triangle collapsed in the end shape s_3 (term 2: only slice 2's
// reference side sees it).
TEST(PathHessianAssemblerTest,
     StatusNamesTheLowestTermsFirstDegenerateElement) {
  const Mesh a = testing::LoadData("plate/plate121.ply");
  const ShellSpace space = testing::MakeSpace(a);
  const std::vector<SparseMatrix> bases(2, RigidGaugeBasis(a.positions));
  const PathHessianAssembler assembler(space);
  const auto collapse = [&](ShellPath* path, int shape, int face) {
    const int v0 = a.faces(face, 0);
    (*path)[shape].row(a.faces(face, 1)) = (*path)[shape].row(v0);
    (*path)[shape].row(a.faces(face, 2)) = (*path)[shape].row(v0);
  };
  // The first face with two vertices of `face` (itself or a neighbour).
  const auto first_degenerate = [&](int face) {
    for (int f = 0; f < a.faces.rows(); ++f) {
      int shared = 0;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) shared += a.faces(f, i) == a.faces(face, j);
      }
      if (shared >= 2) return f;
    }
    return -1;
  };
  const auto status = [&](const ShellPath& path) {
    SparseMatrix h;
    ElementFailure failure;
    EXPECT_FALSE(assembler.TryAssemble(path, bases, 1, &h, &failure));
    return failure.description;
  };
  const auto names = [](const std::string& description, int term, int face) {
    return description.rfind("W[s_" + std::to_string(term) + ", s_" +
                                 std::to_string(term + 1) +
                                 "]: membrane element of triangle " +
                                 std::to_string(face) + " ",
                             0) == 0;
  };
  const int late = static_cast<int>(a.faces.rows()) - 1;
  ASSERT_GT(first_degenerate(late), 0);
  ShellPath two = LinearPath(a.positions, a.positions, 3);
  collapse(&two, 2, 0);
  collapse(&two, 1, late);
  EXPECT_TRUE(names(status(two), 0, first_degenerate(late))) << status(two);
  ShellPath last = LinearPath(a.positions, a.positions, 3);
  collapse(&last, 3, late);
  EXPECT_EQ(status(last).rfind("W[s_2, s_3]: ", 0), 0u) << status(last);
  // Twin: without s_1's collapse the lowest failing term is W[s_1, s_2] at
  // face 0, so the check tells the terms and the faces apart.
  ShellPath one = LinearPath(a.positions, a.positions, 3);
  collapse(&one, 2, 0);
  EXPECT_TRUE(names(status(one), 1, 0)) << status(one);
  EXPECT_FALSE(names(status(one), 0, first_degenerate(late)));
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

// max_k |a_k - b_k| / max_k |b_k| (Frobenius norms of the shapes).
double RelativePathDistance(const ShellPath& a, const ShellPath& b) {
  double distance = 0, size = 0;
  for (size_t k = 0; k < b.size(); ++k) {
    distance = std::max(distance, (a[k] - b[k]).norm());
    size = std::max(size, b[k].norm());
  }
  return distance / size;
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
