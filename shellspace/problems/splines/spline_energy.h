// The time-discrete spline energy and the regression functional as a
// ceres::FirstOrderFunction with the adjoint gradient (docs/math.md,
// "Riemannian splines" and "Regression").
#ifndef SHELLSPACE_PROBLEMS_SPLINES_SPLINE_ENERGY_H_
#define SHELLSPACE_PROBLEMS_SPLINES_SPLINE_ENERGY_H_

#include <ceres/first_order_function.h>

#include <atomic>
#include <memory>
#include <utility>
#include <vector>

#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {

class PathHessianAssembler;

// One observation of the regression data term W[shape, s_index].
struct SplineDatum {
  Positions shape;
  int index = 0;
};

// The path and which of its shapes are unknowns.
//  - Non-periodic: shapes s_0 .. s_K, midpoint terms k = 1 .. K-1.
//  - Periodic: shapes s_0 .. s_{K-1}, midpoint terms k = 0 .. K-1 with
//    neighbours taken mod K.
struct SplineSpec {
  int steps = 0;  // K
  bool periodic = false;
  ShellPath initial;          // K + 1 (or K if periodic) shapes
  std::vector<char> is_free;  // one flag per shape; fixed shapes are data
  std::vector<SplineDatum> data;
  double sigma = 1.0;  // weight of F_K
};

// Where the evaluations of a SplineObjective spend their time (accumulated
// over all Evaluate / SplineEnergyOf calls; the midpoint terms run in
// parallel, so the LM and Newton seconds are summed over the threads and can
// exceed the wall time).
struct SplineTimings {
  int evaluations = 0;           // F_K evaluations (midpoint sweeps)
  int gradient_evaluations = 0;  // of which with the adjoint gradient
  int lm_solves = 0;             // midpoints (re)started by sparse LM
  int lm_iterations = 0;         // their LM iterations
  int newton_steps = 0;          // Hessian assemblies
  int factorizations = 0;        // sparse Cholesky factorisations of H_k
  int cg_iterations = 0;         // CG iterations on a reused factor
  double lm_seconds = 0;         // sparse LM midpoint solves
  double newton_seconds = 0;     // Newton steps (incl. the adjoint's H)
  double gradient_seconds = 0;   // adjoint back-substitutions and sums
};

// R[s] = sum_j W[S_j, s_{k_j}] + sigma F_K[s], F_K = 4 K^3 sum_k W[s_k,
// m_k], m_k = argmin_m W[s_{k-1}, m] + W[m, s_{k+1}] (geodesic midpoint).
// Midpoints: Newton's method (SolveNewton, solvers/newton_solver.h, root
// finding) on G(m) = D_2 W[s_{k-1}, m] + D_1 W[m, s_{k+1}] = 0 with the
// exact Hessian H_k (gauge-reduced; assembled by
// PathHessianAssembler, solved by ReusableCholesky: CG on the last factor of
// this term, refactorised when CG stalls), started from the
// previous evaluation's midpoint; sparse LM first when there is none (from
// (s_{k-1} + s_{k+1})/2, failing that from s_k), or when
// Newton fails (H_k not positive definite, or a step that does not halve
// |G|; a warm LM restart is capped at 50 iterations, then run once more in
// full; the full LM solve stands if Newton cannot improve on it). Newton stops
// at |G| <= 1e-10 |D_2 W[s_{k-1}, m]| (max norms) or at the round-off floor (no
// halving below 1e-8 of it). The last Newton step's H_k serves the adjoint
// below when that step was tiny (else it is reassembled at m_k). Gradient by the adjoint: with H_k = D_2^2
// W[s_{k-1}, m_k] + D_1^2 W[m_k, s_{k+1}] and H_k p_k = -D_2 W[s_k, m_k]
// (solved modulo rigid motions),
//   dF/ds_k     += 4K^3 D_1 W[s_k, m_k],
//   dF/ds_{k-1} += 4K^3 (d_{s_{k-1}} d_m W[s_{k-1}, m_k]) p_k,
//   dF/ds_{k+1} += 4K^3 (d_{s_{k+1}} d_m W[m_k, s_{k+1}]) p_k,
// the mixed blocks mapping a vector on m to one on the neighbour (applied
// as directional derivatives, EnergyGradientDerivative). The
// parameters are the free shapes' coordinates, concatenated in index order.
class SplineObjective : public ceres::FirstOrderFunction {
 public:
  SplineObjective(const ShellSpace& space, SplineSpec spec,
                  const SolverSettings& inner_settings);
  ~SplineObjective() override;

