// Gradient checks of every branching cost function (ceres::GradientChecker,
// fixed seed), and a negative test: a deliberately wrong Jacobian fails.
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "shellspace/cost_functions/branching/double_well_cost_function.h"
#include "shellspace/cost_functions/branching/elastic_cost_function.h"
#include "shellspace/cost_functions/branching/general_cell_cost_function.h"
#include "shellspace/cost_functions/branching/gradient_cost_function.h"
#include "shellspace/cost_functions/branching/km_energy_cost_function.h"
#include "shellspace/cost_functions/branching/lens_energy_cost_function.h"

namespace shellspace::branching {
namespace {

// Runs the checker at `trials` random points produced by `sample` (which
// fills the parameter blocks); returns true if all points pass.
using Sampler = std::function<void(std::mt19937&,
                                   std::vector<std::vector<double>>*)>;

bool CheckAt(const ceres::CostFunction* cost, const Sampler& sample,
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

// Takes `cost` (as Create returns it) and expects it to pass the checker
// at 20 points of `sample`.
void ExpectPassesAt20Points(ceres::CostFunction* cost, const Sampler& sample,
                            double precision) {
  const std::unique_ptr<ceres::CostFunction> owned(cost);
  std::string error;
  EXPECT_TRUE(CheckAt(owned.get(), sample, 20, precision, &error)) << error;
}

TEST(BranchingCostGradient, Elastic) {
  ExpectPassesAt20Points(ElasticCostFunction::Create(0.01, 0.005, 0.5),
                         ScalarBlocks(2, -0.1, 0.1), 1e-7);
}

TEST(BranchingCostGradient, Gradient) {
  ExpectPassesAt20Points(
      GradientCostFunction::Create(1e-3, 0.02, 0.01, 0.005, 0.5),
      ScalarBlocks(3, -0.1, 0.1), 1e-7);
}

TEST(BranchingCostGradient, DoubleWell) {
  ExpectPassesAt20Points(
      DoubleWellCostFunction::Create(1e-3, 0.02, 0.01, 0.005, 0.5),
      ScalarBlocks(2, -0.01, 0.01), 1e-6);
}

TEST(BranchingCostGradient, KmEnergy) {
  ExpectPassesAt20Points(
      KmEnergyCostFunction::Create(1.0 / 32.0, 8.0, 2, 1e-3, 1.0),
      [](std::mt19937& rng, std::vector<std::vector<double>>* b) {
        std::uniform_real_distribution<double> h(0.05, 0.5), t(0.27, 0.48);
        *b = {{h(rng), t(rng)}};
      },
      1e-6);
}

TEST(BranchingCostGradient, LensEnergy) {
  ExpectPassesAt20Points(
      LensEnergyCostFunction::Create(1e-3, 1.0),
      [](std::mt19937& rng, std::vector<std::vector<double>>* b) {
        std::uniform_real_distribution<double> h(0.05, 0.5), t(0.13, 0.31),
            tau(0.0, 0.8), a(-0.8, 0.8);
        *b = {{h(rng), t(rng), tau(rng), a(rng), a(rng)}};
      },
      1e-6);
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
  // The unperturbed cost passes at the same (seeded) point.
  EXPECT_TRUE(CheckAt(&perturbed.inner_, sample, 1, 1e-6, nullptr));
  EXPECT_FALSE(CheckAt(&perturbed, sample, 1, 1e-6, nullptr));
}

// General cell topologies for the checks: the lens topology (one group, two
// needles), a staggered r = 3 cell with a psi-type needle, and an r = 2
// super-cell of two pairs with an odd label offset.
std::vector<GeneralTopology> CheckTopologies() {
  std::vector<GeneralTopology> out;
  GeneralTopology lens;
  lens.pairs = 1;
  lens.r = 3;
  lens.subintervals = 2;
  lens.groups = {NucleationGroup{{{0, 0.5}, {1, 0.5}}, 0.4}};
  out.push_back(lens);
  GeneralTopology staggered = lens;
  staggered.groups = {NucleationGroup{{{0, 0.3}}, 0.3},
                      NucleationGroup{{{3, 0.6}}, 0.6}};
  out.push_back(staggered);
  GeneralTopology pairs;
  pairs.pairs = 2;
  pairs.r = 2;
  pairs.label_offset = 1;
  pairs.subintervals = 2;
  pairs.first_at_zero = true;
  pairs.groups = {NucleationGroup{{{0, 0.5}, {2, 0.4}}, 0.0}};
  out.push_back(pairs);
  return out;
}

// A valid point of the layout: uniform coarse laminate, every trajectory
// linear from birth to closure, knot positions jittered by a few percent of
// the finest width (the widths stay positive).
std::vector<double> GeneralPoint(const GeneralCellLayout& layout,
                                 std::mt19937& rng) {
  const GeneralTopology& t = layout.topology();
  std::vector<double> x(layout.size(), 0.0);
  for (int i = 1; i + 1 < 2 * t.pairs; ++i) x[i - 1] = i / (2.0 * t.pairs);
  x[layout.delta_offset()] = -t.label_offset / (2.0 * t.pairs * t.r);
  for (size_t g = 0; g < t.groups.size(); ++g) {
    const int o = layout.tau_offset(static_cast<int>(g));
    if (o >= 0) x[o] = t.groups[g].tau;
  }
  int e = 0;
  for (const NucleationGroup& g : t.groups) {
    for (const NeedleEvent& n : g.needles) x[layout.p_offset(e++)] = n.p;
  }
  // Fill the knot positions by tracking a straight-line geometry: evaluate
  // with the knots at their birth-to-closure interpolation. The geometry
  // helper needs a full x; iterate knot by knot from the coarse end.
  GeneralCellGeometry geo;
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  const double h = 0.02 / (2.0 * t.r * t.pairs);
  for (int pass = 0; pass < 2; ++pass) {
    EvaluateGeneralGeometry(layout, x.data(), &geo);
    const int N = layout.num_knots();
    for (int m = 1; m + 1 < N; ++m) {
      for (int id : layout.knot(m).order) {
        const int k = layout.knot(m).param[id];
        if (k < 0) continue;
        // Birth knot and position of id.
        int b = 0;
        while (std::isnan(geo.position[b][id])) ++b;
        const double s0 = geo.s[b], g0 = geo.position[b][id];
        const double s1 = 1.0, g1 = geo.position[N - 1][id];
        x[k] = g0 + (g1 - g0) * (geo.s[m] - s0) / (s1 - s0) +
               (pass == 1 ? h * jitter(rng) : 0.0);
      }
    }
  }
  return x;
}

TEST(BranchingCostGradient, GeneralCell) {
  for (const GeneralTopology& t : CheckTopologies()) {
    std::unique_ptr<GeneralCellCostFunction> cost(
        new GeneralCellCostFunction(t));
    auto sample = [&](std::mt19937& rng, std::vector<std::vector<double>>* b) {
      *b = {GeneralPoint(cost->layout(), rng)};
    };
    std::string error;
    EXPECT_TRUE(CheckAt(cost.get(), sample, 5, 1e-6, &error)) << error;
  }
}

TEST(BranchingCostGradient, GeneralCellWrongJacobianIsDetected) {
  // One Jacobian entry of the real cost scaled by 1.01 (a plausible slip in
  // one chain-rule term): the same checker fails.
  const GeneralTopology t = CheckTopologies()[0];
  class Perturbed : public ceres::CostFunction {
   public:
    explicit Perturbed(const GeneralTopology& t) : inner_(t) {
      set_num_residuals(inner_.num_residuals());
      *mutable_parameter_block_sizes() = inner_.parameter_block_sizes();
    }
    bool Evaluate(double const* const* p, double* r,
                  double** j) const override {
      if (!inner_.Evaluate(p, r, j)) return false;
      // d r_0 / d tau_0 (the nucleation position).
      if (j != nullptr && j[0] != nullptr) {
        j[0][inner_.layout().tau_offset(0)] *= 1.01;
      }
      return true;
    }
    GeneralCellCostFunction inner_;
  } perturbed(t);
  // The residual rows after nucleation depend on tau through ds and B.
  auto sample = [&](std::mt19937& rng, std::vector<std::vector<double>>* b) {
    *b = {GeneralPoint(perturbed.inner_.layout(), rng)};
  };
  // The unperturbed cost passes at the same (seeded) point.
  EXPECT_TRUE(CheckAt(&perturbed.inner_, sample, 1, 1e-6, nullptr));
  EXPECT_FALSE(CheckAt(&perturbed, sample, 1, 1e-6, nullptr));
}

}  // namespace
}  // namespace shellspace::branching
