#include "shellspace/tools/path_summary.h"

#include <algorithm>

#include "shellspace/io/png_writer.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/shell_inputs.h"

namespace shellspace {
namespace {

const char* ExpMethodName(ExpStepResult::Method method) {
  return method == ExpStepResult::Method::kNewton ? "newton"
                                                  : "levenberg-marquardt";
}

}  // namespace

int LmIterations(const ceres::Solver::Summary& summary) {
  return std::max(0, static_cast<int>(summary.iterations.size()) - 1);
}

std::string JsonArray(const std::vector<std::string>& objects) {
  std::string out = "[";
  for (size_t i = 0; i < objects.size(); ++i) {
    out += (i ? ", " : "") + objects[i];
  }
  return out + "]";
}

std::vector<std::string> GeodesicStages(const GeodesicResult& result) {
  std::vector<std::string> stages;
  for (const GeodesicStage& stage : result.stages) {
    const bool newton = stage.method == GeodesicStage::Method::kNewton;
    stages.push_back(JsonObject()
                         .Add("method", newton ? "newton"
                                               : "levenberg-marquardt")
                         .Add("iterations", stage.iterations)
                         .Add("final_gradient_norm", stage.final_gradient)
                         .Add("termination", stage.termination)
                         .str());
  }
  return stages;
}

std::vector<std::string> ExpStepStages(const ShootResult& result) {
  std::vector<std::string> stages;
  for (const ExpStepResult& step : result.exp_steps) {
    const int lm = LmIterations(step.summary);
    stages.push_back(
        JsonObject()
            .Add("method", ExpMethodName(step.method))
            .Add("solved", step.solved)
            .Add("newton_steps", step.newton_steps)
            .Add("lm_iterations", lm)
            .Add("iterations", step.newton_steps + lm)
            .Add("residual", step.residual_norm)
            .Add("relative_residual", step.relative_residual)
            .Add("termination", ceres::TerminationTypeToString(
                                    step.summary.termination_type))
            .str());
  }
  return stages;
}

JsonObject GeodesicJson(const GeodesicResult& result) {
  const double relative = result.initial_gradient > 0
                              ? result.final_gradient / result.initial_gradient
                              : 0.0;
  JsonObject json;
  json.Add("path_energy", result.path_energy)
      .Add("step_energies", result.step_energies)
      .Add("iterations", result.iterations)
      .Add("initial_gradient_norm", result.initial_gradient)
      .Add("final_gradient_norm", result.final_gradient)
      .Add("relative_gradient_norm", relative)
      .Add("converged", result.converged)
      .Add("termination", result.stages.empty()
                              ? std::string("no unknowns")
                              : result.stages.back().termination)
      .Raw("stages", JsonArray(GeodesicStages(result)))
      .Add("newton_steps", result.newton.steps)
      .Add("newton_seconds", result.newton.seconds)
      .Add("factorizations", result.newton.factorizations)
      .Add("cg_iterations", result.newton.cg_iterations)
      .Add("linear_solver", result.newton.linear_solver.empty()
                                ? std::string("none")
                                : result.newton.linear_solver)
      .Add("cg_not_converged", result.newton.cg_not_converged)
      .Add("newton_shifted_steps", result.newton.shifted_steps)
      .Add("step_energy_ratio", result.step_energy_ratio)
      .Add("uneven_steps", result.uneven_steps)
      .Add("frames", static_cast<int>(result.path.size()));
  return json;
}

void CheckGeodesic(const GeodesicResult& result, const std::string& what,
                   RunStatus* status) {
  status->Require(result.converged,
                  what + ": |grad| " + Short(result.final_gradient) +
                      " above the target " + Short(result.gradient_target) +
                      " (tolerance x max(1, |grad_0|)) after " +
                      std::to_string(result.iterations) + " iterations (" +
                      (result.stages.empty() ? std::string("no stages")
                                             : result.stages.back().termination) +
                      ")");
  if (result.uneven_steps) {
    const auto [lo, hi] = std::minmax_element(result.step_energies.begin(),
                                              result.step_energies.end());
    status->Warn(what + ": step energies far from equal: max/min " +
                 Short(result.step_energy_ratio) + " (W of step " +
                 std::to_string(hi - result.step_energies.begin() + 1) +
                 " = " + Short(*hi) + ", of step " +
                 std::to_string(lo - result.step_energies.begin() + 1) +
                 " = " + Short(*lo) + "; a geodesic has equal steps)");
  }
}

ShootTotals TotalsOf(const ShootResult& result) {
  ShootTotals totals;
  for (const ExpStepResult& step : result.exp_steps) {
    totals.iterations += step.newton_steps + LmIterations(step.summary);
    totals.max_residual = std::max(totals.max_residual, step.residual_norm);
    totals.max_relative_residual =
        std::max(totals.max_relative_residual, step.relative_residual);
    totals.converged &= step.solved;
  }

  return totals;
}

JsonObject ShootJson(const ShootResult& result) {
  const ShootTotals totals = TotalsOf(result);
  JsonObject json;
  json.Add("path_energy", result.path_energy)
      .Add("step_energies", result.step_energies)
      .Add("iterations", totals.iterations)
      .Add("max_exp_residual", totals.max_residual)
      .Add("max_relative_residual", totals.max_relative_residual)
      .Add("converged", totals.converged)
      .Raw("stages", JsonArray(ExpStepStages(result)))
      .Add("frames", static_cast<int>(result.path.size()));
  return json;
}

void CheckShoot(const ShootResult& result, RunStatus* status) {
  for (size_t i = 0; i < result.exp_steps.size(); ++i) {
    const ExpStepResult& step = result.exp_steps[i];
    status->Require(step.solved,
                    "EXP step " + std::to_string(i + 1) +
                        " not solved: relative residual " +
                        Short(step.relative_residual) + " > " +
                        Short(kExpStepAcceptance) + " (" +
                        ExpMethodName(step.method) + ")");
  }
}

void WritePathOutputs(RunDirectory* out, const Faces& faces,
                      const ShellPath& path) {
  WriteFrames(out->staging(), faces, path);
  if (!FLAGS_png.empty()) {
    RenderOptions options;
    ValidateRenderOptions(options);
    out->Outside().Add(FLAGS_png,
                       EncodePng(RenderFilmStrip(path, faces, options)));
  }
}

}  // namespace shellspace
