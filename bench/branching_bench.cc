// Benchmarks of the branching problem (also the general reduced search,
// r = 4): the relaxed simulation at the CLI
// default grid (64 x 128) and at the finest grid used (eps 1e-3, L 1, H 0.5,
// 128 x 256 nodes = 32768 unknowns, 98304 residuals, delta = 3 dy = 0.0059
// = 0.059 eps^(1/3), continuation 4 delta -> delta; the ladder's finest rung,
// 48 x 250, is smaller), the LM optimisation of the lens and KM families, and the
// scaling ladder of the report (counters: exponent, constant).
#include <cmath>

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

