// Gradients and Hessians of W against central differences, on real meshes:
// D_1 W, D_2 W against differences of the energy; D_2^2 W, D_1^2 W and the
// mixed blocks against differences of the analytic gradients.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {


struct Pair {
  const char* reference;
  const char* deformed;
};

// W[reference, deformed] and its derivatives as functions of the flattened
// coordinates (vertex-major) of one side, the other side held.
struct SideFunctions {
  const ShellSpace& space;
  const Positions& reference;
  const Positions& deformed;

  Positions With(ShellSide side, const Eigen::VectorXd& x) const {
    Positions p = side == ShellSide::kReference ? reference : deformed;
    Eigen::Map<Eigen::VectorXd>(p.data(), p.size()) = x;
    return p;
  }
  Eigen::VectorXd Flat(ShellSide side) const {
    const Positions& p = side == ShellSide::kReference ? reference : deformed;
    return Eigen::Map<const Eigen::VectorXd>(p.data(), p.size());
  }
  // W as a 1-vector of the coordinates of `moved`.
  testing::VectorFunction Energy(ShellSide moved) const {
    return [this, moved](const Eigen::VectorXd& x) {
      const bool r = moved == ShellSide::kReference;
      return Eigen::VectorXd::Constant(
          1, EvaluateDeformationEnergy(space, r ? With(moved, x) : reference,
                                       r ? deformed : With(moved, x))
                 .total);
    };
  }
  // The gradient on side `rows` as a function of the coordinates of `moved`.
  testing::VectorFunction Gradient(ShellSide rows, ShellSide moved) const {
    return [this, rows, moved](const Eigen::VectorXd& x) {
      const bool r = moved == ShellSide::kReference;
      return EnergyGradient(space, r ? With(moved, x) : reference,
                            r ? deformed : With(moved, x), rows);
    };
  }
};

// The mesh pair of the parameter, its shell space and W on it.
class EnergyHessianTest : public ::testing::TestWithParam<Pair> {
 protected:
  const Mesh ref = testing::LoadData(GetParam().reference);
  const Mesh def = testing::LoadData(GetParam().deformed);
  const ShellSpace space = testing::MakeSpace(ref);
  const SideFunctions w{space, ref.positions, def.positions};
};

// Gradient columns g_j as 1-vectors.
testing::DerivativeColumn GradientColumns(const Eigen::VectorXd& g) {
  return [g](int j) { return Eigen::VectorXd::Constant(1, g(j)); };
}

TEST_P(EnergyHessianTest, GradientsMatchEnergyDifferences) {
  const std::vector<int> probes =
      testing::ProbeCoordinates(3 * ref.num_vertices(), 20, 3);
  for (ShellSide side : {ShellSide::kReference, ShellSide::kDeformed}) {
    const Eigen::VectorXd g =
        EnergyGradient(space, ref.positions, def.positions, side);
    // Relative to the largest gradient entry: |g_i - N_i| <= 1e-6 max |g|.
    const double scale = g.cwiseAbs().maxCoeff();
    EXPECT_LT(testing::CentralDifferenceError(w.Energy(side), w.Flat(side),
                                              GradientColumns(g), probes, 1e-6,
                                              scale),
              1e-6)
        << int(side);
    // Negative twin: one probed entry off by 1e-4 of the gradient's scale.
    EXPECT_GT(testing::CentralDifferenceError(
                  w.Energy(side), w.Flat(side),
                  testing::WrongInOneEntry(GradientColumns(g), 0, probes[0],
                                           1e-4 * scale),
                  probes, 1e-6, scale),
              1e-6)
        << int(side);
  }
}

