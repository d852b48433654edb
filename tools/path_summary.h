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

// The EXP steps of a shot, one object each: method "exp step",
// newton_steps, lm_iterations, iterations (their sum), residual (max |F|),
// termination.
std::vector<std::string> ExpStepStages(const ShootResult& result);

// Totals over the EXP steps of a shot: Newton steps plus LM iterations,
// every step converged, the largest residual max |F|.
struct ShootTotals {
  int iterations = 0;
  bool converged = true;
  double max_residual = 0;
};
ShootTotals TotalsOf(const ShootResult& result);

// A geodesic solve (SolveGeodesic, LogK): path_energy (E_K), step_energies,
// iterations (every LM stage and every Newton step), initial_gradient_norm,
// final_gradient_norm (after the last stage, max norm over the free
// coordinates), relative_gradient_norm (final / initial), converged (the
// stopping criterion was met), termination (of the last stage), stages,
// newton_steps, newton_seconds, factorizations, cg_iterations, frames.
JsonObject GeodesicJson(const GeodesicResult& result);

// A shot (ShootWithReport): path_energy, step_energies, iterations (Newton
// steps and LM iterations of every EXP step), max_exp_residual, converged
// (every EXP step converged), stages (the EXP steps), frames.
JsonObject ShootJson(const ShootResult& result);

// Writes shape_000.ply ... into the run's output directory and, if --png
// is set, adds the film strip to its outside files (tools/run_output.h).
void WritePathOutputs(RunDirectory* out, const Faces& faces,
                      const ShellPath& path);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_PATH_SUMMARY_H_
