// Derivatives of the shape-operator bending model
// (cost_functions/shell/shape_operator_element.h) on random stencils with
// one, two and three interior edges: the Jacobians of its residuals (ceres
// GradientChecker, for every combination of variable reference / deformed
// arguments) and its gradients and Hessians (central differences, both
// sides); and the assembled W = W_mem + eta W_bend^SO's gradient and
// D_2^2 W on a bumpy sheet. Each check has a negative twin.
#include <gtest/gtest.h>

#include <ceres/problem.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <type_traits>
#include <vector>

#include "shellspace/cost_functions/shape_operator_bending_cost_function.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/element_cost_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::Mode;
using testing::ShapeOperatorMaterial;

// One stencil with kInterior interior edges: a face and the vertices across
// its edges, at random positions near a bent configuration.
template <int kInterior>
void RandomStencil(unsigned seed, std::vector<double>* ref,
                   std::vector<double>* def) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.15, 0.15);
  const double base[6][3] = {{0, 0, 0},      {1, 0, 0},     {0.4, 0.9, 0},
                             {1.2, 0.9, 0.3}, {-0.5, 0.6, -0.2},
                             {0.5, -0.8, 0.25}};
  ref->assign(3 * (3 + kInterior), 0);
  def->assign(3 * (3 + kInterior), 0);
  for (int v = 0; v < 3 + kInterior; ++v) {
    for (int c = 0; c < 3; ++c) {
      // Centred at (2, 2, 2): Ceres' steps are relative to |x|.
      (*ref)[3 * v + c] = 2 + base[v][c] + noise(rng);
      (*def)[3 * v + c] = 2 + 1.1 * base[v][c] + noise(rng) +
                          (c == 2 ? 0.2 * base[v][0] * base[v][1] : 0);
    }
  }
}

template <int kInterior>
void CheckJacobians() {
  constexpr int kV = 3 + kInterior;
  double worst = 0, twin_least = 1e300;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::vector<double> ref, def;
    RandomStencil<kInterior>(seed, &ref, &def);
    for (Mode mode :
         {Mode::kBothVariable, Mode::kReferenceFixed, Mode::kDeformedFixed}) {
      std::vector<double*> params;
      for (int v = 0; v < kV && mode != Mode::kReferenceFixed; ++v) {
        params.push_back(ref.data() + 3 * v);
      }
      for (int v = 0; v < kV && mode != Mode::kDeformedFixed; ++v) {
        params.push_back(def.data() + 3 * v);
      }
      auto make = [&] {
        return std::unique_ptr<ceres::CostFunction>(
            ShapeOperatorBendingCostFunction<kInterior>::Create(
                0.2, 0.3, 0.7,
                mode == Mode::kReferenceFixed ? ref.data() : nullptr,
                mode == Mode::kDeformedFixed ? def.data() : nullptr, 1.7));
      };
      const auto cost = make();
      ASSERT_EQ(cost->parameter_block_sizes().size(), params.size());
      if (kInterior == 0) {
        // No interior edge: H = Hbar = 0, residuals and Jacobians vanish.
        double r[3];
        std::vector<double> jac(params.size() * 9, 1.0);
        std::vector<double*> blocks(params.size());
        for (size_t b = 0; b < params.size(); ++b) blocks[b] = &jac[9 * b];
        ASSERT_TRUE(cost->Evaluate(params.data(), r, blocks.data()));
        EXPECT_EQ(r[0] * r[0] + r[1] * r[1] + r[2] * r[2], 0.0);
        for (double j : jac) EXPECT_EQ(j, 0.0);
        continue;
      }
      const double error = testing::CostFunctionJacobianError(*cost, params);
      EXPECT_LT(error, 1e-7) << "interior edges " << kInterior << " seed "
                             << seed << " mode " << int(mode);
      // Negative twin: one entry of the last block (a P vertex if any)
      // off by 1e-4 is caught by the same helper.
      const int block = static_cast<int>(params.size()) - 1;
      testing::CostFunctionWithWrongJacobian wrong(make(), block, 4, 1e-4);
      const double twin = testing::CostFunctionJacobianError(wrong, params);
      EXPECT_GT(twin, 1e-6);
      worst = std::max(worst, error);
      twin_least = std::min(twin_least, twin);
    }
  }
  if (kInterior > 0) std::printf("%d interior edges: largest Jacobian error %.2e, smallest "
              "negative-twin error %.2e\n",
              kInterior, worst, twin_least);
}

