// The summaries of the path verbs (`geodesic`, `log`, `shoot`, `transport`,
// `spline`, `regress`, `demo`) as JSON objects, built from the library's own
// results (nothing is recomputed here). The CLI prints them with --json; the
// Python module returns them as dicts (python/). Keys of each object are
// listed above its function.
#ifndef SHELLSPACE_REPORTS_PATH_REPORTS_H_
#define SHELLSPACE_REPORTS_PATH_REPORTS_H_

#include <ceres/solver.h>

#include <string>
#include <vector>

#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/shape_comparison.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/splines/spline_initial_path.h"

namespace shellspace {

// LM iterations of a Ceres solve, without Ceres' iteration 0 (the initial
// evaluation).
int LmIterations(const ceres::Solver::Summary& summary);

// The membrane / bending split of the path energy of the frames s_0..s_K
// of `path` in `space`: {"membrane": K sum_k W_mem[s_k-1, s_k], "bending":
// K sum_k eta W_bend[s_k-1, s_k] (eta included, so membrane + bending =
// E_K), "bending_share": bending / (membrane + bending) (0 for E_K = 0)}.
// Frames with a degenerate triangle give InputError. Costs one energy
// evaluation per step.
JsonObject PathEnergySplitJson(const ShellSpace& space, const ShellPath& path);

// The objects object(item) over `items` (object: item -> JsonObject), in
// order: a JSON array for JsonObject::Add.
template <class T, class ToObject>
std::vector<JsonObject> JsonArrayOf(const std::vector<T>& items,
                                    ToObject object) {
  std::vector<JsonObject> objects;
  for (const T& item : items) objects.push_back(object(item));
  return objects;
}

// The stages of a geodesic solve, one object each: method
// ("levenberg-marquardt" or "newton"), iterations, final_gradient_norm,
// termination.
std::vector<JsonObject> GeodesicStages(const GeodesicResult& result);

// The EXP steps of a shot, one object each: method ("newton" or
// "levenberg-marquardt": the solver that produced the shape), solved
// (relative_residual <= kExpStepAcceptance), newton_steps, lm_iterations,
// iterations (their sum), residual (max |F|), relative_residual (max |F| /
// max |D_2 W|), termination (ExpStepTermination).
std::vector<JsonObject> ExpStepStages(const ShootResult& result);

// An EXP step's outcome in words: "solved (" or "not solved (", then the
// method that produced the shape and its solver's own message, ")". Ceres'
// termination type is not used: an LM fallback that stops at its function
// tolerance reports CONVERGENCE though F = 0 is not solved.
std::string ExpStepTermination(const ExpStepResult& step);

// "newton" or "levenberg-marquardt".
const char* ExpMethodName(ExpStepResult::Method method);

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
// newton_steps, newton_seconds, factorizations,
// time_coupled_factorizations (of them with the time-coupled
// preconditioner), cg_iterations, linear_solver, cg_not_converged,
// newton_shifted_steps (Newton steps from H + lambda I), step_energy_ratio
// (max / min step energy), uneven_steps (ratio > kUnevenStepEnergyRatio),
// smallest_face_area_ratio / _shape / _face (SmallestFaceAreaRatio),
// collapsing_faces (ratio < kCollapsingFaceAreaRatio), frames.
JsonObject GeodesicJson(const GeodesicResult& result);

// How a geodesic's initial path was made (InitialPathReport) and the check
// of a prolongated path (ProlongationCheck), as JSON objects.
JsonObject InitialPathJson(const InitialPathReport& init);
JsonObject ProlongationJson(const ProlongationCheck& check);

// The levels of a multiresolution solve (a JSON array: coarsest first; the
// last is the input mesh), one object each: vertices, faces, iterations,
// path_energy, final_gradient_norm, converged, seconds.
std::vector<JsonObject> MultiresolutionJson(
    const MultiresolutionResult& result);

// A shot (ShootWithReport): path_energy, step_energies, iterations (Newton
// steps and LM iterations of every EXP step), max_exp_residual, converged
// (every EXP step solved), max_relative_residual, stages (the EXP steps),
// frames.
JsonObject ShootJson(const ShootResult& result);

// A parallel transport: variation_max_norms (max |xi_k| per frame),
// exp_residuals (per rung), converged (every rung solved), iterations (Newton
// steps and LM iterations of every rung), rungs (per rung: rung, solved,
// relative_residual, method, epsilon_divisor (the rung was solved at
// epsilon / divisor and scaled back), newton_steps, lm_iterations),
// epsilon, frames.
JsonObject TransportJson(const TransportResult& result, double epsilon);

// A spline or regression solve, appended to `head` (the verb's own keys):
// spline_energy (F_K), data_energy, objective, iterations (L-BFGS, without
// Ceres' iteration 0), lbfgs_rounds, initial_gradient_norm, final_gradient_norm,
// relative_gradient_norm, gradient_criterion_met, converged
// (SplineResult::converged: the outer solver met its criterion; for a path
// that is the LΘA spline alone the caller sets it to "every frame's
// reconstruction converged"), termination ("not optimised" if no iteration
// ran), then `seconds` and frames.
JsonObject SplineJson(JsonObject head, const SplineResult& result,
                      double seconds);

// The LΘA spline's reconstructions (LThetaSplineReport): frames_solved,
// lm_iterations (all frames), unconverged_frames (indices k), and the
// seconds of the quantities' splines and of the reconstructions.
JsonObject LThetaSplineJson(const LThetaSplineReport& report);

// What making a spline's initial path took, added to `head`: init
// ("ltheta" or "geodesic"), then for the LΘA spline ltheta_seconds and ltheta
// (LThetaSplineJson), for the piecewise geodesic init_seconds and
// init_segments (an array: from, to, path_energy, iterations, converged per
// segment).
JsonObject& AddSplineInitJson(JsonObject& head,
                              const SplineInitialPath& initial);

// The summary of `compare` (CompareShapes and its verdict): frames,
// max_distance, mean_distance, diameter, relative_max_distance,
// frame_max_distance, frame_mean_distance, then path_energy_a,
// path_energy_b, relative_energy_difference (paths) or energy_a_to_b
// (single shells), tolerance, energy_tolerance, equal.
JsonObject ComparisonJson(const ShapeComparison& comparison, double tolerance,
                          double energy_tolerance);

}  // namespace shellspace

#endif  // SHELLSPACE_REPORTS_PATH_REPORTS_H_
