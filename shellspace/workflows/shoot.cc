#include "shellspace/workflows/shoot.h"

#include <string>
#include <utility>

#include "shellspace/reports/path_reports.h"

namespace shellspace {
namespace workflows {

ShootResult RunShoot(const ShootOptions& options) {
  if (options.steps < 1) {
    throw InputError("shoot: the number of steps K must be at least 1, got " +
                     std::to_string(options.steps));
  }
  ShootResult result;
  result.first = options.first;
  result.material = options.material;
  const ShellSpace space(options.first, options.topology,
                         options.material.material);
  SolverSettings settings = options.settings;
  const StopRecorder stop(&settings);
  result.shot = ShootWithReport(
      space, options.first.positions, options.second, options.steps,
      options.backward ? StepDirection::kBackward : StepDirection::kForward,
      options.fixed_vertices, settings);
  result.stopped = stop.stopped();
  std::vector<std::string> failures;
  for (size_t i = 0; i < result.shot.exp_steps.size(); ++i) {
    const ExpStepResult& step = result.shot.exp_steps[i];
    if (step.solved) continue;
    failures.push_back("EXP step " + std::to_string(i + 1) +
                       " not solved: relative residual " +
                       ShortNumber(step.relative_residual) + " > " +
                       ShortNumber(kExpStepAcceptance) + " (" +
                       ExpMethodName(step.method) + ")");
  }
  result.energy_split = PathEnergySplit(space, result.shot.path);
  result.status = StatusOf(std::move(failures), result.stopped);
  return result;
}

JsonObject ToJson(const ShootResult& result) {
  JsonObject json = ShootJson(result.shot);
  json.Add("energy_split", EnergySplitJson(result.energy_split));
  return json;
}

}  // namespace workflows
}  // namespace shellspace
