// Gradient checks of every branching cost function (ceres::GradientChecker,
// fixed seed), and a negative test: a deliberately wrong Jacobian fails.
// The general cell's Jacobian (automatic differentiation) also against
// central differences through the suite's derivative-check helper, with its
// negative twin.
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "shellspace/cost_functions/branching/double_well_cost_function.h"
#include "shellspace/cost_functions/branching/elastic_cost_function.h"
#include "shellspace/cost_functions/branching/general_cell_cost_function.h"
#include "shellspace/cost_functions/branching/gradient_cost_function.h"
#include "shellspace/cost_functions/branching/km_energy_cost_function.h"
#include "shellspace/cost_functions/branching/lens_energy_cost_function.h"
#include "tests/testing/derivative_check.h"

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

// Every topology class of the general cell tests (here and in
// tests/problems/branching/branching_general_test.cc): the needle (p = 1/2)
// and the psi-junctions (p = 1, p = 0) of r = 2, nucleating at tau = 0 or
// later; the lens (two needles in one group); staggered groups; two and
// three lamella pairs with odd label offsets; the r = 4 cell of three
// groups with K = 6.
struct GeneralCase {
  const char* name;
  GeneralTopology topology;
};

GeneralTopology Cell(int pairs, int r, int offset, int subintervals,
                     bool at_zero, std::vector<NucleationGroup> groups) {
  GeneralTopology t;
  t.pairs = pairs;
  t.r = r;
  t.label_offset = offset;
  t.subintervals = subintervals;
  t.first_at_zero = at_zero;
  t.groups = std::move(groups);
  return t;
}

std::vector<GeneralCase> GeneralCases() {
  const std::vector<GeneralTopology> check = CheckTopologies();
  return {
      {"needle_at_zero", Cell(1, 2, 0, 2, true, {{{{0, 0.5}}, 0.0}})},
      {"psi_top_at_zero", Cell(1, 2, 0, 2, true, {{{{0, 1.0}}, 0.0}})},
      {"psi_bottom", Cell(1, 2, 1, 2, false, {{{{1, 0.0}}, 0.5}})},
      {"lens", check[0]},
      {"lens_at_zero", Cell(1, 3, 0, 2, true, {{{{0, 0.5}, {1, 0.5}}, 0.0}})},
      {"staggered", check[1]},
      {"two_pairs_odd_offset", check[2]},
      {"three_pairs_psi", Cell(3, 2, 1, 3, false,
                               {{{{1, 0.5}, {3, 0.0}}, 0.4},
                                {{{0, 1.0}}, 0.6}})},
      {"r4_three_groups", Cell(1, 4, 1, 6, false,
                               {{{{0, 0.5}}, 0.3},
                                {{{3, 0.5}}, 0.5},
                                {{{0, 0.5}}, 0.7}})},
  };
}

// The residuals at x (NaN outside the domain).
Eigen::VectorXd GeneralResiduals(const GeneralCellCostFunction& cost,
                                 const Eigen::VectorXd& x) {
  Eigen::VectorXd r(cost.num_residuals());
  const double* parameters[] = {x.data()};
  if (!cost.Evaluate(parameters, r.data(), nullptr)) {
    r.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return r;
}

// The Jacobian of the general cell against central differences of its
// residuals (testing::CentralDifferenceError, h = 1e-6, every coordinate but
// a needle position on the boundary p = 0 or 1, where one side leaves the
// domain) at 3 random points per topology class: the start values of tau
// and of the interior p drawn, the knots jittered (GeneralPoint). The
// negative twin is the same Jacobian with its largest probed entry off by
// 1e-4 of that entry. The residuals of an evaluation with the Jacobian are
// those without, to the bit.
TEST(BranchingCostGradient, GeneralCellJacobianMatchesCentralDifferences) {
  std::mt19937 rng(20261204);
  std::uniform_real_distribution<double> shift(-1.0, 1.0);
  int checked = 0;
  for (const GeneralCase& c : GeneralCases()) {
    for (int trial = 0; trial < 3; ++trial) {
      SCOPED_TRACE(std::string(c.name) + " trial " + std::to_string(trial));
      GeneralTopology t = c.topology;
      for (size_t g = 0; g < t.groups.size(); ++g) {
        if (!(t.first_at_zero && g == 0)) t.groups[g].tau += 0.04 * shift(rng);
        for (NeedleEvent& e : t.groups[g].needles) {
          if (e.p > 0.0 && e.p < 1.0) e.p += 0.15 * shift(rng);
        }
      }
      const GeneralCellCostFunction cost(t);
      const GeneralCellLayout& layout = cost.layout();
      const std::vector<double> start = GeneralPoint(layout, rng);
      const Eigen::VectorXd x =
          Eigen::Map<const Eigen::VectorXd>(start.data(), start.size());
      const int n = layout.size();
      const int m = cost.num_residuals();
      Eigen::VectorXd residuals(m);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
          jacobian(m, n);
      const double* parameters[] = {x.data()};
      double* jacobians[] = {jacobian.data()};
      ASSERT_TRUE(cost.Evaluate(parameters, residuals.data(), jacobians));
      const Eigen::VectorXd plain = GeneralResiduals(cost, x);
      EXPECT_TRUE((residuals.array() == plain.array()).all());
      std::vector<int> probes;
      for (int k = 0; k < n; ++k) {
        const bool needle = k >= layout.p_offset(0) &&
                            k < layout.p_offset(0) + layout.num_needles();
        if (!(needle && (x(k) == 0.0 || x(k) == 1.0))) probes.push_back(k);
      }
      // The wrong entry: the largest of the probed columns.
      testing::WrongEntry wrong{0, probes[0], 0.0};
      for (int k : probes) {
        Eigen::Index row = 0;
        const double v = jacobian.col(k).cwiseAbs().maxCoeff(&row);
        if (v > std::abs(wrong.offset)) {
          wrong = {static_cast<int>(row), k, v};
        }
      }
      wrong.offset *= 1e-4;
      const testing::ErrorAndTwin e = testing::CentralDifferenceErrorAndTwin(
          [&](const Eigen::VectorXd& y) { return GeneralResiduals(cost, y); },
          x, [&](int k) -> Eigen::VectorXd { return jacobian.col(k); },
          probes, 1e-6, wrong);
      EXPECT_LT(e.error, 1e-7) << n << " parameters";
      EXPECT_GT(e.twin_error, 1e-5);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 27);
}

}  // namespace
}  // namespace shellspace::branching
