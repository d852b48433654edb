#include "shellspace/workflows/branching.h"

#include <cmath>
#include <utility>
#include <vector>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/reports/branching_reports.h"
#include "shellspace/geometry/mesh.h"

namespace shellspace {
namespace workflows {
void CheckBranchingSimulate(const BranchingSimulateOptions& options) {
  const branching::SimulationSettings& s = options.settings;
  if (s.delta > 0 && s.height / s.ny > s.delta / 2.0) {
    throw InputError("delta is not resolved: need height / ny <= delta / 2");
  }
  CheckSimulationSettings(s);
  branching::CheckExtrapolationCount(options.delta_extrapolation);
  const double nodes = (static_cast<double>(s.nx) + 1) * s.ny;
  CheckMemory(BranchingBytes(nodes),
              "nx " + std::to_string(s.nx) + ", ny " + std::to_string(s.ny) +
                  " (" + std::to_string(static_cast<long>(nodes)) + " nodes)",
              "16 MB + 3 KB x (nx + 1) x ny");
}

BranchingSimulateResult RunBranchingSimulate(
    const BranchingSimulateOptions& options) {
  using namespace branching;
  CheckBranchingSimulate(options);
  const SimulationSettings& s = options.settings;
  SimulationResult simulation = RunSimulation(s);
  if (const std::string why = SimulationBreakdown(simulation); !why.empty()) {
    throw InputError("branching simulate: " + why +
                     " (ny, delta, epsilon, length, height)");
  }
  std::optional<DeltaExtrapolation> extrapolation;
  const bool stopped = s.stop.stop_requested();
  if (options.delta_extrapolation >= 2 && !stopped) {
    extrapolation.emplace(ExtrapolateDelta(
        s, ExtrapolationWidths(simulation.delta, options.delta_extrapolation),
        options.on_width));
  }
  const DeltaExtrapolation* ex = extrapolation ? &*extrapolation : nullptr;
  JsonObject summary = SimulationJson(s, simulation, ex);
  // Asked again: a stop during the extrapolation counts too.
  SolveStatus status =
      StatusOf(SimulationFailures(s, simulation, ex, "lm_iterations"),
               s.stop.stop_requested());
  return BranchingSimulateResult{s, std::move(simulation),
                                 std::move(extrapolation), std::move(summary),
                                 std::move(status)};
}

BranchingConstructResult RunBranchingConstruct(
    const BranchingConstructOptions& options) {
  using namespace branching;
  if (!(options.epsilon > 0) || !(options.length > 0)) {
    throw InputError("epsilon and length must be > 0");
  }
  const std::string& family = options.family;
  if (family != "km" && family != "needle" && family != "lens" &&
      family != "general") {
    throw InputError("family must be km, needle, lens or general, got '" +
                     family + "'");
  }
  BranchingConstructResult result;
  if (family == "general") {
    const GeneralSearchOptions search = MakeGeneralSearchOptions(
        options.search_ratios, options.search_pairs, options.subintervals,
        options.search_starts, options.search_threads, options.search_filter);
    const GeneralConstruction& general = result.general.emplace(
        ConstructGeneral(search, options.search, options.on_topology));
    const GeneralResult& best = general.best;
    result.series = OptimalFreeLengths(best.A, best.B, best.topology.r,
                                       options.epsilon, options.length);
    result.summary = GeneralConstructionJson(
        best, result.series, options.epsilon, options.length, options.search,
        general.solves, general.seconds);
    return result;
  }
  if (options.search) throw InputError("search needs family general");
  const ConstructionResult& c = result.construction.emplace(ConstructFamily(
      family, options.epsilon, options.length, options.optimize));
  if (!std::isfinite(c.constant) || !std::isfinite(c.h0)) {
    throw InputError("branching construct: the construction is not finite "
                     "(constant " + std::to_string(c.constant) + ", h0 " +
                     std::to_string(c.h0) +
                     "): epsilon and length this far apart");
  }
  result.summary =
      ConstructionJson(c, options.epsilon, options.length, options.optimize);
  return result;
}

}  // namespace workflows
}  // namespace shellspace
