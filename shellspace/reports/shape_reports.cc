#include "shellspace/reports/shape_reports.h"

#include <algorithm>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/reports/relative_gradient.h"

namespace shellspace {

JsonObject EnergyJson(const DeformationEnergy& energy,
                      const ShellMaterial& material) {
  JsonObject json;
  json.Add("membrane", energy.membrane)
      .Add("bending", energy.bending)
      .Add("total", energy.total)
      .Add("mu", material.mu)
      .Add("lambda", material.lambda)
      .Add("eta", material.eta)
      .Add("bending_share",
           energy.total > 0 ? (energy.total - energy.membrane) / energy.total
                            : 0.0);
  return json;
}

JsonObject EdgeAngleBendingJson(const EdgeAngleBending& bending) {
  JsonObject json;
  json.Add("bending", bending.energy)
      .Add("reference_functional", bending.reference.energy)
      .Add("reference_iterations", bending.reference.iterations)
      .Add("deformed_iterations", bending.deformed.iterations)
      .Add("iterations", bending.reference.iterations + bending.deformed.iterations)
      .Add("converged", bending.converged);
  return json;
}

JsonObject EnergySplitJson(double membrane, double bending) {
  const double total = membrane + bending;
  return JsonObject()
      .Add("membrane", membrane)
      .Add("bending", bending)
      .Add("bending_share", total > 0 ? bending / total : 0.0);
}

JsonObject MaterialJson(const ShellMaterial& material, const Mesh& reference,
                        bool eta_absolute) {
  const double area = SurfaceArea(reference);
  JsonObject json;
  json.Add("membrane_law", MembraneLawName(material.membrane_law))
      .Add("mu", material.mu)
      .Add("lambda", material.lambda)
      .Add("eta", material.eta)
      .Add("relative_eta", material.eta / area)
      .Add("eta_from", eta_absolute ? "absolute" : "relative")
      .Add("reference_area", area)
      .Add("bending_model", BendingModelName(material.bending_model));
  return json;
}

JsonObject MeanJson(const ElasticMeanResult& result, int inputs,
                    const std::vector<std::string>& far_inputs) {
  const double relative =
      RelativeGradientNorm(result.gradient_norm, result.initial_gradient_norm);
  JsonObject json;
  json.Add("energy", result.energy)
      .Add("energies", result.energies)
      .Add("far_inputs", far_inputs)
      .Add("inputs", inputs)
      .Add("iterations", result.lm_iterations + result.newton_iterations)
      .Add("lm_iterations", result.lm_iterations)
      .Add("newton_iterations", result.newton_iterations)
      .Add("stages", JsonObject()
                         .Add("lm_iterations", result.lm_iterations)
                         .Add("newton_steps", result.newton_iterations))
      .Add("newton_fell_back", result.newton_fell_back)
      .Add("initial_gradient_norm", result.initial_gradient_norm)
      .Add("final_gradient_norm", result.gradient_norm)
      .Add("relative_gradient_norm", relative)
      .Add("gradient_target", result.gradient_target)
      .Add("converged", result.converged)
      .Add("termination", result.termination);
  return json;
}

namespace {

std::vector<double> ToVector(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

JsonObject PcaMeanJson(int inputs, const ElasticMeanResult& mean) {
  JsonObject json;
  json.Add("inputs", inputs)
      .Add("mean_energy", mean.energy)
      .Add("mean_iterations", mean.lm_iterations)
      .Add("mean_newton_iterations", mean.newton_iterations)
      .Add("mean_gradient_norm", mean.gradient_norm);
  return json;
}

JsonObject PcaJson(int inputs, const ElasticMeanResult& mean,
                   const std::string& displacement,
                   const ShellPcaOptions& options, const ShellPcaModel& shell,
                   int modes, const std::vector<std::string>& failed_shapes,
                   const std::vector<std::string>& far_inputs,
                   double amplitude) {
  JsonObject json = PcaMeanJson(inputs, mean);
  json.Add("mean_relative_gradient_norm",
           RelativeGradientNorm(mean.gradient_norm, mean.initial_gradient_norm))
      .Add("mean_converged", mean.converged)
      .Add("mean_termination", mean.termination)
      .Add("displacement", displacement)
      .Add("log_steps", options.steps)
      .Add("exp_steps", options.exp_steps)
      .Add("eigenvalues", ToVector(shell.eigenvalues))
      .Add("modes", modes)
      .Add("failed_mode_shapes", failed_shapes)
      .Add("far_inputs", far_inputs)
      .Add("amplitude", amplitude);
  return json;
}

void AddProcrustesJson(const ProcrustesPcaModel& model, int modes,
                       JsonObject* json) {
  json->Add("procrustes_eigenvalues", ToVector(model.eigenvalues))
      .Add("procrustes_modes", modes);
}

std::vector<std::pair<std::string, Positions>> AddProcrustesBaseline(
    const ProcrustesPcaModel& model, int modes, double amplitude,
    JsonObject* json) {
  const int pairs = std::min<int>(modes, static_cast<int>(model.modes.size()));
  std::vector<std::pair<std::string, Positions>> shapes = {
      {"procrustes_mean", model.mean}};
  for (int j = 0; j < pairs; ++j) {
    const std::string stem = "procrustes_mode_" + std::to_string(j + 1);
    shapes.emplace_back(stem + "_minus",
                        ProcrustesModeShape(model, j, -amplitude));
    shapes.emplace_back(stem + "_plus",
                        ProcrustesModeShape(model, j, amplitude));
  }
  AddProcrustesJson(model, pairs, json);
  return shapes;
}

JsonObject LeaveOneOutJson(const LeaveOneOutTable& table) {
  std::vector<JsonObject> rows;
  for (const LeaveOneOutRow& row : table.rows) {
    rows.push_back(
        JsonObject()
            .Add("modes", row.modes)
            .Add("shell_vertex_error", row.shell_vertex_error)
            .Add("shell_energy", row.shell_energy)
            .Add("procrustes_vertex_error", row.procrustes_vertex_error)
            .Add("procrustes_energy", row.procrustes_energy)
            .Add("shell_failed", row.shell_failed)
            .Add("procrustes_vertex_error_shell_folds",
                 row.procrustes_vertex_error_shell_folds)
            .Add("procrustes_energy_shell_folds",
                 row.procrustes_energy_shell_folds));
  }
  std::vector<JsonObject> folds;
  for (const LeaveOneOutFold& f : table.folds) {
    std::vector<int> shot_steps;
    std::vector<double> shot_drift;
    std::vector<int> shot_ok;  // 1: passed the safeguard
    for (const ExpShotReport& r : f.shell_shots) {
      shot_steps.push_back(r.steps);
      shot_drift.push_back(r.energy_drift);
      shot_ok.push_back(r.ok ? 1 : 0);
    }
    folds.push_back(
        JsonObject()
            .Add("held_out", f.held_out)
            .Add("mean_energy", f.mean_energy)
            .Add("mean_iterations", f.mean_iterations)
            .Add("mean_newton_iterations", f.mean_newton_iterations)
            .Add("mean_converged", f.mean_converged)
            .Add("log_iterations", f.log_iterations)
            .Add("shell_vertex_error", f.shell_vertex_error)
            .Add("shell_energy", f.shell_energy)
            .Add("procrustes_vertex_error", f.procrustes_vertex_error)
            .Add("procrustes_energy", f.procrustes_energy)
            .Add("shell_exp_steps", shot_steps)
            .Add("shell_exp_energy_drift", shot_drift)
            .Add("shell_exp_ok", shot_ok)
            .Add("seconds", f.seconds));
  }
  return JsonObject()
      .Add("energy_order", "W[truth, reconstruction]")
      .Add("vertex_error",
           "mean over vertices of |aligned reconstruction - truth|")
      .Add("rows", rows)
      .Add("folds", folds)
      .Add("seconds", table.seconds);
}

}  // namespace shellspace
