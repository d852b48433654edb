// The directly assembled path Hessian (PathHessianAssembler) on the shared
// plate, sphere and finger pairs: against the independently tested blocks
// of EnergyHessian with a mask and with a rigid gauge, against central
// differences of the path gradient (with its negative twin), its deformed
// sums and mixed blocks; a collapsed triangle is an InputError of Assemble
// and a status of TryAssemble that names the lowest failing term's first
// degenerate element.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/shell_paths.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::PerturbedLinearPath;

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

}  // namespace
}  // namespace shellspace
