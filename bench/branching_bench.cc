// Benchmarks of the branching problem (also the general reduced search,
// r = 4): the relaxed simulation at the CLI
// default grid (64 x 128) and at the finest grid used (eps 1e-3, L 1, H 0.5,
// 128 x 256 nodes = 32768 unknowns, 98304 residuals, delta = 3 dy = 0.0059
// = 0.059 eps^(1/3), continuation 4 delta -> delta; the ladder's finest rung,
// 48 x 250, is smaller), the LM optimisation of the lens and KM families, and the
// scaling ladder of the report (counters: exponent, constant), and one
// evaluation of the general cell cost function (residuals, or residuals and
// Jacobian) on three topologies.
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/general_search.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/scaling_ladder.h"
#include "shellspace/problems/branching/simulation.h"

namespace shellspace::branching {
namespace {

void BM_SimulateFinestGrid(benchmark::State& state) {
  SimulationSettings s;
  s.epsilon = 1e-3;
  s.length = 1.0;
  s.height = 0.5;
  s.nx = static_cast<int>(state.range(0));
  s.ny = static_cast<int>(state.range(1));
  s.init = "needle";
  s.continuation = 3;
  s.num_threads = 1;
  SimulationResult last(RelaxedGrid(1, 1, 2, 8, 1));
  for (auto _ : state) {
    SimulationResult r = RunSimulation(s);
    benchmark::DoNotOptimize(r.energy.total());
    last = std::move(r);
  }
  state.counters["unknowns"] = s.nx * s.ny;
  state.counters["lm_iterations"] = last.iterations;
  state.counters["energy"] = last.energy.total();
  state.counters["E_over_eps23"] =
      last.energy.total() / std::pow(s.epsilon, 2.0 / 3.0);
  int max_count = 0;
  for (int c : last.interfaces) max_count = std::max(max_count, c);
  state.counters["interfaces_far"] = last.interfaces.back();
  state.counters["interfaces_max"] = max_count;
}
BENCHMARK(BM_SimulateFinestGrid)
    ->Args({64, 128})
    ->Args({128, 256})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

void BM_OptimizeLens(benchmark::State& state) {
  ConstructionResult r;
  for (auto _ : state) {
    const ConstructionResult start = DefaultLens(1e-3, 1.0);
    r = OptimizeLens(1e-3, 1.0, start.h0, start.theta, LensShape{0.2, 0, 0});
    benchmark::ClobberMemory();
  }
  state.counters["lm_iterations"] = r.iterations;
  state.counters["C_lens"] = r.constant;
  state.counters["ratio_to_KM"] = r.constant / KmClosedFormConstant();
  state.counters["ratio_to_KM_shifted"] =
      r.constant / KmShiftedClosedFormConstant();
}
BENCHMARK(BM_OptimizeLens)->Unit(benchmark::kMicrosecond);

void BM_OptimizeKm(benchmark::State& state) {
  ConstructionResult r;
  for (auto _ : state) {
    r = OptimizeKm(1e-3, 1.0, 0.1, 0.3);
    benchmark::ClobberMemory();
  }
  state.counters["lm_iterations"] = r.iterations;
  state.counters["C_KM"] = r.constant;  // optimal shift, 7.546124
}
BENCHMARK(BM_OptimizeKm)->Unit(benchmark::kMicrosecond);

// The general optimiser: the search restricted to r = 4, one lamella pair
// (every grouping of the 3 needles, both label offsets, 6 starts each, the
// best 4 refined to 6 pieces per segment); counter: C with free lengths.
void BM_GeneralSearchR4(benchmark::State& state) {
  GeneralSearchOptions o;
  o.ratios = {4};
  o.max_pairs = 1;
  o.num_threads = static_cast<int>(state.range(0));
  GeneralSearchResult r;
  for (auto _ : state) r = SearchGeneral(o);
  state.counters["C_free"] = r.best.constant_free;
  state.counters["solves"] = r.solves;
}
BENCHMARK(BM_GeneralSearchR4)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);

// One GeneralCellCostFunction::Evaluate at a start of a topology:
// range(0) picks the topology (0: the lens, r = 3, one pair, K = 2, 11
// parameters; 1: the r = 4 cell of three groups with K = 6, 96 parameters;
// 2: two pairs, r = 3, two groups, K = 3, 61 parameters; 32, 300 and 300
// residuals), range(1) = 1 asks for the Jacobian as well.
void BM_GeneralCellEvaluate(benchmark::State& state) {
  GeneralTopology t;
  switch (state.range(0)) {
    case 0:
      t.r = 3;
      t.subintervals = 2;
      t.groups = {NucleationGroup{{{0, 0.5}, {1, 0.5}}, 0.4}};
      break;
    case 1:
      t.r = 4;
      t.label_offset = 1;
      t.subintervals = 6;
      t.groups = {NucleationGroup{{{0, 0.5}}, 0.3},
                  NucleationGroup{{{3, 0.5}}, 0.5},
                  NucleationGroup{{{0, 0.5}}, 0.7}};
      break;
    default:
      t.pairs = 2;
      t.r = 3;
      t.label_offset = 1;
      t.subintervals = 3;
      t.groups = {NucleationGroup{{{0, 0.5}, {2, 0.5}}, 0.3},
                  NucleationGroup{{{1, 0.5}, {6, 0.5}}, 0.6}};
      break;
  }
  const GeneralCellCostFunction cost(t);
  // The first valid start of the search's (shift, noise) sequence.
  const double base = -t.label_offset / (2.0 * t.pairs * t.r);
  const double unit = 1.0 / (4.0 * t.r * t.pairs);
  std::vector<double> x;
  bool valid = false;
  for (double shift : {0.0, unit, -unit}) {
    for (double noise : {0.3, 0.0}) {
      if (!valid) valid = GeneralStart(cost.layout(), base + shift, noise, 1, &x);
    }
  }
  if (!valid) {
    state.SkipWithError("no valid start");
    return;
  }
  std::vector<double> residuals(cost.num_residuals());
  std::vector<double> jacobian(residuals.size() * x.size());
  const double* parameters[] = {x.data()};
  double* jacobians[] = {jacobian.data()};
  const bool with_jacobian = state.range(1) != 0;
  for (auto _ : state) {
    const bool ok = cost.Evaluate(parameters, residuals.data(),
                                  with_jacobian ? jacobians : nullptr);
    benchmark::DoNotOptimize(ok);
    benchmark::ClobberMemory();
  }
  state.counters["parameters"] = static_cast<double>(x.size());
  state.counters["residuals"] = static_cast<double>(residuals.size());
}
BENCHMARK(BM_GeneralCellEvaluate)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// The ladder of the report: 5 eps over a decade, delta = 0.06 eps^(1/3),
// H = 0.5, nx = 48 (graded), dy = delta / 3.
void BM_ScalingLadder(benchmark::State& state) {
  LadderSettings s;
  for (int k = 0; k < 5; ++k) s.epsilons.push_back(1e-3 * std::pow(10.0, k / 4.0));
  s.height = 0.5;
  s.nx = 48;
  s.delta_over_lambda = 0.06;
  s.continuation = 3;
  LadderResult r;
  for (auto _ : state) {
    r = RunLadder(s);
  }
  state.counters["exponent"] = r.exponent;
  state.counters["constant"] = r.constant;
  for (size_t k = 0; k < r.rungs.size(); ++k) {
    state.counters["E" + std::to_string(k)] = r.rungs[k].energy;
    state.counters["ny" + std::to_string(k)] = r.rungs[k].ny;
  }
}
BENCHMARK(BM_ScalingLadder)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace shellspace::branching

