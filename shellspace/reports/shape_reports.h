// The summaries of the verbs on single shapes and shape sets (`energy`,
// `mean`, `pca`) as JSON
// objects, built from the library's own results. The CLI prints them with
// --json; the Python module returns them as dicts (python/).
#ifndef SHELLSPACE_REPORTS_SHAPE_REPORTS_H_
#define SHELLSPACE_REPORTS_SHAPE_REPORTS_H_

#include <string>
#include <utility>
#include <vector>

#include "shellspace/cost_functions/edge_angle_bending.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"

namespace shellspace {

// W[reference, deformed]: membrane (W_mem), bending (W_bend, without eta),
// total (W_mem + eta W_bend), mu, lambda, eta.
JsonObject EnergyJson(const DeformationEnergy& energy,
                      const ShellMaterial& material);

// The edge-angle variant's W_bend (without eta): bending (phi fitted),
// reference_functional (the reference's own fitted curvature functional),
// the Levenberg-Marquardt iterations of each fit and their sum, converged
// (both fits).
JsonObject EdgeAngleBendingJson(const EdgeAngleBending& bending);

// An elastic mean of `inputs` shapes: energy (sum_i W[S_i, mean]), energies,
// far_inputs (the names given), inputs, iterations (LM + Newton),
// lm_iterations, newton_iterations, stages {lm_iterations, newton_steps},
// newton_fell_back, initial_gradient_norm, final_gradient_norm,
// relative_gradient_norm, converged.
// {"membrane", "bending", "bending_share": bending / (membrane + bending),
// 0 when both are 0}: the split of an energy whose bending part includes
// eta.
JsonObject EnergySplitJson(double membrane, double bending);

// The material of a run as resolved from its options: mu, lambda, eta,
// relative_eta (eta / area of the reference), eta_from ("absolute" when eta
// was given, else "relative"), reference_area, bending_model
// (cost_functions/shell/relative_bending_weight.h).
JsonObject MaterialJson(const ShellMaterial& material, const Mesh& reference,
                        bool eta_absolute);

JsonObject MeanJson(const ElasticMeanResult& result, int inputs,
                    const std::vector<std::string>& far_inputs);

// The first keys of a PCA summary, those of its elastic mean of `inputs`
// shapes: inputs, mean_energy, mean_iterations (LM), mean_newton_iterations,
// mean_gradient_norm.
JsonObject PcaMeanJson(int inputs, const ElasticMeanResult& mean);

// Shell PCA at an elastic mean of `inputs` shapes: the keys of PcaMeanJson,
// mean_relative_gradient_norm, mean_converged, mean_termination,
// displacement (the word given), log_steps, exp_steps (of `options`),
// eigenvalues, modes (mode pairs shot), failed_mode_shapes, far_inputs,
// amplitude.
JsonObject PcaJson(int inputs, const ElasticMeanResult& mean,
                   const std::string& displacement,
                   const ShellPcaOptions& options, const ShellPcaModel& shell,
                   int modes, const std::vector<std::string>& failed_shapes,
                   const std::vector<std::string>& far_inputs,
                   double amplitude);

// Adds the Procrustes baseline to a PCA summary: procrustes_eigenvalues,
// procrustes_modes.
void AddProcrustesJson(const ProcrustesPcaModel& model, int modes,
                       JsonObject* json);

// The Procrustes baseline of a PCA: adds it to the summary
// (AddProcrustesJson with the modes the model has, at most `modes`) and
// returns its shapes by the names the pca verb gives them (the CLI's file
// stems, the Python module's keys): procrustes_mean, then for J = 1, 2, ...
// procrustes_mode_J_minus and procrustes_mode_J_plus, the mean -/+
// `amplitude` standard deviations along mode J (ProcrustesModeShape).
std::vector<std::pair<std::string, Positions>> AddProcrustesBaseline(
    const ProcrustesPcaModel& model, int modes, double amplitude,
    JsonObject* json);

// The leave-one-out table as a JSON object: energy_order, vertex_error (the
// definitions), rows (per number of modes m), folds (per held-out input),
// seconds.
JsonObject LeaveOneOutJson(const LeaveOneOutTable& table);

}  // namespace shellspace

#endif  // SHELLSPACE_REPORTS_SHAPE_REPORTS_H_
