// The general reduced sharp-interface optimiser (general_search.h): the
// reference cells reproduced as special topologies, the cross-check against
// the generic cell evaluator, and a pattern with C <= 5.70 checked by an
// independent evaluation (exact u on a fine y-grid, elastic integral by
// quadrature).
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "shellspace/cost_functions/branching/cell_pattern.h"
#include "shellspace/cost_functions/branching/general_cell_cost_function.h"
#include "shellspace/problems/branching/general_search.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/self_similar_series.h"

namespace shellspace::branching {
namespace {

GeneralTopology OneGroup(int r, std::vector<NeedleEvent> needles,
                         bool at_zero, int subintervals = 1) {
  GeneralTopology t;
  t.pairs = 1;
  t.r = r;
  t.subintervals = subintervals;
  t.first_at_zero = at_zero;
  t.groups = {NucleationGroup{needles, at_zero ? 0.0 : 0.5}};
  return t;
}

// A, B of the straight (clean) start of a topology: no optimisation.
GeneralCellGeometry Straight(const GeneralTopology& t, double delta) {
  const GeneralCellLayout layout(t);
  std::vector<double> x;
  EXPECT_TRUE(GeneralStart(layout, delta, 0.0, 1, &x));
  GeneralCellGeometry geo;
  EXPECT_TRUE(EvaluateGeneralGeometry(layout, x.data(), &geo));
  return geo;
}

double K(int r) { return SeriesConstant(1.0, 1.0, r, OptimalTheta(r)); }

// The reference cells as topologies of the general model, straight
// interfaces: the needle (T2) cell, the KM psi-junction (needle at the top
// of the +1 lamella, p = 1), and needles in every lamella with r = 3 and
// tau = 0.
TEST(BranchingGeneral, ReproducesReferenceCells) {
  const GeneralCellGeometry needle =
      Straight(OneGroup(2, {{0, 0.5}}, true), -0.125);
  EXPECT_NEAR(needle.A, 1.0 / 32.0, 1e-14);
  EXPECT_NEAR(needle.B, 8.0, 1e-14);
  EXPECT_NEAR(K(2) * std::cbrt(needle.A * needle.B * needle.B), 6.856108742239,
              1e-9);
  const GeneralCellGeometry km = Straight(OneGroup(2, {{0, 1.0}}, true), 0.0);
  EXPECT_NEAR(km.A, 1.0 / 24.0, 1e-14);
  EXPECT_NEAR(km.B, 8.0, 1e-14);
  EXPECT_NEAR(K(2) * std::cbrt(km.A * km.B * km.B), KmShiftedClosedFormConstant(),
              1e-9);
  const GeneralCellGeometry lens =
      Straight(OneGroup(3, {{0, 0.5}, {1, 0.5}}, true), 0.0);
  EXPECT_NEAR(lens.A, 5.0 / 216.0, 1e-14);
  EXPECT_NEAR(lens.B, 12.0, 1e-14);
  EXPECT_NEAR(K(3) * std::cbrt(lens.A * lens.B * lens.B), 6.078, 5e-4);
  std::printf("general: needle %.10f km %.10f lens(tau=0) %.10f\n",
              K(2) * std::cbrt(needle.A * needle.B * needle.B),
              K(2) * std::cbrt(km.A * km.B * km.B),
              K(3) * std::cbrt(lens.A * lens.B * lens.B));
}

// The lens topology optimised with 6 linear pieces per segment: the
// optimum of the lens family (5.837450, cubic profile) within the
// piecewise-linear approximation error, and the generic evaluator
// (EvaluateCell on the CellPattern) agrees with the cost function.
TEST(BranchingGeneral, LensOptimumAndEvaluatorCrossCheck) {
  const GeneralResult r =
      SolveGeneral(OneGroup(3, {{0, 0.5}, {1, 0.5}}, false, 6), 0.0, 0.0, 1);
  ASSERT_TRUE(r.ok) << r.termination;
  std::printf("general lens: C_geo %.8f C_free %.8f tau %.6f (%d iterations)\n",
              r.constant_geometric, r.constant_free, r.topology.groups[0].tau,
              r.iterations);
  EXPECT_NEAR(r.constant_geometric, 5.837450, 2e-4 * 5.837450);
  EXPECT_NEAR(r.topology.groups[0].tau, 0.5, 1e-3);
  const CellCoefficients c = EvaluateCell(GeneralCellPattern(r), 8);
  EXPECT_NEAR(c.A, r.A, 1e-10);
  EXPECT_NEAR(c.B, r.B, 1e-10);
}

// Independent evaluation of a general cell: at Gauss–Legendre nodes s of
// every knot interval the interfaces are interpolated linearly, u(s, eta) =
// \int_0^eta u_y is computed exactly on a uniform eta-grid of `n` points
// (u_y = +-1 from the interface count below eta), d_s u by a central
// difference, the per-column mean removed, and the squares summed
// (trapezoid in eta, Gauss in s). B from the birth positions.
double IndependentA(const GeneralCellLayout& layout,
                    const GeneralCellGeometry& geo, int n) {
  std::vector<double> nodes, weights;
  GaussLegendre01(3, &nodes, &weights);
  double A = 0.0;
  const int N = layout.num_knots();
  auto column_u = [&](int m, double s, std::vector<double>* u) {
    // Interfaces of interval m at s, reduced mod 1, with their jumps.
    const std::vector<int>& order = geo.order[m];
    const double f = (s - geo.s[m]) / (geo.s[m + 1] - geo.s[m]);
    std::vector<std::pair<double, int>> cuts;
    for (int id : order) {
      double g = geo.position[m][id] +
                 f * (geo.position[m + 1][id] - geo.position[m][id]);
      g -= std::floor(g);
      cuts.push_back({g, layout.jump(id)});
    }
    std::sort(cuts.begin(), cuts.end());
    // Variant on [0, first cut): the one below the last cut, i.e. after all
    // jumps: v0 = -(sum of jumps up to the last cut)/... determined by the
    // last cut's jump: above a +2 jump the variant is +1.
    const double v_start = cuts.back().second > 0 ? 1.0 : -1.0;
    u->assign(n, 0.0);
    double value = 0.0, y = 0.0, v = v_start;
    size_t c = 0;
    for (int j = 0; j < n; ++j) {
      const double target = static_cast<double>(j) / n;
      while (c < cuts.size() && cuts[c].first < target) {
        value += v * (cuts[c].first - y);
        y = cuts[c].first;
        v = cuts[c].second > 0 ? 1.0 : -1.0;
        ++c;
      }
      value += v * (target - y);
      y = target;
      (*u)[j] = value;
    }
  };
  std::vector<double> up, um;
  for (int m = 0; m + 1 < N; ++m) {
    const double a = geo.s[m], b = geo.s[m + 1];
    const double h = 1e-7 * (b - a);
    for (int q = 0; q < 3; ++q) {
      const double s = a + (b - a) * nodes[q];
      column_u(m, s + h, &up);
      column_u(m, s - h, &um);
      double mean = 0.0, second = 0.0;
      for (int j = 0; j < n; ++j) {
        const double d = (up[j] - um[j]) / (2.0 * h);
        mean += d / n;
        second += d * d / n;
      }
      A += (b - a) * weights[q] * (second - mean * mean);
    }
  }
  return A;
}

// The pattern found by `branching construct --family general --search`
// (r = 4, one lamella pair: a -1 needle nucleates in the +1 lamella at
// tau_A, then a second -1 needle in the lower part of the +1 lamella and a
// +1 needle in the -1 lamella at a common tau_B; 6 linear pieces per
// segment; label offset 1, i.e. the next generation has the variants
// swapped). Parameter block listed as found.
GeneralTopology BestTopology() {
  GeneralTopology t;
  t.pairs = 1;
  t.r = 4;
  t.label_offset = 1;
  t.subintervals = 6;
  t.groups = {NucleationGroup{{{0, 0.5}}, 0.3},
              NucleationGroup{{{0, 0.5}, {3, 0.5}}, 0.7}};
  t.name = "r4-n1-o1-0|0,3";
  return t;
}

const std::vector<double> kBestX = {
-0.19102851414427263,0.5529863263763568,0.7235069323072173,0.7043352649687242,0.41608773630053475,0.4613787500126208,3.759414609558015e-05,7.516813763438988e-05,0.00011270177602246466,0.00015017476360917734,0.00018756662376329954,0.00022485657319690924,-0.0031516187852121086,0.3466448564524819,0.35810345061168664,-0.006504724415571793,0.34089327683862347,0.36373243334747024,-0.009834385472324562,0.33514305079608186,0.369286865729617,-0.013140424919439866,0.3293943340707739,0.37476903487618285,-0.01642260371246154,0.3236467072951176,0.3801805875552438,-0.0196806150309617,0.31789960132504835,0.38552293789558534,-0.027282462465705173,0.11100101630237684,0.13064776251842575,0.31654453642939157,0.39397816538711056,0.7375037355453766,0.7572760542999639,-0.03493562189443454,0.10102052998751422,0.1407185856070298,0.31501235602559546,0.4022045004344197,0.7273694560027253,0.76726412303749,-0.04264050435078515,0.09084609050111764,0.15104367321999995,0.31340238057178166,0.41027052038721473,0.7169915462539705,0.7774038766125567,-0.050395156256686946,0.08046192041374851,0.1616611401573621,0.3118017218842796,0.4182275418028097,0.706332646970517,0.7877151376097672,-0.05819457167873831,0.0698462695162976,0.1726171698750725,0.31029472567512356,0.42611635260078046,0.6953461689871764,0.7982251626288451};

TEST(BranchingGeneral, PatternBelow570IndependentlyChecked) {
  const GeneralCellLayout layout(BestTopology());
  ASSERT_EQ(layout.size(), static_cast<int>(kBestX.size()));
  GeneralCellGeometry geo;
  ASSERT_TRUE(EvaluateGeneralGeometry(layout, kBestX.data(), &geo));
  // Column check: the +1 fraction is 1/2 at every knot; the fine end is the
  // coarse end scaled by 1/4 (8 interfaces at spacing 1/8).
  for (int m = 0; m < layout.num_knots(); ++m) {
    double plus = 0.0;
    for (int id : geo.order[m]) plus -= layout.jump(id) / 2.0 * geo.position[m][id];
    EXPECT_NEAR(plus, 0.5, 1e-13) << m;
  }
  const std::vector<int>& last = geo.order.back();
  ASSERT_EQ(last.size(), 8u);
  for (size_t j = 1; j < 8; ++j) {
    EXPECT_NEAR(geo.position.back()[last[j]] - geo.position.back()[last[j - 1]],
                0.125, 1e-12);
  }
  // B from the birth positions.
  double B = 0.0;
  for (int id = 0; id < layout.num_trajectories(); ++id) {
    int b = 0;
    while (std::isnan(geo.position[b][id])) ++b;
    B += 2.0 * (1.0 - geo.s[b]);
  }
  const double A = IndependentA(layout, geo, 40000);
  const double C = FreeLengthSeriesConstant(4) * std::cbrt(A * B * B);
  std::printf("best: A %.9f (cost function %.9f) B %.9f C_free %.6f C_geo %.6f\n",
              A, geo.A, B, C, K(4) * std::cbrt(A * B * B));
  EXPECT_NEAR(A, geo.A, 2e-4 * geo.A);
  EXPECT_NEAR(B, geo.B, 1e-12);
  EXPECT_LE(C, 5.70);
  // The energy of the series with the free lengths, summed directly.
  const FreeLengthSeries series = OptimalFreeLengths(A, B, 4, 1e-3, 1.0);
  EXPECT_NEAR(series.constant, C, 1e-9 * C);
  // The generic evaluator on the same curves.
  GeneralResult r;
  r.topology = BestTopology();
  r.x = kBestX;
  r.delta = kBestX[layout.delta_offset()];
  const CellCoefficients c = EvaluateCell(GeneralCellPattern(r), 8);
  EXPECT_NEAR(c.A, geo.A, 1e-10);
}

}  // namespace
}  // namespace shellspace::branching
