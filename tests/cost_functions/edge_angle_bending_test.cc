// The edge-angle variant of the shape-operator bending energy (docs/math.md,
// "Bending energy: two models"; geometry/edge_angle_second_form.h,
// cost_functions/edge_angle_bending_cost_function.h, edge_angle_bending.h): at
// phi = 0 it is the plain shape-operator energy of the element set; the cost
// function's Jacobian against GradientChecker with a negative twin; the fitted
// angles are a stationary point (central differences of the total, independent
// of Ceres) and a minimum; zero at rest and rigid invariance; and on jittered
// icospheres the curvature functional converges at second order where the plain
// model does not converge (meshes generated here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "shellspace/cost_functions/edge_angle_bending.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The bumpy sheet pair of the shape-operator tests, with its topology.
struct TestShells : testing::BumpySheetPair {
  Topology topology;
};
TestShells MakeTestShells() {
  TestShells s{testing::MakeBumpySheetPair(), {}};
  s.topology = Topology::Build(s.mesh);
  return s;
}

// The total sum_T e_T(phi) of `shape` against `reference`.
double Total(const std::vector<EdgeAngleFace>& shape,
             const std::vector<EdgeAngleReferenceFace>& reference,
             const std::vector<double>& angles, double alpha, double beta) {
  double sum = 0;
  for (size_t f = 0; f < shape.size(); ++f) {
    const EdgeAngleBendingCostFunction cost(shape[f], reference[f], alpha, beta);
    double phi[3], r[3];
    FaceEdgeAngles(shape[f], angles, phi);
    cost.Residuals(phi, r);
    sum += 0.5 * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  }
  return sum;
}

TEST(EdgeAngleBendingTest, AtZeroAnglesIsThePlainShapeOperatorEnergy) {
  // Independent: the element set's shape-operator bending (mid-edge normals
  // as dot products, no angles) against the angle form at phi = 0, with the
  // reference's unrotated second forms as targets.
  const TestShells s = MakeTestShells();
  for (const auto& [alpha, beta] : {std::pair{0.0, 1.0}, std::pair{0.3, 0.7}}) {
    const double plain =
        EvaluateDeformationEnergy(
            testing::MakeSpace(s.mesh, testing::ShapeOperatorMaterial(1, alpha, beta)),
            s.reference, s.deformed)
            .bending;
    ASSERT_GT(plain, 1e-2);
    const int edges = static_cast<int>(s.topology.interior_edges.size());
    const std::vector<double> zero(edges, 0.0);
    const auto hbar = EdgeAngleSecondForms(
        EdgeAngleFaces(s.mesh, s.topology, s.reference), zero);
    const double at_zero =
        Total(EdgeAngleFaces(s.mesh, s.topology, s.deformed),
              EdgeAngleReferenceFaces(s.mesh, s.reference, hbar), zero, alpha,
              beta);
    EXPECT_NEAR(at_zero, plain, 1e-12 * plain) << alpha << " " << beta;
  }
}

TEST(EdgeAngleBendingTest, JacobianMatchesGradientCheckerWithNegativeTwin) {
  const TestShells s = MakeTestShells();
  const auto shape = EdgeAngleFaces(s.mesh, s.topology, s.deformed);
  const auto reference = EdgeAngleReferenceFaces(
      s.mesh, s.reference,
      EdgeAngleSecondForms(EdgeAngleFaces(s.mesh, s.topology, s.reference),
                           std::vector<double>(s.topology.interior_edges.size(),
                                               0.1)));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-0.4, 0.4);
  int checked = 0;
  double worst = 0, twin_least = 1e300;
  for (size_t f = 0; f < shape.size(); ++f) {
    int interior = 0;
    for (int i = 0; i < 3; ++i) interior += shape[f].interior(i);
    if (interior < 2) continue;
    // Angles away from 0 (Ridders' steps are relative to |x|).
    double phi[3] = {0.5 + angle(rng), -0.5 + angle(rng), 0.7 + angle(rng)};
    std::vector<double*> params = {&phi[0], &phi[1], &phi[2]};
    auto make = [&] {
      return std::unique_ptr<ceres::CostFunction>(
          EdgeAngleBendingCostFunction::Create(shape[f], reference[f], 0.3, 0.7));
    };
    const double error = testing::CostFunctionJacobianError(*make(), params);
    EXPECT_LT(error, 1e-8) << "face " << f;
    int slot = 0;
    while (!shape[f].interior(slot)) ++slot;
    testing::CostFunctionWithWrongJacobian wrong(make(), slot, 1, 1e-4);
    const double twin = testing::CostFunctionJacobianError(wrong, params);
    EXPECT_GT(twin, 1e-6) << "face " << f;
    worst = std::max(worst, error);
    twin_least = std::min(twin_least, twin);
    ++checked;
  }
  EXPECT_GT(checked, 20);
  std::printf("%d faces: largest Jacobian error %.2e, smallest twin %.2e\n",
              checked, worst, twin_least);
}

