#include "shellspace/workflows/pca.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <utility>

#include "shellspace/reports/shape_reports.h"
#include "shellspace/workflows/mean.h"

namespace shellspace {
namespace workflows {
namespace {

void CheckOptions(const PcaOptions& options) {
  const int n = static_cast<int>(options.shapes.size());
  const int minimum = options.leave_one_out ? 3 : 2;
  if (n < minimum) {
    throw InputError("shapes needs at least " + std::to_string(minimum) +
                     " shells" +
                     (options.leave_one_out ? " with leave_one_out" : "") +
                     ", got " + std::to_string(n));
  }
  CheckPcaModeCount(options.modes, n, options.leave_one_out, "modes",
                    "leave_one_out");
  if (!(options.amplitude >= 0) || !std::isfinite(options.amplitude)) {
    throw InputError("amplitude must be >= 0");
  }
}

// The shapes mode_j_minus and mode_j_plus of the first result->shell_modes
// modes of `model` by EXP_K, each added to result->shapes, or named with its
// reason in failed_shapes where the shot fails; no new shot once `stop`
// has stopped.
void AddModeShapes(const ShellSpace& space, const ShellPcaModel& model,
                   const PcaOptions& options, const SolverSettings& inner,
                   const StopRecorder& stop, PcaResult* result) {
  for (int j = 0; j < result->shell_modes; ++j) {
    for (const double sign : {-1.0, 1.0}) {
      if (stop.stopped()) return;
      const std::string name =
          "mode_" + std::to_string(j + 1) + (sign < 0 ? "_minus" : "_plus");
      Positions shape;
      ExpShotReport shot;
      if (TryShellModeShape(space, model, j, sign * options.amplitude,
                            options.pca, inner, &shape, &shot)) {
        result->shapes.emplace_back(name, std::move(shape));
      } else {
        result->failed_shapes.push_back(name);
        result->failed_shape_reasons.push_back(shot.failure);
      }
    }
  }
}

// The Procrustes PCA of the inputs (the linear baseline) and its mean and
// mode shapes, added to result->shapes.
void AddProcrustesShapes(const PcaOptions& options, PcaResult* result) {
  result->procrustes = ComputeProcrustesPca(options.shapes);
  JsonObject unused;
  for (auto& shape : AddProcrustesBaseline(*result->procrustes, options.modes,
                                           options.amplitude, &unused)) {
    result->shapes.push_back(std::move(shape));
  }
}

// The leave-one-out table of the shell PCA (EvaluateLeaveOneOut), each
// mean warm-started from the mean of all inputs.
LeaveOneOutTable LeaveOneOut(const ShellSpace& space, const PcaOptions& options,
                             const SolverSettings& inner,
                             const ElasticMeanResult& mean) {
  LeaveOneOutOptions loo;
  loo.max_modes = options.modes;
  loo.pca = options.pca;
  loo.initial_mean = mean.mean;  // warm start; same minimiser
  loo.log = options.leave_one_out_log;
  return EvaluateLeaveOneOut(space, options.shapes, loo, inner);
}

// Seconds since `start` as text, for the progress lines only.
std::string SecondsSince(std::chrono::steady_clock::time_point start) {
  std::ostringstream text;
  text << std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                        start)
              .count();
  return text.str();
}

}  // namespace

const Positions* PcaResult::Shape(const std::string& name) const {
  for (const auto& [key, shape] : shapes) {
    if (key == name) return &shape;
  }
  return nullptr;
}

PcaResult RunPca(const PcaOptions& options) {
  CheckOptions(options);
  const auto clock = std::chrono::steady_clock::now();
  const auto seconds = [&clock] { return SecondsSince(clock); };
  const auto log = [&options](const std::string& line) {
    if (options.log) options.log(line);
  };
  PcaResult result;
  result.reference = options.reference;
  result.material = options.material;
  result.inputs = static_cast<int>(options.shapes.size());
  const ShellSpace space(options.reference, options.topology,
                         options.material.material);
  SolverSettings settings = options.settings;
  const StopRecorder stop(&settings);
  SolverSettings inner = settings;
  inner.progress = false;

  log("elastic mean of " + std::to_string(result.inputs) + " shells" +
      (options.initial_mean ? " from the given mean" : ""));
  result.mean = ComputeElasticMean(
      space, options.shapes, settings,
      options.initial_mean ? &*options.initial_mean : nullptr);
  if (result.mean.summary.termination_type == ceres::FAILURE) {
    result.status = FailedStatus("elastic mean", result.mean.summary.message);
    return result;
  }
  std::vector<std::string> failures;
  if (!result.mean.converged) {
    failures.push_back(MeanFailure(result.mean, "the elastic mean"));
  }
  result.shapes.emplace_back("mean", result.mean.mean);
  // A stop ends the run with the mean alone.
  const auto finish = [&](const char* phase) {
    result.stopped = stop.stopped();
    if (phase != nullptr) {
      result.stopped_in = phase;
      result.shapes.resize(1);
    }
    result.status = StatusOf(std::move(failures), result.stopped);
    return std::move(result);
  };
  if (stop.stopped()) return finish("mean");
  result.far_input_indices = FarInputs(result.mean.energies);
  for (int i : result.far_input_indices) {
    result.far_inputs.push_back(InputName(options.names, i));
  }
  log("elastic mean done (" + std::to_string(result.mean.lm_iterations) +
      " LM + " + std::to_string(result.mean.newton_iterations) +
      " Newton iterations, " + seconds() + " s); displacements (" +
      DisplacementKindName(options.pca.displacement) +
      ") and the Gram matrix");
  ShellPcaModel model = ComputeShellPca(space, result.mean.mean,
                                        options.shapes, options.pca, inner);
  if (stop.stopped()) return finish("displacements");
  result.shell_modes =
      std::min<int>(options.modes, static_cast<int>(model.modes.size()));
  log("shell PCA done (" + seconds() + " s); " +
      std::to_string(2 * result.shell_modes) + " mode shapes by EXP_K");
  AddModeShapes(space, model, options, inner, stop, &result);
  if (stop.stopped()) return finish("mode shapes");
  log("shell modes done");
  result.model = std::move(model);

  if (options.procrustes) AddProcrustesShapes(options, &result);
  if (options.leave_one_out) {
    result.leave_one_out = LeaveOneOut(space, options, inner, result.mean);
    if (stop.stopped()) {
      result.model.reset();
      result.procrustes.reset();
      result.leave_one_out.reset();
      return finish("leave-one-out");
    }
  }
  return finish(nullptr);
}

JsonObject ToJson(const PcaResult& result, const PcaOptions& options) {
  if (!result.stopped_in.empty() || !result.model) {
    JsonObject json = PcaMeanJson(result.inputs, result.mean);
    json.Add("modes", 0).Add("stopped_in", result.stopped_in);
    return json;
  }
  std::vector<std::string> failed_files;
  for (const std::string& name : result.failed_shapes) {
    failed_files.push_back(name + ".ply");
  }
  JsonObject json =
      PcaJson(result.inputs, result.mean,
              DisplacementKindName(options.pca.displacement), options.pca,
              *result.model, result.shell_modes, failed_files,
              result.far_inputs, options.amplitude);
  if (result.procrustes) {
    AddProcrustesJson(*result.procrustes,
                      std::min<int>(options.modes, static_cast<int>(
                                                       result.procrustes->modes
                                                           .size())),
                      &json);
  }
  if (result.leave_one_out) {
    json.Add("leave_one_out", LeaveOneOutJson(*result.leave_one_out));
  }
  return json;
}

}  // namespace workflows
}  // namespace shellspace