  int NumParameters() const override { return num_parameters_; }
  bool Evaluate(const double* parameters, double* cost,
                double* gradient) const override;

  std::vector<double> InitialParameters() const;
  ShellPath PathFrom(const double* parameters) const;
  // F_K alone (without sigma and data) of a path, solving the midpoints.
  double SplineEnergyOf(const ShellPath& path) const;
  int num_shapes() const { return static_cast<int>(spec_.initial.size()); }
  SplineTimings timings() const;

  // A stop token for the sparse LM runs of the midpoints without a warm
  // start (the long part of a first evaluation: 20 s on the cactus); one
  // that never stops (the default) for exact evaluations. When it stops
  // one, the evaluation returns false and stopped() is true from then on:
  // its midpoints are unfinished and no value of this objective may be
  // used any more.
  void set_cold_start_stop(StopToken stop) {
    cold_start_stop_ = std::move(stop);
  }
  bool stopped() const { return stopped_.load(); }

 private:
  struct Term {
    int previous, center, next;
  };
  struct Midpoint;  // the midpoint m_k and its adjoint data
  // Solves all midpoints of `path`; with `adjoint`, also leaves H_k factorised
  // and the mixed blocks of the terms with a free neighbour. False if a
  // midpoint solve fails.
  bool SolveMidpoints(const ShellPath& path, bool adjoint) const;
  bool SolveMidpoint(const Positions& a, const Positions& b,
                     const Positions& cold_start, bool adjoint,
                     Midpoint* midpoint) const;
  // The LM runs of one SolveMidpoint so far, and whether the full one (the
  // last allowed) is done.
  struct LmRuns {
    int runs = 0;
    bool done = false;
  };
  // SolveMidpoint's parts: one LM run (false if it failed or was stopped),
  // the midpoint of ends equal to round-off, and the Newton iteration from
  // midpoint->m (with LM runs when Newton fails).
  bool RunMidpointLm(const Positions& a, const Positions& b,
                     const Positions& cold_start, LmRuns* lm,
                     Midpoint* midpoint) const;
  bool SolveEqualEndsMidpoint(const Positions& a, const Positions& b,
                              bool adjoint, Midpoint* midpoint) const;
  bool NewtonMidpoint(const Positions& a, const Positions& b,
                      const Positions& cold_start, bool adjoint, LmRuns* lm,
                      Midpoint* midpoint) const;
  // Evaluate's parts: the cost of a path whose midpoints are solved (false
  // if degenerate or not finite), and term t's adjoint gradient parts.
  bool RegressionCost(const ShellPath& path, double* cost) const;
  bool SolveAdjointTerm(const ShellPath& path, int t) const;
  const ShellSpace& space_;
  SplineSpec spec_;
  SolverSettings inner_settings_;
  std::vector<Term> terms_;
  std::vector<int> free_shapes_;
  int num_parameters_ = 0;
  std::unique_ptr<PathHessianAssembler> assembler_;  // for the H_k
  mutable std::vector<std::unique_ptr<Midpoint>> midpoints_;  // per term
  mutable SplineTimings timings_;
  StopToken cold_start_stop_;
  mutable std::atomic<bool> stopped_{false};
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINES_SPLINE_ENERGY_H_
