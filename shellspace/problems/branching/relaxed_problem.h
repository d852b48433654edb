// The relaxed functional on a RelaxedGrid as a Ceres least-squares problem, its
// energy split, and the sparse LM solve with continuation in the interface
// width delta (docs/math.md, "Branching: the Kohn–Müller model").
//
//   E_delta[u] = (1/H) \int u_x^2 + (3 eps / 4) (delta u_yy^2
//                + (1 - u_y^2)^2 / delta) dx dy      (energy per unit height)
//
// discretised as the sum of squares of ElasticCostFunction (x-edges),
// GradientCostFunction (nodes) and DoubleWellCostFunction (y-edges); see
// relaxed_grid.h for the weights. u = 0 on the austenite row i = 0 (constant
// parameter blocks), periodic in y.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_RELAXED_PROBLEM_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_RELAXED_PROBLEM_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ceres/ceres.h>

#include "shellspace/models/branching/relaxed_grid.h"
#include "shellspace/runtime/stop_token.h"

namespace shellspace::branching {

// Energy per unit height, split. interfacial = gradient + well (the diffuse
// counterpart of the sharp (eps/H) \int TV_y(u_y) dx).
struct RelaxedEnergy {
  double elastic = 0.0;
  double gradient = 0.0;
  double well = 0.0;
  double interfacial() const { return gradient + well; }
  double total() const { return elastic + gradient + well; }
};

// Evaluates the discrete energy directly (no Ceres), term by term.
RelaxedEnergy EvaluateRelaxedEnergy(const RelaxedField& field, double epsilon,
                                    double delta);

// Adds all residual blocks of E_delta for `field` to `problem` (the nodes of
// field.u are the parameter blocks, size 1; row 0 is set constant). The
// field must outlive the problem and must not be resized.
void AddRelaxedResiduals(RelaxedField* field, double epsilon, double delta,
                         ceres::Problem* problem);

struct RelaxedSolveOptions {
  // Interface widths of the continuation, solved in order (last = target).
  std::vector<double> deltas;
  int max_iterations = 200;  // per continuation stage
  int num_threads = 1;
  double function_tolerance = 1e-9;
  // Called after every LM iteration (progress output); may be empty.
  std::function<void(double delta, int iteration, double energy)> progress;
  // Asked after every LM iteration (as SolverSettings::stop): a stop ends
  // the stage at its best iterate and the continuation after it.
  StopToken stop;
};

struct RelaxedStage {
  double delta = 0.0;
  int iterations = 0;
  double seconds = 0.0;
  RelaxedEnergy energy;
  std::string termination;  // Ceres' termination, or "COLLAPSED"
  double max_slope = 0.0;   // max |u_y| over the field after the stage
  bool retried = false;     // re-solved from the stage's start at delta / 2
};

// max |u_y| (staggered slopes, rows i >= 1).
double MaxSlope(const RelaxedField& field);

// A stage collapsed when max |u_y| < kCollapsedSlope: the pattern has
// decayed to u ~ 0 (energy ~ 3 eps L / (4 delta), the saddle of the double
// well, from which the next stage cannot leave).
constexpr double kCollapsedSlope = 0.5;

// Levenberg–Marquardt, SPARSE_NORMAL_CHOLESKY (SuiteSparse), one stage per
// delta. Returns one record per stage; `field` holds the final minimiser.
// A stage that collapses (see above) is re-solved from its own start field
// with half its width (recorded with retried = true and the smaller delta)
// while that stays >= the final width; a collapse at the final width ends
// the continuation with termination "COLLAPSED" (the grid / width cannot
// hold the pattern; the caller reports it).
std::vector<RelaxedStage> SolveRelaxed(RelaxedField* field, double epsilon,
                                       const RelaxedSolveOptions& options);

// Continuation schedule: `steps` widths from `factor^(steps-1) delta` down to
// delta (geometric), e.g. steps = 3, factor = 2: 4 delta, 2 delta, delta.
std::vector<double> ContinuationDeltas(double delta, int steps,
                                       double factor = 2.0);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_RELAXED_PROBLEM_H_
