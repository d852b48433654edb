// The branching workflows (the `branching simulate` and `branching
// construct` verbs, shellspace.branching_simulate and
// shellspace.branching_construct): from checked settings to the relaxed
// Kohn-Mueller field or the self-similar construction, their summaries
// (reports/branching_reports.h) and their status. The front ends keep the
// flags, the keywords, the progress lines and the files.
#ifndef SHELLSPACE_WORKFLOWS_BRANCHING_H_
#define SHELLSPACE_WORKFLOWS_BRANCHING_H_

#include <functional>
#include <optional>
#include <string>

#include "shellspace/io/json_writer.h"
#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/general_construction.h"
#include "shellspace/problems/branching/self_similar_series.h"
#include "shellspace/problems/branching/simulation.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct BranchingSimulateOptions {
  // The simulation's settings; settings.stop is the front end's stop
  // request, settings.progress its progress lines (both may be empty).
  branching::SimulationSettings settings;
  // Widths of the delta -> 0 extrapolation: 0 (none) or 2 ..
  // kMaxExtrapolationWidths; skipped once a stop was requested.
  int delta_extrapolation = 0;
  // Called after each width of the extrapolation (may be empty).
  std::function<void(const branching::DeltaWidth&)> on_width;
};

struct BranchingSimulateResult {
  branching::SimulationSettings settings;  // as run
  branching::SimulationResult simulation;
  std::optional<branching::DeltaExtrapolation> extrapolation;
  JsonObject summary;  // SimulationJson
  // kNotConverged when the last stage or a width of the extrapolation did
  // not converge (failures name the per-stage limit "lm_iterations").
  SolveStatus status;
};

// Throws InputError for settings the simulation refuses (a delta the grid
// does not resolve, CheckSimulationSettings, an extrapolation count out of
// range, a grid above the memory limit) and for a simulation that broke
// down (SimulationBreakdown), each naming the settings in the library's
// words (nx, ny, delta, epsilon, length, height).
BranchingSimulateResult RunBranchingSimulate(
    const BranchingSimulateOptions& options);

// The checks RunBranchingSimulate makes before it solves (the InputErrors
// above but the breakdown), for a front end that checks before it prepares
// its outputs.
void CheckBranchingSimulate(const BranchingSimulateOptions& options);

struct BranchingConstructOptions {
  double epsilon = 0, length = 0;
  std::string family = "km";  // km, needle, lens or general
  bool optimize = false;      // km, needle, lens: optimised from a start
  // general: the topology search (search) and its options
  // (MakeGeneralSearchOptions' values).
  bool search = false;
  std::string search_ratios = "2,3,4";
  int search_pairs = 2, subintervals = 3, search_starts = 1;
  int search_threads = 1;
  std::string search_filter;
  // general with search: called for each topology solved (may be empty).
  std::function<void(const branching::GeneralResult&)> on_topology;
};

struct BranchingConstructResult {
  // km, needle, lens: the construction; general: the best pattern, its
  // free-length series and the search's count of solves and seconds.
  std::optional<branching::ConstructionResult> construction;
  std::optional<branching::GeneralConstruction> general;
  branching::FreeLengthSeries series;  // general only
  JsonObject summary;  // ConstructionJson or GeneralConstructionJson
};

// Throws InputError for an epsilon or length that is not positive, an
// unknown family, a search without the general family, search options out
// of range, or a construction that is not finite.
BranchingConstructResult RunBranchingConstruct(
    const BranchingConstructOptions& options);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_BRANCHING_H_
