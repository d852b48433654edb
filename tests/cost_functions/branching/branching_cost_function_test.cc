// Gradient checks of every branching cost function (ceres::GradientChecker,
// fixed seed), and a negative test: a deliberately wrong Jacobian fails.
#include <memory>
#include <random>
#include <vector>

#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "shellspace/cost_functions/branching/double_well_cost_function.h"
#include "shellspace/cost_functions/branching/elastic_cost_function.h"
#include "shellspace/cost_functions/branching/gradient_cost_function.h"
#include "shellspace/cost_functions/branching/km_energy_cost_function.h"
#include "shellspace/cost_functions/branching/lens_energy_cost_function.h"

namespace shellspace::branching {
namespace {

// Runs the checker at `trials` random points produced by `sample` (which
// fills the parameter blocks); returns true if all points pass.
bool CheckAt(const ceres::CostFunction* cost,
             const std::function<void(std::mt19937&, std::vector<std::vector<double>>*)>& sample,
             int trials, double precision, std::string* error) {
  ceres::NumericDiffOptions numeric;
  // The checker differentiates with Ridders extrapolation; keep its first
  // step inside the domain of the construction energies.
  numeric.ridders_relative_initial_step_size = 1e-4;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  ceres::GradientChecker checker(cost, no_manifolds, numeric);
  std::mt19937 rng(20240521);
  for (int t = 0; t < trials; ++t) {
    std::vector<std::vector<double>> blocks;
    sample(rng, &blocks);
    std::vector<double*> pointers;
    for (auto& b : blocks) pointers.push_back(b.data());
    ceres::GradientChecker::ProbeResults results;
    if (!checker.Probe(pointers.data(), precision, &results)) {
      if (error) *error = results.error_log;
      return false;
    }
  }
  return true;
}

auto ScalarBlocks(int count, double low, double high) {
  return [=](std::mt19937& rng, std::vector<std::vector<double>>* blocks) {
    std::uniform_real_distribution<double> d(low, high);
    blocks->assign(count, std::vector<double>(1));
    for (auto& b : *blocks) b[0] = d(rng);
  };
}

TEST(BranchingCostGradient, Elastic) {
  std::unique_ptr<ceres::CostFunction> cost(
      ElasticCostFunction::Create(0.01, 0.005, 0.5));
  std::string error;
  EXPECT_TRUE(CheckAt(cost.get(), ScalarBlocks(2, -0.1, 0.1), 20, 1e-7, &error))
      << error;
}

TEST(BranchingCostGradient, Gradient) {
  std::unique_ptr<ceres::CostFunction> cost(
      GradientCostFunction::Create(1e-3, 0.02, 0.01, 0.005, 0.5));
  std::string error;
  EXPECT_TRUE(CheckAt(cost.get(), ScalarBlocks(3, -0.1, 0.1), 20, 1e-7, &error))
      << error;
}

TEST(BranchingCostGradient, DoubleWell) {
  std::unique_ptr<ceres::CostFunction> cost(
      DoubleWellCostFunction::Create(1e-3, 0.02, 0.01, 0.005, 0.5));
  std::string error;
  EXPECT_TRUE(
      CheckAt(cost.get(), ScalarBlocks(2, -0.01, 0.01), 20, 1e-6, &error))
      << error;
}

TEST(BranchingCostGradient, KmEnergy) {
  std::unique_ptr<ceres::CostFunction> cost(
      KmEnergyCostFunction::Create(1.0 / 32.0, 8.0, 2, 1e-3, 1.0));
  auto sample = [](std::mt19937& rng, std::vector<std::vector<double>>* b) {
    std::uniform_real_distribution<double> h(0.05, 0.5), t(0.27, 0.48);
    *b = {{h(rng), t(rng)}};
  };
  std::string error;
  EXPECT_TRUE(CheckAt(cost.get(), sample, 20, 1e-6, &error)) << error;
}

TEST(BranchingCostGradient, LensEnergy) {
  std::unique_ptr<ceres::CostFunction> cost(
      LensEnergyCostFunction::Create(1e-3, 1.0));
  auto sample = [](std::mt19937& rng, std::vector<std::vector<double>>* b) {
    std::uniform_real_distribution<double> h(0.05, 0.5), t(0.13, 0.31),
        tau(0.0, 0.8), a(-0.8, 0.8);
    *b = {{h(rng), t(rng), tau(rng), a(rng), a(rng)}};
  };
  std::string error;
  EXPECT_TRUE(CheckAt(cost.get(), sample, 20, 1e-6, &error)) << error;
}

// A double-well residual whose Jacobian misses the factor 2 (a plausible
// slip): the same checker must reject it.
class WrongDoubleWell : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  bool Evaluate(double const* const* p, double* r,
                double** jacobians) const override {
    const double d = p[1][0] - p[0][0];
    r[0] = 1.0 - d * d * 1e4;
    if (jacobians != nullptr) {
      if (jacobians[0]) jacobians[0][0] = d * 1e4;   // should be 2 d 1e4
      if (jacobians[1]) jacobians[1][0] = -d * 1e4;
    }
    return true;
  }
};

TEST(BranchingCostGradient, WrongJacobianIsDetected) {
  WrongDoubleWell wrong;
  std::string error;
  EXPECT_FALSE(CheckAt(&wrong, ScalarBlocks(2, -0.01, 0.01), 5, 1e-6, &error));
  EXPECT_FALSE(error.empty());
}

TEST(BranchingCostGradient, LensEnergyWrongJacobianIsDetected) {
  // Perturb one Jacobian entry of the real lens cost: the checker fails.
  class Perturbed : public ceres::SizedCostFunction<kLensEnergyPoints + 1, 5> {
   public:
    bool Evaluate(double const* const* p, double* r,
                  double** j) const override {
      if (!inner_.Evaluate(p, r, j)) return false;
      if (j != nullptr && j[0] != nullptr) j[0][3] *= 1.01;  // d r_0 / d a1
      return true;
    }
    LensEnergyCostFunction inner_{1e-3, 1.0};
  } perturbed;
  auto sample = [](std::mt19937&, std::vector<std::vector<double>>* b) {
    *b = {{0.3, 0.2, 0.3, 0.4, -0.2}};
  };
  EXPECT_FALSE(CheckAt(&perturbed, sample, 1, 1e-6, nullptr));
}

}  // namespace
}  // namespace shellspace::branching
