// Continuation in the load: a globalisation of one EXP step's Newton method.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_EXP_STEP_CONTINUATION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_EXP_STEP_CONTINUATION_H_

#include <string>

#include "shellspace/problems/calculus/exp_step_newton.h"

namespace shellspace {

// What SolveExpStepByContinuation did.
struct ExpContinuationReport {
  bool solved = false;   // F(s) = 0 reached at load 1 (max |F| <= accept)
  double load = 0;       // the last load t whose root was found
  int substeps = 0;      // roots found, at t in (0, 1]
  int newton_steps = 0;  // Newton steps over every attempt
  double final_residual = 0;  // max |F| at *s (load 1) if solved
  std::string stop_reason;
};

// How far the continuation goes: Newton's tolerance at load 1 and the
// round-off floor accepted there (absolute, max |F|, as ExpNewtonStopping),
// the tolerance of the roots on the way, and the budget.
struct ExpContinuationSettings {
  double tolerance = 0;
  double accept = 0;
  double intermediate_tolerance = 0;
  int max_substeps = 48;       // attempts, successful or not
  int max_newton_steps = 120;  // over every attempt
  double first_load_step = 0.25;
  double min_load_step = 1.0 / 256;
};

// Solves F(s) = c + D_fixed W = 0 (exp_step_newton.h) by following the roots
// of F_t(s) = t c + D_fixed W, t from 0 to 1: a continuation in the load.
// At t = 0 the fixed shell b itself is the root (W[b, .] and W[., b] are
// smallest, 0, at b). Each increase of t starts Newton from the secant
// extrapolation of the last two roots (from b itself at the first: Newton's
// first step from there is the tangent of the root curve). A load step
// whose Newton fails (8 steps, or a degenerate predictor) is halved, down
// to `min_load_step`; one that succeeds in at most 3 steps doubles the next,
// one that needs more than 5 halves it. Where the plain guess m = 2 b - a
// is far from the root (a step that folds a sliver), Newton from it leaves
// the basin, while every root on the way is near its predictor. Masked
// vertices move with the load, b + t (m - b), so that the mask rows are
// the caller's at t = 1. On success *s is the root at load 1; otherwise *s
// is left unchanged.
ExpContinuationReport SolveExpStepByContinuation(
    const ExpStepEquation& equation, const Positions& plain_guess,
    const ExpContinuationSettings& settings, Positions* s);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_EXP_STEP_CONTINUATION_H_
