#include "shellspace/workflows/common.h"

#include <cstdio>
#include <utility>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/reports/shape_reports.h"

namespace shellspace {
namespace workflows {

EnergySplit PathEnergySplit(const ShellSpace& space,
                            const std::vector<Positions>& path) {
  EnergySplit split;
  const double steps = path.size() > 1 ? path.size() - 1.0 : 0.0;
  for (size_t k = 1; k < path.size(); ++k) {
    const DeformationEnergy w =
        EvaluateDeformationEnergy(space, path[k - 1], path[k]);
    split.membrane += steps * w.membrane;
    split.bending += steps * (w.total - w.membrane);
  }
  return split;
}

EnergySplit MeanEnergySplit(const ShellSpace& space, const Positions& mean,
                            const std::vector<Positions>& shapes) {
  EnergySplit split;
  for (const Positions& shape : shapes) {
    // The inputs are the references: W[S_i, mean], as the mean's objective.
    const DeformationEnergy w = EvaluateDeformationEnergy(space, shape, mean);
    split.membrane += w.membrane;
    split.bending += w.total - w.membrane;
  }
  return split;
}

JsonObject MaterialChoiceJson(const MaterialChoice& choice,
                              const Mesh& reference) {
  return MaterialJson(choice.material, reference, choice.eta_absolute);
}

JsonObject EnergySplitJson(const EnergySplit& split) {
  return shellspace::EnergySplitJson(split.membrane, split.bending);
}

StopRecorder::StopRecorder(StopToken* token)
    : flag_(std::make_shared<std::atomic<bool>>(false)) {
  if (!token->stop_possible()) return;
  std::shared_ptr<std::atomic<bool>> flag = flag_;
  *token = StopToken([caller = *token, flag] {
    if (!caller.stop_requested()) return false;
    flag->store(true);
    return true;
  });
}

std::string ShortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

}  // namespace workflows
}  // namespace shellspace
