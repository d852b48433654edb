#include "shellspace/workflows/transport.h"

#include <cmath>
#include <utility>

#include "shellspace/reports/path_reports.h"

namespace shellspace {
namespace workflows {

TransportResult RunTransport(const TransportOptions& options) {
  if (!(options.epsilon > 0) || !std::isfinite(options.epsilon)) {
    throw InputError("transport: epsilon must be > 0, got " +
                     std::to_string(options.epsilon));
  }
  if (options.path.size() < 2) {
    throw InputError("transport: the path needs at least 2 frames");
  }
  TransportResult result;
  result.first = options.first;
  result.material = options.material;
  result.epsilon = options.epsilon;
  const ShellSpace space(options.first, options.topology,
                         options.material.material);
  SolverSettings settings = options.settings;
  const StopRecorder stop(&settings);
  result.transport = ParallelTransport(
      space, options.path, options.variation - options.first.positions,
      options.epsilon, options.fixed_vertices, settings);
  result.stopped = stop.stopped();
  std::vector<std::string> failures;
  for (size_t k = 0; k < result.transport.rungs.size(); ++k) {
    const shellspace::TransportResult::Rung& rung = result.transport.rungs[k];
    const std::string name = "rung " + std::to_string(k + 1);
    if (!rung.solved) {
      failures.push_back(name + " not solved: EXP residual " +
                         ShortNumber(rung.relative_residual) + " > " +
                         ShortNumber(kExpStepAcceptance) +
                         " (also at epsilon / " +
                         std::to_string(rung.divisor) + ")");
    } else if (rung.divisor > 1) {
      result.warnings.push_back(name + " solved at epsilon / " +
                                std::to_string(rung.divisor) +
                                " and scaled back");
    }
  }
  result.energy_split = PathEnergySplit(space, result.transport.shapes);
  result.status = StatusOf(std::move(failures), result.stopped);
  return result;
}

JsonObject ToJson(const TransportResult& result) {
  JsonObject json = TransportJson(result.transport, result.epsilon);
  json.Add("energy_split", EnergySplitJson(result.energy_split));
  return json;
}

}  // namespace workflows
}  // namespace shellspace