TEST(EdgeAngleBendingTest, FittedAnglesAreAStationaryMinimum) {
  const TestShells s = MakeTestShells();
  const EdgeAngleBending w =
      EvaluateEdgeAngleBending(s.mesh, s.topology, s.reference, s.deformed);
  ASSERT_TRUE(w.converged) << w.deformed.message;
  EXPECT_GT(w.deformed.iterations, 0);
  EXPECT_LT(w.energy, w.deformed.energy_at_zero);
  const auto shape = EdgeAngleFaces(s.mesh, s.topology, s.deformed);
  const auto reference = EdgeAngleReferenceFaces(
      s.mesh, s.reference,
      EdgeAngleSecondForms(EdgeAngleFaces(s.mesh, s.topology, s.reference),
                           w.reference.angles));
  const std::vector<double>& phi = w.deformed.angles;
  EXPECT_NEAR(Total(shape, reference, phi, 0, 1), w.energy, 1e-13 * w.energy);
  // Central differences of the total in every angle: zero at the fit,
  // not at phi = 0 (the twin: the same measurement catches a non-minimum).
  auto gradient_norm = [&](const std::vector<double>& at) {
    const double h = 1e-6;
    double largest = 0;
    for (size_t e = 0; e < at.size(); ++e) {
      std::vector<double> plus = at, minus = at;
      plus[e] += h;
      minus[e] -= h;
      largest = std::max(largest, std::abs(Total(shape, reference, plus, 0, 1) -
                                           Total(shape, reference, minus, 0, 1)) /
                                      (2 * h));
    }
    return largest;
  };
  const double at_fit = gradient_norm(phi);
  const double at_zero =
      gradient_norm(std::vector<double>(phi.size(), 0.0));
  std::printf("largest |dW/dphi|: %.2e at the fit, %.2e at phi = 0\n", at_fit,
              at_zero);
  // Ceres stops on the relative change of the energy (1e-14), which
  // leaves the gradient at ~1e-7 of its start.
  EXPECT_LT(at_fit, 1e-5 * at_zero);
  EXPECT_GT(at_zero, 1e-3);
  // A minimum: random perturbations raise the energy.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> step(-1e-2, 1e-2);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> moved = phi;
    for (double& a : moved) a += step(rng);
    EXPECT_GT(Total(shape, reference, moved, 0, 1), w.energy);
  }
}

TEST(EdgeAngleBendingTest, ZeroAtRestAndInvariantUnderRigidMotions) {
  const TestShells s = MakeTestShells();
  const EdgeAngleBending rest =
      EvaluateEdgeAngleBending(s.mesh, s.topology, s.deformed, s.deformed);
  EXPECT_TRUE(rest.converged);
  EXPECT_GT(rest.reference.energy, 1e-2);  // a curved shell's own functional
  EXPECT_LT(rest.energy, 1e-20);
  const double w =
      EvaluateEdgeAngleBending(s.mesh, s.topology, s.reference, s.deformed).energy;
  ASSERT_GT(w, 1e-3);
  const double w_ref =
      EvaluateEdgeAngleBending(s.mesh, s.topology,
                               testing::RandomRigidMotion(s.reference, 3),
                               s.deformed)
          .energy;
  const double w_def =
      EvaluateEdgeAngleBending(s.mesh, s.topology, s.reference,
                               testing::RandomRigidMotion(s.deformed, 4))
          .energy;
  EXPECT_NEAR(w_ref, w, 1e-8 * w);
  EXPECT_NEAR(w_def, w, 1e-8 * w);
  // A non-rigid map changes it.
  Positions stretched = s.deformed;
  stretched.col(2) *= 1.5;
  EXPECT_GT(std::abs(EvaluateEdgeAngleBending(s.mesh, s.topology, s.reference,
                                              stretched)
                         .energy -
                     w),
            1e-3 * w);
}

TEST(EdgeAngleBendingTest, JitteredIcosphereConvergesAtSecondOrder) {
  // docs/math.md, "Bending energy: two models": jittered by 0.3 h and projected
  // back, the plain mid-edge form stays ~7.6 % off, the fitted angles give
  // 1.0069, 1.0017, 1.00044, 1.00011 (second order, for another jitter seed
  // than ours, so the values are compared loosely and the rate strictly).
  double error[3];
  for (int level = 2; level <= 4; ++level) {
    Mesh sphere = MakeIcosphere(level);
    const Topology topology = Topology::Build(sphere);
    const double h = MeanEdgeLength(sphere, topology);
    sphere.positions =
        JitterTangentially(sphere.positions, sphere.positions, 0.3 * h, 1);
    sphere.positions.rowwise().normalize();
    const EdgeAngleFit fit = FitEdgeAngles(
        EdgeAngleFaces(sphere, topology, sphere.positions),
        EdgeAngleReferenceFaces(sphere, sphere.positions),
        static_cast<int>(topology.interior_edges.size()));
    ASSERT_TRUE(fit.converged) << fit.message;
    const double ratio = fit.energy / (8 * kPi);
    const double plain = fit.energy_at_zero / (8 * kPi);
    error[level - 2] = ratio - 1;
    std::printf("jittered icosphere level %d: edge angles %.6f (%d iterations), "
                "plain %.6f\n",
                level, ratio, fit.iterations, plain);
    EXPECT_GT(plain - 1, 0.03);  // the plain model does not converge
    EXPECT_GT(ratio, 1.0);
    EXPECT_LT(ratio - 1, 0.012 / (1 << (2 * (level - 2))));
  }
  for (int l = 0; l + 1 < 3; ++l) {
    const double rate = std::log2(error[l] / error[l + 1]);
    std::printf("rate %d->%d: %.3f\n", l + 2, l + 3, rate);
    EXPECT_GT(rate, 1.7);
    EXPECT_LT(rate, 2.4);
  }
}

}  // namespace
}  // namespace shellspace
