// The summaries of `branching simulate` and `branching construct` as JSON
// objects, built from the library's results (problems/branching/). The CLI
// prints them with --json and writes them as summary.json; the Python
// module returns them as dicts (python/).
#ifndef SHELLSPACE_REPORTS_BRANCHING_REPORTS_H_
#define SHELLSPACE_REPORTS_BRANCHING_REPORTS_H_

#include <string>
#include <vector>

#include "shellspace/io/json_writer.h"
#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/general_search.h"
#include "shellspace/problems/branching/self_similar_series.h"
#include "shellspace/problems/branching/simulation.h"

namespace shellspace {

// {elastic, interfacial, total}.
JsonObject BranchingEnergyJson(double elastic, double interfacial);

// A relaxed simulation with settings `s`: command, epsilon, length, height,
// nx, ny, grading, delta, init, periods, energy, energy_over_eps23_L13
// (E / (eps^2/3 L^1/3)), km_constant, iterations, seconds, stages (per
// continuation stage), converged, x and interfaces (interface counts per
// node row), and with `extrapolation` its DeltaExtrapolationJson last.
// converged: the last stage's LM met Ceres' convergence criterion and, with
// an extrapolation, every width of it converged (all_converged) -- what the
// front ends' verdicts judge (the CLI's exit 4, NotConvergedError).
JsonObject SimulationJson(
    const branching::SimulationSettings& s,
    const branching::SimulationResult& result,
    const branching::DeltaExtrapolation* extrapolation = nullptr);

// The verdicts behind SimulationJson's converged, one line each ("" for
// none): the last stage's ("the last stage ended NO_CONVERGENCE after 40
// LM iterations (LABEL 40 per stage)", LABEL naming the per-stage limit as
// the front end calls it) and the extrapolation's.
std::vector<std::string> SimulationFailures(
    const branching::SimulationSettings& s,
    const branching::SimulationResult& result,
    const branching::DeltaExtrapolation* extrapolation,
    const std::string& iterations_label);

// The delta -> 0 extrapolation: delta, ny, nx, constant (per width), widths
// (per width: delta, nx, ny, constant, elastic, interfacial, iterations,
// termination, converged, interfaces_far, interfaces_max, seconds),
// all_converged, monotone, linear_c0, linear_c1, linear_rms, (if fitted)
// quadratic_q0..q2, quadratic_rms, root_s0..s2, root_rms,
// extrapolated_constant (s0, else c0), extrapolation_error (the fits'
// spread, max(|s0 - q0|, |s0 - c0|)), and of the narrowest width's field x,
// interfaces (per node row) and count_steps [{x, outer, inner}] (x = L
// toward 0).
JsonObject DeltaExtrapolationJson(const branching::DeltaExtrapolation& ex);

// A construction of the km, needle or lens family: command, family,
// optimized, epsilon, length, constant, constant_free_lengths, parameters
// {r, h0, theta (lens: tau, a1, a2)}, A, B, energy, (km: A_zero_edge,
// constant_zero_edge), the closed-form constants and the ratios to them,
// (optimized: iterations, seconds, termination).
JsonObject ConstructionJson(const branching::ConstructionResult& result,
                            double epsilon, double length, bool optimized);

// The general family's best pattern `best` with its free-length series:
// command, family "general", search, epsilon, length, constant,
// constant_geometric_lengths, parameters (topology, needles, the first 12
// lengths), A, B, AB2, energy, the KM constants and ratios, solves, seconds.
JsonObject GeneralConstructionJson(const branching::GeneralResult& best,
                                   const branching::FreeLengthSeries& series,
                                   double epsilon, double length, bool search,
                                   int solves, double seconds);

}  // namespace shellspace

#endif  // SHELLSPACE_REPORTS_BRANCHING_REPORTS_H_
