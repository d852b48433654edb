// Gradients and Hessians of W against central differences, on real meshes:
// D_1 W, D_2 W against differences of the energy; D_2^2 W, D_1^2 W and the
// mixed blocks against differences of the analytic gradients.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/tests/testing/test_support.h"

namespace shellspace {
namespace {

Positions Perturb(const Positions& p, int index, double h) {
  Positions q = p;
  q(index / 3, index % 3) += h;
  return q;
}

struct Pair {
  const char* reference;
  const char* deformed;
};

class EnergyHessianTest : public ::testing::TestWithParam<Pair> {};

TEST_P(EnergyHessianTest, GradientsMatchEnergyDifferences) {
  const Mesh ref = testing::LoadData(GetParam().reference);
  const Mesh def = testing::LoadData(GetParam().deformed);
  const ShellSpace space = testing::MakeSpace(ref);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, 3 * ref.num_vertices() - 1);
  for (ShellSide side : {ShellSide::kReference, ShellSide::kDeformed}) {
    const Eigen::VectorXd g =
        EnergyGradient(space, ref.positions, def.positions, side);
    const double scale = g.cwiseAbs().maxCoeff();
    for (int trial = 0; trial < 20; ++trial) {
      const int i = pick(rng);
      const double h = 1e-6;
      auto energy = [&](double step) {
        const bool r = side == ShellSide::kReference;
        return EvaluateDeformationEnergy(
                   space, r ? Perturb(ref.positions, i, step) : ref.positions,
                   r ? def.positions : Perturb(def.positions, i, step))
            .total;
      };
      const double numeric = (energy(h) - energy(-h)) / (2 * h);
      EXPECT_NEAR(g(i), numeric, 1e-6 * scale) << i;
    }
  }
}

TEST_P(EnergyHessianTest, HessiansMatchGradientDifferences) {
  const Mesh ref = testing::LoadData(GetParam().reference);
  const Mesh def = testing::LoadData(GetParam().deformed);
  const ShellSpace space = testing::MakeSpace(ref);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> pick(0, 3 * ref.num_vertices() - 1);
  const ShellSide sides[] = {ShellSide::kReference, ShellSide::kDeformed};
  for (ShellSide rows : sides) {
    for (ShellSide cols : sides) {
      const Eigen::MatrixXd hessian = Eigen::MatrixXd(
          EnergyHessian(space, ref.positions, def.positions, rows, cols));
      const double scale = hessian.cwiseAbs().maxCoeff();
      double worst = 0;
      for (int trial = 0; trial < 8; ++trial) {
        const int j = pick(rng);
        const double h = 1e-6;
        auto gradient = [&](double step) {
          const bool r = cols == ShellSide::kReference;
          return EnergyGradient(
              space, r ? Perturb(ref.positions, j, step) : ref.positions,
              r ? def.positions : Perturb(def.positions, j, step), rows);
        };
        const Eigen::VectorXd numeric = (gradient(h) - gradient(-h)) / (2 * h);
        worst = std::max(
            worst, (hessian.col(j) - numeric).cwiseAbs().maxCoeff() / scale);
      }
      EXPECT_LT(worst, 1e-6) << int(rows) << int(cols);
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
  const Mesh ref = testing::LoadData(GetParam().reference);
  const Mesh def = testing::LoadData(GetParam().deformed);
  const ShellSpace space = testing::MakeSpace(ref);
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
