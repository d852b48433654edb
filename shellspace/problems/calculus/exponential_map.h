// The discrete exponential map (docs/math.md, "Exponential map"): steps,
// geodesic shooting EXP_K, and the discrete logarithm LOG_K.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_EXPONENTIAL_MAP_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_EXPONENTIAL_MAP_H_

#include <ceres/solver.h>

#include <vector>

#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {

enum class StepDirection { kForward, kBackward };

// An EXP step is solved when max |F| <= kExpStepAcceptance times
// max |D_2 W[s_{k-1}, s_k]| (over the unknown vertices): the level Newton's
// round-off stall is accepted at.
inline constexpr double kExpStepAcceptance = 1e-8;

struct ExpStepResult {
  Positions shape;
  double residual_norm = 0;  // max-norm of F at the result
  // max |D_2 W[s_{k-1}, s_k]| over the unknown vertices (forward; backward
  // max |D_1 W[s_k, s_{k+1}]|): the scale of F.
  double residual_scale = 0;
  double relative_residual = 0;  // residual_norm / residual_scale
  // relative_residual <= kExpStepAcceptance: F = 0 was solved. False: no
  // root was found from the initial guesses (the result is the best point
  // LM reached).
  bool solved = false;
  enum class Method { kNewton, kLevenbergMarquardt };
  Method method = Method::kNewton;  // the solver that produced `shape`
  int newton_steps = 0;      // Newton steps on F (exp_step_newton.h)
  // Load steps of the continuation (exp_step_continuation.h) if Newton from
  // the initial guess did not converge (0: not needed or none found).
  int continuation_substeps = 0;
  int lm_iterations = 0;     // LM iterations of the fallback (0: none)
  // The LM solve, if Newton did not converge; else a summary with
  // termination CONVERGENCE, no iterations and message "Newton on F: ...".
  ceres::Solver::Summary summary;
};

// One step of the discrete geodesic through (a, b) beyond b:
//  forward  (a, b) = (s_{k-1}, s_k): s_{k+1} with
//           D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}] = 0;
//  backward (a, b) = (s_{k+1}, s_k): s_{k-1} with
//           D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}] = 0.
// Solved by Newton's method on F with the exact Jacobian and sparse LU
// (exp_step_newton.h) to max |F| <= 1e-11 max |D_2 W[s_{k-1}, s_k]| (or
// kExpStepAcceptance = 1e-8 if round-off stalls it; at most 20 Newton
// steps), else by Newton along a continuation in the load from b
// (exp_step_continuation.h), else as least squares of the per-vertex
// residuals F_v (cost_functions/gradient_field_residual.h) by sparse LM,
// from 2 b - a (or b if that has degenerate triangles), at most
// settings.max_iterations LM iterations (0: no LM fallback; the initial
// guess is returned unsolved, method kNewton); `solved` says whether the
// result reaches kExpStepAcceptance. Vertices in `fixed_vertices` are not
// unknowns: they move on linearly, to 2 b - a (their positions in b if the
// mask does not move), as geodesic interpolation moves them (linear
// interpolation of the end shapes), so that shooting from (s_0, s_1) of a
// masked geodesic continues its mask; without them the rigid gauge is pinned.
// `alternative_start` (optional): a second initial guess, used instead if
// its residual max |F| is smaller (its masked vertices are overwritten).
ExpStepResult ExpStep(const ShellSpace& space, const Positions& a,
                      const Positions& b, StepDirection direction,
                      const std::vector<int>& fixed_vertices,
                      const SolverSettings& settings,
                      const Positions* alternative_start = nullptr);

// Geodesic shooting: from (s_0, s_1) computes s_2 .. s_steps by forward
// steps (backward: from (s_0, s_1) the shapes s_{-1} .. s_{-(steps-1)}
// before s_0). Returns the whole path in time order (steps + 1 shapes).
ShellPath Shoot(const ShellSpace& space, const Positions& s0,
                const Positions& s1, int steps, StepDirection direction,
                const std::vector<int>& fixed_vertices,
                const SolverSettings& settings,
                std::vector<ceres::Solver::Summary>* summaries = nullptr);

// Geodesic shooting with its report: the path of Shoot, every EXP step's
// result (in the order computed; `shape` is left empty, the shapes are in
// `path`) and the path energy of the result.
struct ShootResult {
  // Time order, steps + 1 shapes; fewer if settings.stop ended the shot
  // (the steps completed before it, SolverSettings::stop).
  ShellPath path;
  std::vector<ExpStepResult> exp_steps;
  double path_energy = 0;              // E_K of `path`, K = steps
  std::vector<double> step_energies;   // W[s_{k-1}, s_k], time order
  bool stopped = false;  // settings.stop ended the shot before step K
};
ShootResult ShootWithReport(const ShellSpace& space, const Positions& s0,
                            const Positions& s1, int steps,
                            StepDirection direction,
                            const std::vector<int>& fixed_vertices,
                            const SolverSettings& settings);

// EXP_K(v) at s_0: s_1 = s_0 + v/K, then K - 1 forward steps; returns s_K.
Positions ExpK(const ShellSpace& space, const Positions& s0,
               const Positions& variation, int steps,
               const std::vector<int>& fixed_vertices,
               const SolverSettings& settings);

// LOG_K of a discrete geodesic (s_0, ..., s_K): K (s_1 - s_0) (docs/math.md,
// "Logarithm").
Positions LogOfGeodesic(const ShellPath& geodesic);

// LOG_K(a -> b) = K (s_1 - a) for the discrete geodesic (a, s_1, ..., b),
// solved from `initial` (K + 1 shapes, its ends replaced by a and b) if
// given, else from the linear path.
Positions LogK(const ShellSpace& space, const Positions& a, const Positions& b,
               int steps, const std::vector<int>& fixed_vertices,
               const SolverSettings& settings,
               GeodesicResult* geodesic = nullptr,
               const ShellPath* initial = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_EXPONENTIAL_MAP_H_
