// The general reduced sharp-interface optimiser (thesis §8.2): LM on
// GeneralCellCostFunction (cost_functions/branching/general_cell_cost_function.h)
// for one topology from one start, a deterministic multi-start search over
// topologies, and the conversion of an optimum to a CellPattern (rendering,
// EvaluateCell cross-check).
//
// The cell energy and the generation series separate: every generation uses
// the same cell, so the construction costs C eps^(2/3) L^(1/3) with
// C = K_r (A B^2)^(1/3), K_r the series constant of self_similar_series.h
// (geometric lengths: SeriesConstant(1, 1, r, OptimalTheta(r)); free lengths:
// FreeLengthSeriesConstant(r)). The optimiser minimises A B^2.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_GENERAL_SEARCH_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_GENERAL_SEARCH_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/models/branching/cell_pattern.h"
#include "shellspace/cost_functions/branching/general_cell_cost_function.h"

namespace shellspace::branching {

struct GeneralResult {
  GeneralTopology topology;   // with the optimised tau / p as start values
  std::vector<double> x;      // the parameter block at the optimum
  double A = 0.0, B = 0.0;
  double AB2 = 0.0;           // A B^2
  double constant_geometric = 0.0;  // K_r^geo (A B^2)^(1/3)
  double constant_free = 0.0;       // K_r^free (A B^2)^(1/3)
  double delta = 0.0;               // closure shift
  int iterations = 0;
  bool ok = false;                  // a valid start and a usable solve
  std::string termination;
};

// The start: uniform coarse laminate (q_i = i / 2n_c), closure shift
// `delta`, every trajectory linear in s from its birth point (hosts
// interpolated) to its closure position, the topology's tau and p; knot
// positions perturbed by `noise` times the smallest start width (seeded).
// Returns false if the start violates the ordering or the volume slave
// leaves its neighbours.
bool GeneralStart(const GeneralCellLayout& layout, double delta, double noise,
                  unsigned seed, std::vector<double>* x);

// LM (DENSE_QR) with p in [0, 1], tau in [0.01, 0.98].
GeneralResult OptimizeGeneral(const GeneralTopology& topology,
                              const std::vector<double>& start,
                              int max_iterations = 400);

// One start + solve (ok = false if the start is invalid).
GeneralResult SolveGeneral(const GeneralTopology& topology, double delta,
                           double noise, unsigned seed,
                           int max_iterations = 400);

// The optimum re-solved with `factor` times more knots per segment, started
// from the same (piecewise-linear) geometry, so the energy does not rise.
GeneralResult RefineGeneral(const GeneralResult& coarse, int factor,
                            int max_iterations = 400);

struct GeneralSearchOptions {
  std::vector<int> ratios = {2, 3, 4};
  int max_pairs = 2;
  int subintervals = 3;
  int starts_per_topology = 1;  // noisy restarts besides the clean start
  unsigned seed = 1;
  int max_iterations = 300;
  int num_threads = 1;          // topologies solved in parallel (order-free)
  std::string filter;           // only topologies whose name contains it
  int refine_best = 4;          // the best topologies refined at the end
  int refine_factor = 2;        // knots per segment multiplied by this
  int refine_iterations = 2000; // LM iterations of each refinement
};

struct GeneralSearchResult {
  GeneralResult best;
  std::vector<GeneralResult> per_topology;  // best of each topology
  int solves = 0;
};

// The topologies searched (deterministic list): see general_search.cc.
std::vector<GeneralTopology> SearchTopologies(const GeneralSearchOptions& options);

GeneralSearchResult SearchGeneral(
    const GeneralSearchOptions& options,
    const std::function<void(const GeneralResult&)>& progress = nullptr);

// The optimum as a CellPattern (piecewise-linear curves, period = the
// super-cell, next_offset = r Delta, variants swapped for odd offsets).
CellPattern GeneralCellPattern(const GeneralResult& result);

// A human-readable description of the topology and the optimum (knots).
std::string DescribeGeneral(const GeneralResult& result);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_GENERAL_SEARCH_H_
