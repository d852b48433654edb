#include "shellspace/workflows/regress.h"

#include <cmath>
#include <utility>

#include "shellspace/reports/path_reports.h"

namespace shellspace {
namespace workflows {

std::string SplineShortfall(const std::string& verb,
                            const shellspace::SplineResult& result,
                            double tolerance) {
  if (result.converged) return "";
  if (!result.evaluated) {
    return verb + ": stopped before the first evaluation of F_K finished";
  }
  return verb + ": relative gradient " +
         ShortNumber(result.relative_gradient_norm) + " above the tolerance " +
         ShortNumber(tolerance) + ", no function-tolerance stop, after " +
         std::to_string(result.iterations) + " L-BFGS iterations (" +
         ceres::TerminationTypeToString(result.summary.termination_type) + ")";
}

RegressResult RunRegress(const RegressOptions& options) {
  if (!(options.sigma >= 0) || !std::isfinite(options.sigma)) {
    throw InputError("regress: sigma must be >= 0, got " +
                     std::to_string(options.sigma));
  }
  RegressResult result;
  result.reference = options.reference;
  result.material = options.material;
  result.sigma = options.sigma;
  const ShellSpace space(options.reference, options.topology,
                         options.material.material);
  SplineSettings settings = options.settings;
  const StopRecorder stop(&settings.stop);
  result.spline = SolveRegression(space, options.inputs, options.at,
                                  options.steps, options.sigma, {}, settings);
  result.stopped = stop.stopped();
  result.energy_split = PathEnergySplit(space, result.spline.path);
  std::vector<std::string> failures;
  const std::string shortfall = SplineShortfall(
      "regress", result.spline, options.settings.gradient_tolerance);
  if (!shortfall.empty()) failures.push_back(shortfall);
  result.status = StatusOf(std::move(failures), result.stopped);
  return result;
}

JsonObject ToJson(const RegressResult& result, double seconds) {
  JsonObject head;
  head.Add("sigma", result.sigma)
      .Add("energy_split", EnergySplitJson(result.energy_split));
  return SplineJson(std::move(head), result.spline, seconds);
}

}  // namespace workflows
}  // namespace shellspace