TEST_P(EnergyHessianTest, HessiansMatchGradientDifferences) {
  const std::vector<int> probes =
      testing::ProbeCoordinates(3 * ref.num_vertices(), 8, 5);
  const ShellSide sides[] = {ShellSide::kReference, ShellSide::kDeformed};
  for (ShellSide rows : sides) {
    for (ShellSide cols : sides) {
      const SparseMatrix hessian =
          EnergyHessian(space, ref.positions, def.positions, rows, cols);
      const testing::DerivativeColumn columns = [&hessian](int j) {
        return Eigen::VectorXd(hessian.col(j));
      };
      // Relative to the largest entry of the block, as before the helper.
      const double scale = Eigen::MatrixXd(hessian).cwiseAbs().maxCoeff();
      EXPECT_LT(testing::CentralDifferenceError(w.Gradient(rows, cols),
                                                w.Flat(cols), columns, probes,
                                                1e-6, scale),
                1e-6)
          << int(rows) << int(cols);
      // Negative twin: the block with one entry of a probed column off by
      // 1e-4 of its scale.
      const double offset = 1e-4 * scale;
      const int row = hessian.col(probes[0]).nonZeros() > 0
                          ? SparseMatrix::InnerIterator(hessian, probes[0]).row()
                          : 0;
      EXPECT_GT(testing::CentralDifferenceError(
                    w.Gradient(rows, cols), w.Flat(cols),
                    testing::WrongInOneEntry(columns, row, probes[0], offset),
                    probes, 1e-6, scale),
                1e-6)
          << int(rows) << int(cols);
    }
  }
  // Symmetry of the pure blocks and transpose relation of the mixed ones.
  const SparseMatrix h22 =
      EnergyHessian(space, ref.positions, def.positions, ShellSide::kDeformed,
                    ShellSide::kDeformed);
  EXPECT_LT((Eigen::MatrixXd(h22) - Eigen::MatrixXd(h22.transpose())).norm(),
            1e-9 * h22.norm());
  const SparseMatrix h12 =
      EnergyHessian(space, ref.positions, def.positions, ShellSide::kReference,
                    ShellSide::kDeformed);
  const SparseMatrix h21 =
      EnergyHessian(space, ref.positions, def.positions, ShellSide::kDeformed,
                    ShellSide::kReference);
  EXPECT_LT((Eigen::MatrixXd(h12) - Eigen::MatrixXd(h21.transpose())).norm(),
            1e-9 * h12.norm());
}

// The directional derivative of a gradient is the Hessian block times the
// direction, for all four (gradient, moved) combinations.
TEST_P(EnergyHessianTest, GradientDerivativeIsHessianTimesDirection) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd p(3 * ref.num_vertices());
  for (int i = 0; i < p.size(); ++i) p(i) = u(rng);
  for (ShellSide gradient : {ShellSide::kReference, ShellSide::kDeformed}) {
    for (ShellSide moved : {ShellSide::kReference, ShellSide::kDeformed}) {
      const Eigen::VectorXd expected =
          EnergyHessian(space, ref.positions, def.positions, gradient, moved) *
          p;
      const Eigen::VectorXd actual = EnergyGradientDerivative(
          space, ref.positions, def.positions, gradient, moved, p);
      EXPECT_LT((actual - expected).norm(), 1e-12 * expected.norm())
          << int(gradient) << int(moved);
    }
  }
}

// At rest the Hessian D_2^2 W[s, s] annihilates the 6 rigid motions.
TEST(EnergyHessianRestTest, RigidNullSpaceAtRest) {
  const Mesh mesh = testing::LoadData("sphere/unitSphere1.ply");
  const ShellSpace space = testing::MakeSpace(mesh);
  const Eigen::MatrixXd h = Eigen::MatrixXd(
      EnergyHessian(space, mesh.positions, mesh.positions, ShellSide::kDeformed,
                    ShellSide::kDeformed));
  const int n = mesh.num_vertices();
  Eigen::VectorXd v(3 * n);
  for (int mode = 0; mode < 6; ++mode) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d x = mesh.vertex(i);
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      if (mode < 3)
        d(mode) = 1;
      else
        d = Eigen::Vector3d::Unit(mode - 3).cross(x);
      v.segment<3>(3 * i) = d;
    }
    EXPECT_LT((h * v).norm(), 1e-10 * h.norm() * v.norm()) << mode;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
  EXPECT_GT(eig.eigenvalues()(0), -1e-10 * eig.eigenvalues().maxCoeff());
  EXPECT_GT(eig.eigenvalues()(6), 1e-8 * eig.eigenvalues().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, EnergyHessianTest,
                         ::testing::Values(Pair{"simple/square4.ply",
                                                "simple/square4_bent.ply"},
                                           Pair{"sphere/unitSphere1.ply",
                                                "sphere/unitSphere1_defX.ply"},
                                           Pair{"plate/plate121.ply",
                                                "plate/plate121_rolledA.ply"}));

}  // namespace
}  // namespace shellspace
