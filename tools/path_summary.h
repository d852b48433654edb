// The --json reports of the verbs, built from the library's own results
// (nothing is recomputed here), and the frame output of the path verbs.
#ifndef SHELLSPACE_TOOLS_PATH_SUMMARY_H_
#define SHELLSPACE_TOOLS_PATH_SUMMARY_H_

#include <ceres/solver.h>

#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/tools/run_output.h"
#include "shellspace/tools/run_status.h"

namespace shellspace {

// LM iterations of a Ceres solve, without Ceres' iteration 0 (the initial
// evaluation).
int LmIterations(const ceres::Solver::Summary& summary);

// A JSON array of already serialised objects.
std::string JsonArray(const std::vector<std::string>& objects);

// The stages of a geodesic solve, one object each: method
// ("levenberg-marquardt" or "newton"), iterations, final_gradient_norm,
// termination.
std::vector<std::string> GeodesicStages(const GeodesicResult& result);

// The EXP steps of a shot, one object each: method ("newton" or
// "levenberg-marquardt": the solver that produced the shape), solved
// (relative_residual <= kExpStepAcceptance), newton_steps, lm_iterations,
// iterations (their sum), residual (max |F|), relative_residual (max |F| /
// max |D_2 W|), termination.
std::vector<std::string> ExpStepStages(const ShootResult& result);

// Totals over the EXP steps of a shot: Newton steps plus LM iterations,
// every step converged, the largest residual max |F|.
struct ShootTotals {
  int iterations = 0;
  bool converged = true;  // every EXP step solved
  double max_residual = 0;
  double max_relative_residual = 0;
};
ShootTotals TotalsOf(const ShootResult& result);

// A geodesic solve (SolveGeodesic, LogK): path_energy (E_K), step_energies,
// iterations (every LM stage and every Newton step), initial_gradient_norm,
// final_gradient_norm (after the last stage, max norm over the free
// coordinates), relative_gradient_norm (final / initial), converged (the
// stopping criterion was met), termination (of the last stage), stages,
// newton_steps, newton_seconds, factorizations, cg_iterations,
// newton_shifted_steps (Newton steps from H + lambda I), step_energy_ratio
// (max / min step energy), uneven_steps (ratio > kUnevenStepEnergyRatio),
// frames.
JsonObject GeodesicJson(const GeodesicResult& result);

// Records in `status` whether the geodesic met its stopping criterion
// (naming `what`, e.g. "geodesic") and warns about uneven step energies.
void CheckGeodesic(const GeodesicResult& result, const std::string& what,
                   RunStatus* status);

// A shot (ShootWithReport): path_energy, step_energies, iterations (Newton
// steps and LM iterations of every EXP step), max_exp_residual, converged
// (every EXP step solved), max_relative_residual, stages (the EXP steps),
// frames.
JsonObject ShootJson(const ShootResult& result);

// Records each unsolved EXP step of the shot in `status`.
void CheckShoot(const ShootResult& result, RunStatus* status);

// Writes shape_000.ply ... into the run's output directory and, if --png
// is set, adds the film strip to its outside files (tools/run_output.h).
void WritePathOutputs(RunDirectory* out, const Faces& faces,
                      const ShellPath& path);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_PATH_SUMMARY_H_