TEST(ShapeOperatorTest, JacobiansMatchGradientCheckerWithNegativeTwin) {
  CheckJacobians<0>();
  CheckJacobians<1>();
  CheckJacobians<2>();
  CheckJacobians<3>();
}

// Gradients of the closed-form energy and Hessians (dual numbers over the
// analytic gradient J^T r) against central differences, both sides.
template <int kInterior>
void CheckSecondDerivatives() {
  constexpr int kV = 3 + kInterior, n = 3 * kV;
  ShapeOperatorElement<kInterior> element;
  element.eta = 1;
  element.alpha = 0.3;
  element.beta = 0.7;
  const double weight = 0.4;
  std::vector<double> ref, def;
  RandomStencil<kInterior>(11, &ref, &def);
  for (ShellSide side : {ShellSide::kDeformed, ShellSide::kReference}) {
    const bool active_ref = side == ShellSide::kReference;
    const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(
        active_ref ? ref.data() : def.data(), n);
    auto at = [&](const Eigen::VectorXd& x, std::vector<double>* r,
                  std::vector<double>* d) {
      *r = ref;
      *d = def;
      std::copy(x.data(), x.data() + n, active_ref ? r->data() : d->data());
    };
    // Energy and its gradient on the active side.
    const testing::VectorFunction energy = [&](const Eigen::VectorXd& x) {
      std::vector<double> r, d;
      at(x, &r, &d);
      Vec3<double> rv[kV], dv[kV];
      for (int v = 0; v < kV; ++v) {
        rv[v] = Vec3<double>(r.data() + 3 * v);
        dv[v] = Vec3<double>(d.data() + 3 * v);
      }
      double e = 0;
      EXPECT_TRUE(element.Energy(rv, dv, &e));
      return Eigen::VectorXd::Constant(1, weight * e);
    };
    auto derivatives = [&](const Eigen::VectorXd& x) {
      std::vector<double> r, d;
      at(x, &r, &d);
      ElementSecondDerivatives<kV> out;
      EXPECT_TRUE(out.Compute(element, r.data(), d.data(), side, weight));
      return out;
    };
    const ElementSecondDerivatives<kV> d0 = derivatives(x0);
    const Eigen::VectorXd gradient =
        active_ref ? Eigen::VectorXd(d0.grad_reference)
                   : Eigen::VectorXd(d0.grad_deformed);
    std::vector<int> all(n);
    for (int j = 0; j < n; ++j) all[j] = j;
    const testing::DerivativeColumn grad_column = [&](int j) {
      return Eigen::VectorXd::Constant(1, gradient(j));
    };
    if (kInterior == 0) {
      // A face without interior edges has H = Hbar = 0: e = 0 identically.
      EXPECT_LT(
          testing::CentralDifferenceError(energy, x0, grad_column, all, 1e-6),
          1e-7);
      EXPECT_EQ(gradient.norm(), 0.0);
      EXPECT_EQ(d0.d_grad_reference.norm() + d0.d_grad_deformed.norm(), 0.0);
      continue;
    }
    const testing::ErrorAndTwin g = testing::CentralDifferenceErrorAndTwin(
        energy, x0, grad_column, all, 1e-6, {0, 2, 1e-4 * gradient.norm()});
    EXPECT_LT(g.error, 1e-7);
    EXPECT_GT(g.twin_error, 1e-6);
    // The gradient on the reference side (rows_ref) or the deformed side as
    // a function of the active side's coordinates, and its derivative by
    // them at x0: the block d_grad_reference or d_grad_deformed of d0.
    auto gradient_of = [&](bool rows_ref) -> testing::VectorFunction {
      return [&derivatives, rows_ref](const Eigen::VectorXd& x) {
        const ElementSecondDerivatives<kV> d = derivatives(x);
        return rows_ref ? Eigen::VectorXd(d.grad_reference)
                        : Eigen::VectorXd(d.grad_deformed);
      };
    };
    auto derivative_block = [&](bool rows_ref) {
      return rows_ref ? Eigen::MatrixXd(d0.d_grad_reference)
                      : Eigen::MatrixXd(d0.d_grad_deformed);
    };
    auto columns =
        [](const Eigen::MatrixXd& block) -> testing::DerivativeColumn {
      return [&block](int j) { return Eigen::VectorXd(block.col(j)); };
    };
    // Hessian: f = the active side's gradient, columns of d_grad.
    const testing::VectorFunction grad_fn = gradient_of(active_ref);
    const Eigen::MatrixXd hessian = derivative_block(active_ref);
    const testing::ErrorAndTwin h = testing::CentralDifferenceErrorAndTwin(
        grad_fn, x0, columns(hessian), all, 1e-5,
        {1, 3, 1e-3 * hessian.norm()});
    EXPECT_LT(h.error, 1e-6) << "interior edges " << kInterior;
    EXPECT_GT(h.twin_error, 1e-5);
    std::printf("%d interior edges, %s side: Hessian error %.2e\n", kInterior,
                active_ref ? "reference" : "deformed", h.error);
    // The mixed block (rows the other side's gradient, columns active).
    const testing::VectorFunction other_grad = gradient_of(!active_ref);
    const Eigen::MatrixXd mixed = derivative_block(!active_ref);
    const testing::ErrorAndTwin m = testing::CentralDifferenceErrorAndTwin(
        other_grad, x0, columns(mixed), all, 1e-5, {2, 4, 1e-3 * mixed.norm()});
    EXPECT_LT(m.error, 1e-6);
    EXPECT_GT(m.twin_error, 1e-5) << "interior edges " << kInterior;
  }
}

