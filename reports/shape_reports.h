// The summaries of the verbs on single shapes (`energy`, `mean`) as JSON
// objects, built from the library's own results. The CLI prints them with
// --json; the Python module returns them as dicts (python/).
#ifndef SHELLSPACE_REPORTS_SHAPE_REPORTS_H_
#define SHELLSPACE_REPORTS_SHAPE_REPORTS_H_

#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/statistics/elastic_mean.h"

namespace shellspace {

// W[reference, deformed]: membrane (W_mem), bending (W_bend, without eta),
// total (W_mem + eta W_bend), mu, lambda, eta.
JsonObject EnergyJson(const DeformationEnergy& energy,
                      const ShellMaterial& material);

// An elastic mean of `inputs` shapes: energy (sum_i W[S_i, mean]), energies,
// far_inputs (the names given), inputs, iterations (LM + Newton),
// lm_iterations, newton_iterations, stages {lm_iterations, newton_steps},
// newton_fell_back, initial_gradient_norm, final_gradient_norm,
// relative_gradient_norm, converged.
JsonObject MeanJson(const ElasticMeanResult& result, int inputs,
                    const std::vector<std::string>& far_inputs);

}  // namespace shellspace

#endif  // SHELLSPACE_REPORTS_SHAPE_REPORTS_H_
