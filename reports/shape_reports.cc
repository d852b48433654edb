#include "shellspace/reports/shape_reports.h"

namespace shellspace {

JsonObject EnergyJson(const DeformationEnergy& energy,
                      const ShellMaterial& material) {
  JsonObject json;
  json.Add("membrane", energy.membrane)
      .Add("bending", energy.bending)
      .Add("total", energy.total)
      .Add("mu", material.mu)
      .Add("lambda", material.lambda)
      .Add("eta", material.eta);
  return json;
}

JsonObject MeanJson(const ElasticMeanResult& result, int inputs,
                    const std::vector<std::string>& far_inputs) {
  const double relative =
      result.initial_gradient_norm > 0
          ? result.gradient_norm / result.initial_gradient_norm
          : 0.0;
  JsonObject json;
  json.Add("energy", result.energy)
      .Add("energies", result.energies)
      .Add("far_inputs", far_inputs)
      .Add("inputs", inputs)
      .Add("iterations", result.lm_iterations + result.newton_iterations)
      .Add("lm_iterations", result.lm_iterations)
      .Add("newton_iterations", result.newton_iterations)
      .Raw("stages", JsonObject()
                         .Add("lm_iterations", result.lm_iterations)
                         .Add("newton_steps", result.newton_iterations)
                         .str())
      .Add("newton_fell_back", result.newton_fell_back)
      .Add("initial_gradient_norm", result.initial_gradient_norm)
      .Add("final_gradient_norm", result.gradient_norm)
      .Add("relative_gradient_norm", relative)
      .Add("converged", result.converged);
  return json;
}

}  // namespace shellspace