TEST(ShapeOperatorTest, GradientsAndHessiansMatchCentralDifferences) {
  CheckSecondDerivatives<0>();
  CheckSecondDerivatives<1>();
  CheckSecondDerivatives<2>();
  CheckSecondDerivatives<3>();
}

// The assembled W = W_mem + eta W_bend^SO: its gradient and D_2^2 W against
// central differences (the shape-operator groups go through the generic
// evaluators of energy_derivatives.h).
TEST(ShapeOperatorTest, AssembledGradientAndHessianOfW) {
  const testing::BumpySheetPair s = testing::MakeBumpySheetPair();
  const ShellSpace space =
      testing::MakeSpace(s.mesh, ShapeOperatorMaterial(0.5, 0.3, 0.7));
  const int n = 3 * s.mesh.num_vertices();
  const Eigen::VectorXd x0 =
      Eigen::Map<const Eigen::VectorXd>(Positions(s.deformed).data(), n);
  auto shape = [&](const Eigen::VectorXd& x) {
    Positions p(s.mesh.num_vertices(), 3);
    Eigen::Map<Eigen::VectorXd>(p.data(), n) = x;
    return p;
  };
  const testing::VectorFunction total = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd::Constant(
        1, EvaluateDeformationEnergy(space, s.reference, shape(x)).total);
  };
  const Eigen::VectorXd g =
      EnergyGradient(space, s.reference, s.deformed, ShellSide::kDeformed);
  const std::vector<int> probes = testing::ProbeCoordinates(n, 20, 5);
  const testing::DerivativeColumn g_column = [&](int j) {
    return Eigen::VectorXd::Constant(1, g(j));
  };
  EXPECT_LT(testing::CentralDifferenceError(total, x0, g_column, probes, 1e-6),
            1e-7);
  const SparseMatrix h = EnergyHessian(space, s.reference, s.deformed,
                                       ShellSide::kDeformed, ShellSide::kDeformed);
  const testing::VectorFunction grad = [&](const Eigen::VectorXd& x) {
    return EnergyGradient(space, s.reference, shape(x), ShellSide::kDeformed);
  };
  const testing::DerivativeColumn h_column = [&](int j) {
    return Eigen::VectorXd(h.col(j));
  };
  EXPECT_LT(testing::CentralDifferenceError(grad, x0, h_column, probes, 1e-5),
            1e-6);
  EXPECT_GT(testing::CentralDifferenceError(
                grad, x0, testing::WrongInOneEntry(h_column, probes[0], probes[0], 1e-2),
                probes, 1e-5),
            1e-5);
}

}  // namespace
}  // namespace shellspace
