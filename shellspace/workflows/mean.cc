#include "shellspace/workflows/mean.h"

#include <cstdio>
#include <utility>

#include "shellspace/reports/shape_reports.h"

namespace shellspace {
namespace workflows {

std::string InputName(const std::vector<std::string>& names, int i) {
  if (i < static_cast<int>(names.size())) return names[i];
  return "inputs[" + std::to_string(i) + "]";
}

std::string FarInputText(const ElasticMeanResult& mean, int i) {
  const double median = Median(mean.energies);
  char text[160];
  std::snprintf(text, sizeof(text),
                "W[S, mean] = %.4g, %.0f times the median %.4g",
                mean.energies[i], mean.energies[i] / median, median);
  return text;
}

std::string MeanFailure(const ElasticMeanResult& mean,
                        const std::string& what) {
  if (mean.converged) return "";
  return what + ": |grad| " + ShortNumber(mean.gradient_norm) +
         " above the target " + ShortNumber(mean.gradient_target) +
         " after " + std::to_string(mean.lm_iterations) + " LM + " +
         std::to_string(mean.newton_iterations) + " Newton iterations (" +
         mean.termination + ")";
}

MeanResult RunMean(const MeanOptions& options) {
  MeanResult result;
  result.reference = options.reference;
  result.material = options.material;
  result.inputs = static_cast<int>(options.shapes.size());
  const ShellSpace space(options.reference, options.topology,
                         options.material.material);
  SolverSettings settings = options.settings;
  const StopRecorder stop(&settings);
  result.mean = ComputeElasticMean(
      space, options.shapes, settings,
      options.initial_mean ? &*options.initial_mean : nullptr);
  result.stopped = stop.stopped();
  if (result.mean.summary.termination_type == ceres::FAILURE) {
    result.status = FailedStatus("elastic mean", result.mean.summary.message);
    return result;
  }
  result.far_input_indices = FarInputs(result.mean.energies);
  for (int i : result.far_input_indices) {
    result.far_inputs.push_back(InputName(options.names, i));
  }
  result.energy_split =
      MeanEnergySplit(space, result.mean.mean, options.shapes);
  std::vector<std::string> failures;
  if (!result.mean.converged) {
    failures.push_back(MeanFailure(result.mean, "elastic mean"));
  }
  result.status = StatusOf(std::move(failures), result.stopped);
  return result;
}

JsonObject ToJson(const MeanResult& result) {
  JsonObject json = MeanJson(result.mean, result.inputs, result.far_inputs);
  json.Add("energy_split", EnergySplitJson(result.energy_split));
  return json;
}

}  // namespace workflows
}  // namespace shellspace
