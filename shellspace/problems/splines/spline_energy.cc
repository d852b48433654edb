#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/problems/splines/spline_energy.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"

namespace shellspace {

namespace {

double SecondsSince(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since)
      .count();
}

double MaxNorm(const Eigen::VectorXd& v) {
  return v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
}

// Newton's stopping rules on G(m) (relative to |D_2 W[a, m]|): converged
// (round-off leaves |G| ~ 1e-11 on the cactus), and the floor below which a
// step that does not halve |G| ends the iteration instead of handing over to
// LM.
constexpr double kNewtonTolerance = 1e-10;
constexpr double kRoundOffFloor = 1e-8;
// The Hessian of the last Newton step (taken at the previous iterate) serves
// the adjoint if that step moved no vertex coordinate by more than this times
// the bounding-box diagonal (p_k is then as accurate); otherwise H_k is
// assembled once more at the final midpoint. (A small |G| does not bound the
// step: H_k of a thin shell is badly conditioned.)
constexpr double kReuseHessianBelow = 1e-9;
constexpr int kMaxNewtonSteps = 10;
// Ends closer than this times the diagonal (max norm) are equal: their
// midpoint is their average (SolveMidpoint).
constexpr double kEqualEnds = 1e-12;
// LM restarted from a warm start (Newton failed: a trial point of the line
// search far from the last one) gets this many iterations; if the midpoint is
// not found then, the trial point is rejected and the line search shrinks.
constexpr int kMaxWarmLmIterations = 50;

// H_k = D_2^2 W[a, m] + D_1^2 W[m, b] restricted to the rigid gauge of m
// (p = T q with T = RigidGaugeBasis(m)), assembled by PathHessianAssembler
// on the path (a, m, b) (which gives 2 H_k), and solved by ReusableCholesky:
// its factor serves as CG preconditioner for later Newton steps and later
// L-BFGS evaluations of the same term, refactorised when CG stalls.
class MidpointHessian {
 public:
  void Assemble(const PathHessianAssembler& assembler, const Positions& a,
                const Positions& m, const Positions& b, int threads) {
    basis_ = RigidGaugeBasis(m);
    system_.matrix = 0.5 * assembler.Assemble({a, m, b}, {basis_}, threads);
    system_.vertex_of = BasisColumnVertices(basis_);
    system_.num_vertices = static_cast<int>(basis_.rows() / 3);
  }
  // H p = rhs to relative residual `tolerance`; false if H is not positive
  // definite (modulo rigid motions).
  bool Solve(const Eigen::VectorXd& rhs, double tolerance,
             Eigen::VectorXd* p) {
    Eigen::VectorXd q;
    const Eigen::VectorXd reduced = basis_.transpose() * rhs;
    if (!solver_.Solve(system_, reduced, tolerance, &q)) return false;
    *p = basis_ * q;
    return true;
  }
  const SparseMatrix& basis() const { return basis_; }
  const LinearSystem& system() const { return system_; }
  ReusableCholesky* solver() { return &solver_; }
  const ReusableCholesky::Stats& stats() const { return solver_.stats(); }

 private:
  SparseMatrix basis_;
  LinearSystem system_;  // T^T H_k T (lower triangle)
  ReusableCholesky solver_;
};

// Relative residual of the linear solves: Newton steps (|G| / scale clamped
// to [1e-12, 1e-3]: tighter as |G| falls) and the adjoint.
constexpr double kForcingMin = 1e-12;
constexpr double kForcingMax = 1e-3;
constexpr double kAdjointTolerance = 1e-10;

// G(m) = D_2 W[a, m] + D_1 W[m, b] = 0 for SolveNewton (root finding; the
// "Jacobian" is H_k, SPD modulo rigid motions): residual T^T G with T =
// RigidGaugeBasis(m), max norm of G over all coordinates, tolerance scale
// |D_2 W[a, m]|_inf; H_k assembled into `hessian` (kept for the adjoint,
// *has_adjoint set); retraction m += T q. An accepted step larger than
// kReuseHessianBelow times the bounding-box diagonal clears *has_adjoint
// (H_k is from before the step).
class MidpointProblem : public NewtonProblem {
 public:
  MidpointProblem(const ShellSpace& space,
                  const PathHessianAssembler& assembler, const Positions& a,
                  const Positions& b, int threads, Positions* m,
                  MidpointHessian* hessian, bool* has_adjoint,
                  int* assemblies)
      : space_(space), assembler_(assembler), a_(a), b_(b),
        threads_(threads), m_(m), hessian_(hessian),
        has_adjoint_(has_adjoint), assemblies_(assemblies) {}

  EvaluationStatus Merit(NewtonPoint, double*) override {
    return EvaluationStatus::kInfeasible;  // root finding
  }
  EvaluationStatus Residual(NewtonPoint point,
                            NewtonResidual* residual) override {
    const bool current = point == NewtonPoint::kCurrent;
    const Positions& m = current ? *m_ : trial_;
    Eigen::VectorXd g_a, g;
    Eigen::VectorXd g_b;
    const bool ok =
        TryEnergyGradient(space_, a_, m, ShellSide::kDeformed, &g_a) &&
        TryEnergyGradient(space_, m, b_, ShellSide::kReference, &g_b);
    if (ok) g = g_a + g_b;
    if (!ok) {
      if (!current) {  // no usable trial: never "smaller"
        trial_residual_ = NewtonResidual();
        trial_residual_.max_norm = HUGE_VAL;
      }
      return EvaluationStatus::kInfeasible;
    }
    residual->scale = std::max(MaxNorm(g_a), 1e-300);
    residual->max_norm = MaxNorm(g);
    residual->two_norm = g.norm();
    residual->reduced = RigidGaugeBasis(m).transpose() * g;
    (current ? current_ : trial_residual_) = *residual;
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Assemble(LinearSystem* system) override {
    hessian_->Assemble(assembler_, a_, *m_, b_, threads_);
    ++*assemblies_;
    *has_adjoint_ = true;
    *system = hessian_->system();
    return EvaluationStatus::kOk;
  }
  void SetTrial(const Eigen::VectorXd& step) override {
    step_ = hessian_->basis() * step;
    trial_ = *m_;
    Eigen::Map<Eigen::VectorXd>(trial_.data(), trial_.size()) += step_;
  }
  void AcceptTrial() override {
    *m_ = trial_;
    current_ = trial_residual_;
    // H_k from before the step serves the adjoint only after a small step.
    const double diagonal =
        (m_->colwise().maxCoeff() - m_->colwise().minCoeff()).norm();
    if (MaxNorm(step_) > kReuseHessianBelow * diagonal) {
      *has_adjoint_ = false;
    }
  }
  // G at *m (the last Residual(kCurrent) or accepted trial), and the last
  // trial's: valid after a line search.
  const NewtonResidual& current() const { return current_; }
  const NewtonResidual& trial() const { return trial_residual_; }
  const Eigen::VectorXd& last_step() const { return step_; }  // T q

 private:
  const ShellSpace& space_;
  const PathHessianAssembler& assembler_;
  const Positions& a_;
  const Positions& b_;
  const int threads_;
  Positions* m_;
  MidpointHessian* hessian_;
  bool* has_adjoint_;
  int* assemblies_;
  Positions trial_;
  Eigen::VectorXd step_;
  NewtonResidual current_, trial_residual_;
};

// SolveNewton's settings for the midpoint's root finding, with `budget`
// Hessian assemblies left.
NewtonSettings MidpointNewtonSettings(int budget) {
  NewtonSettings settings;
  settings.mode = NewtonMode::kRootFind;
  settings.max_steps = budget;
  settings.tolerance = kNewtonTolerance;  // times |D_2 W[a, m]|
  settings.forcing_rule = NewtonSettings::Forcing::kRelativeResidual;
  settings.forcing = kForcingMax;
  settings.forcing_min = kForcingMin;
  settings.max_halvings = 0;
  settings.accept_max_norm_reduction = 0.5;
  return settings;
}

// Damped Newton: H_k is positive definite, so dm descends the midpoint
// energy E(m) = W[a, m] + W[m, b]; halve it until E drops. False (*m
// unchanged) if 20 halvings do not: not a usable midpoint.
bool DampedMidpointStep(const ShellSpace& space, const Positions& a,
                        const Positions& b, const Eigen::VectorXd& dm,
                        Positions* m) {
  const auto energy = [&](const Positions& x) {
    return EvaluateDeformationEnergy(space, a, x).total +
           EvaluateDeformationEnergy(space, x, b).total;
  };
  const double e0 = energy(*m);
  bool decreased = false;
  Positions candidate;
  for (int halving = 1; halving <= 20 && !decreased; ++halving) {
    candidate = *m;
    Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) +=
        std::ldexp(1.0, -halving) * dm;
    decreased = energy(candidate) < e0;
  }
  if (!decreased) return false;
  *m = candidate;
  return true;
}

}  // namespace

// m_k, and (when `has_adjoint`) H_k at m_k for the adjoint gradient.
struct SplineObjective::Midpoint {
  Positions m;
  bool has_adjoint = false;
  MidpointHessian hessian;  // H_k = D_2^2 W[s_{k-1}, m] + D_1^2 W[m, s_{k+1}]
  // This term's share of SplineTimings (terms are solved in parallel, each
  // counting its own; timings() sums them in term order).
  int lm_solves = 0, lm_iterations = 0, newton_steps = 0;
  double lm_seconds = 0, newton_seconds = 0;
  // The adjoint's contributions of this term to the gradient (unscaled):
  // D_1 W[s_k, m_k] on the centre, the mixed blocks times p_k on the
  // neighbours (empty when that neighbour is fixed).
  Eigen::VectorXd center_part, previous_part, next_part;
};

SplineObjective::~SplineObjective() = default;

SplineTimings SplineObjective::timings() const {
  SplineTimings t = timings_;
  for (const auto& mid : midpoints_) {
    t.lm_solves += mid->lm_solves;
    t.lm_iterations += mid->lm_iterations;
    t.newton_steps += mid->newton_steps;
    t.lm_seconds += mid->lm_seconds;
    t.newton_seconds += mid->newton_seconds;
    t.factorizations += mid->hessian.stats().factorizations;
    t.cg_iterations += mid->hessian.stats().cg_iterations;
  }
  return t;
}

SplineObjective::SplineObjective(const ShellSpace& space, SplineSpec spec,
                                 const SolverSettings& inner_settings)
    : space_(space),
      spec_(std::move(spec)),
      inner_settings_(inner_settings),
      assembler_(std::make_unique<PathHessianAssembler>(space)) {
  const int K = spec_.steps;
  const int shapes = spec_.periodic ? K : K + 1;
  if (K < 2) {
    throw InputError(
        "spline energy: the number of steps K must be at least 2, got " +
        std::to_string(K));
  }
  if (static_cast<int>(spec_.initial.size()) != shapes) {
    throw InputError("spline: the initial path must have " +
                     std::to_string(shapes) + " shapes");
  }
  if (static_cast<int>(spec_.is_free.size()) != shapes) {
    throw InputError("spline: one free flag per shape expected");
  }
  for (const SplineDatum& d : spec_.data) {
    if (d.index < 0 || d.index >= shapes) {
      throw InputError("data index " + std::to_string(d.index) +
                       " outside the path");
    }
  }
  if (spec_.periodic) {
    for (int k = 0; k < K; ++k)
      terms_.push_back({(k + K - 1) % K, k, (k + 1) % K});
  } else {
    for (int k = 1; k < K; ++k) terms_.push_back({k - 1, k, k + 1});
  }
  for (int k = 0; k < shapes; ++k) {
    if (spec_.is_free[k]) free_shapes_.push_back(k);
  }
  num_parameters_ =
      static_cast<int>(free_shapes_.size()) * 3 * space_.num_vertices;
  for (size_t t = 0; t < terms_.size(); ++t) {
    midpoints_.push_back(std::make_unique<Midpoint>());
  }
}

std::vector<double> SplineObjective::InitialParameters() const {
  std::vector<double> x;
  x.reserve(num_parameters_);
  for (int k : free_shapes_) {
    const Positions& s = spec_.initial[k];
    x.insert(x.end(), s.data(), s.data() + s.size());
  }
  return x;
}

ShellPath SplineObjective::PathFrom(const double* parameters) const {
  ShellPath path = spec_.initial;
  const int block = 3 * space_.num_vertices;
  for (size_t i = 0; i < free_shapes_.size(); ++i) {
    Positions& s = path[free_shapes_[i]];
    std::copy(parameters + i * block, parameters + (i + 1) * block, s.data());
  }
  return path;
}

// LM runs: from a warm start, first one capped at kMaxWarmLmIterations,
// then (if Newton still fails) one with the full inner settings; from no
// warm start, one full run from `cold_start`.
bool SplineObjective::RunMidpointLm(const Positions& a, const Positions& b,
                                    const Positions& cold_start, LmRuns* lm,
                                    Midpoint* mid) const {
  SolverSettings settings = inner_settings_;
  settings.num_threads = 1;  // the terms run in parallel
  if (mid->m.size() == 0) {
    mid->m = cold_start;
    settings.stop = cold_start_stop_;
    lm->done = true;
  } else if (lm->runs == 0) {
    settings.max_iterations =
        std::min(settings.max_iterations, kMaxWarmLmIterations);
  } else {
    lm->done = true;
  }
  ++lm->runs;
  const auto clock = std::chrono::steady_clock::now();
  ceres::Solver::Summary summary;
  mid->m = SolveWeightedMidpoint(space_, a, b, 1.0, 1.0, mid->m, {}, settings,
                                 &summary);
  mid->lm_seconds += SecondsSince(clock);
  ++mid->lm_solves;
  mid->lm_iterations += static_cast<int>(summary.iterations.size());
  mid->has_adjoint = false;
  if (settings.stop.stop_requested()) {
    stopped_ = true;  // unfinished: not a midpoint
    return false;
  }
  return summary.IsSolutionUsable();
}

// Equal ends (to round-off; e.g. a path through one keyframe twice):
// W >= 0 and W[a, a] = 0, and W is quadratic about its rest, so
// m = (a + b) / 2 to O(|b - a|^2). No criterion relative to
// |D_2 W[a, m]| can be met there (every |G| is round-off).
bool SplineObjective::SolveEqualEndsMidpoint(const Positions& a,
                                             const Positions& b, bool adjoint,
                                             Midpoint* mid) const {
  mid->m = 0.5 * (a + b);
  if (!adjoint) return true;
  MidpointProblem problem(space_, *assembler_, a, b, /*threads=*/1, &mid->m,
                          &mid->hessian, &mid->has_adjoint, &mid->newton_steps);
  NewtonResidual g;
  LinearSystem unused;
  return problem.Residual(NewtonPoint::kCurrent, &g) == EvaluationStatus::kOk &&
         problem.Assemble(&unused) == EvaluationStatus::kOk;
}

// Newton (SolveNewton) within kMaxNewtonSteps iterations (Hessian
// assemblies) in all; a step is taken if it halves max |G|. When it does
// not: converged at the round-off floor; else LM from the current point;
// after the full LM, the step if it lowers max |G| at all, else damped
// Newton on the midpoint energy.
bool SplineObjective::NewtonMidpoint(const Positions& a, const Positions& b,
                                     const Positions& cold_start, bool adjoint,
                                     LmRuns* lm, Midpoint* mid) const {
  const auto clock = std::chrono::steady_clock::now();
  const double lm_seconds_before = mid->lm_seconds;
  MidpointProblem problem(space_, *assembler_, a, b, /*threads=*/1, &mid->m,
                          &mid->hessian, &mid->has_adjoint,
                          &mid->newton_steps);
  NewtonResidual g;  // at mid->m
  bool converged = false;
  int budget = kMaxNewtonSteps;
  bool ok = problem.Residual(NewtonPoint::kCurrent, &g) ==
            EvaluationStatus::kOk;
  while (ok && budget > 0 && !converged) {
    const NewtonReport report = SolveNewton(&problem, mid->hessian.solver(),
                                            MidpointNewtonSettings(budget));
    budget -= report.iterations;
    g = problem.current();
    if (report.stop == NewtonStop::kConverged) {
      if (mid->has_adjoint || !adjoint) {
        converged = true;
      } else if (budget > 0) {  // H_k is needed for the adjoint only
        LinearSystem unused;
        problem.Assemble(&unused);
        --budget;
        converged = true;
      }
      break;
    }
    if (report.stop == NewtonStop::kLinearSolveFailed) {
      mid->has_adjoint = false;
      // H_k indefinite even after LM
      if (lm->done || !RunMidpointLm(a, b, cold_start, lm, mid)) break;
    } else if (report.stop == NewtonStop::kLineSearchFailed) {
      if (g.max_norm <= kRoundOffFloor * g.scale) {
        converged = true;  // at round-off; H_k is at mid->m
        break;
      }
      if (!lm->done) {  // far from the midpoint: LM from here
        if (!RunMidpointLm(a, b, cold_start, lm, mid)) break;
      } else if (problem.trial().max_norm < g.max_norm) {
        problem.AcceptTrial();  // a decrease after the full LM solve: take it
        g = problem.current();
        continue;
      } else {
        if (!DampedMidpointStep(space_, a, b, problem.last_step(), &mid->m)) {
          break;  // not a usable midpoint
        }
        mid->has_adjoint = false;
      }
    } else {
      break;  // max steps (budget spent) or an infeasible start
    }
    // mid->m moved outside the engine (LM, damped step): G there.
    ok = problem.Residual(NewtonPoint::kCurrent, &g) == EvaluationStatus::kOk;
  }
  if (ok && !converged && g.max_norm <= kRoundOffFloor * g.scale &&
      (mid->has_adjoint || !adjoint)) {
    converged = true;
  }
  mid->newton_seconds +=
      SecondsSince(clock) - (mid->lm_seconds - lm_seconds_before);
  return converged;
}

bool SplineObjective::SolveMidpoint(const Positions& a, const Positions& b,
                                    const Positions& cold_start, bool adjoint,
                                    Midpoint* mid) const {
  LmRuns lm;
  mid->has_adjoint = false;
  const double diagonal =
      (a.colwise().maxCoeff() - a.colwise().minCoeff()).norm();
  if ((a - b).cwiseAbs().maxCoeff() <= kEqualEnds * diagonal) {
    return SolveEqualEndsMidpoint(a, b, adjoint, mid);
  }
  if (mid->m.size() == 0 && !RunMidpointLm(a, b, cold_start, &lm, mid)) {
    return false;
  }
  return NewtonMidpoint(a, b, cold_start, adjoint, &lm, mid);
}

bool SplineObjective::SolveMidpoints(const ShellPath& path,
                                     bool adjoint) const {
  ++timings_.evaluations;
  if (adjoint) ++timings_.gradient_evaluations;
  // The terms are independent given the path: each is solved on its own
  // thread with one-thread assemblies, from its own warm start, so the
  // result does not depend on the thread count or the order of completion.
  std::vector<char> solved(terms_.size(), 0);
  ParallelFor(static_cast<int>(terms_.size()), inner_settings_.num_threads,
              [&](int t) {
                const Term& term = terms_[t];
                const bool needs_adjoint =
                    adjoint &&
                    (spec_.is_free[term.previous] || spec_.is_free[term.next]);
                // Without a warm start: from the average of the neighbours,
                // else (it can be crumpled, e.g. cactus9 and cactus15) from
                // s_k.
                const Positions& a = path[term.previous];
                const Positions& b = path[term.next];
                Midpoint* mid = midpoints_[t].get();
                const bool cold = mid->m.size() == 0;
                if (SolveMidpoint(a, b, Positions(0.5 * (a + b)),
                                  needs_adjoint, mid)) {
                  solved[t] = 1;
                  return;
                }
                if (!cold || stopped_) return;
                mid->m.resize(0, 3);
                solved[t] = SolveMidpoint(a, b, path[term.center],
                                          needs_adjoint, mid);
              });
  return std::all_of(solved.begin(), solved.end(),
                     [](char ok) { return ok != 0; });
}

double SplineObjective::SplineEnergyOf(const ShellPath& path) const {
  if (!SolveMidpoints(path, false)) return NAN;
  double sum = 0;
  DeformationEnergy w;
  for (size_t t = 0; t < terms_.size(); ++t) {
    if (!TryEvaluateDeformationEnergy(space_, path[terms_[t].center],
                                      midpoints_[t]->m, &w)) {
      return NAN;
    }
    sum += w.total;
  }
  const double K = spec_.steps;
  return 4 * K * K * K * sum;
}

// R = data + sigma F_K of `path` into *cost, its midpoints solved; false if
// a shape or midpoint is degenerate or F_K is not finite.
bool SplineObjective::RegressionCost(const ShellPath& path,
                                     double* cost) const {
  const double K = spec_.steps;
  DeformationEnergy w;
  double spline = 0;
  for (size_t t = 0; t < terms_.size(); ++t) {
    if (!TryEvaluateDeformationEnergy(space_, path[terms_[t].center],
                                      midpoints_[t]->m, &w)) {
      return false;
    }
    spline += w.total;
  }
  spline *= 4 * K * K * K;
  if (!std::isfinite(spline)) return false;
  double data = 0;
  for (const SplineDatum& d : spec_.data) {
    if (!TryEvaluateDeformationEnergy(space_, d.shape, path[d.index], &w)) {
      return false;
    }
    data += w.total;
  }
  *cost = data + spec_.sigma * spline;
  return true;
}

// Term t's adjoint parts of the gradient (unscaled) into its Midpoint:
// D_1 W[s_k, m_k] on the centre and, for a free neighbour, the mixed block
// times p_k (H_k p_k = -D_2 W[s_k, m_k]). False if a derivative or the solve
// fails.
bool SplineObjective::SolveAdjointTerm(const ShellPath& path, int t) const {
  const Term& term = terms_[t];
  Midpoint& mid = *midpoints_[t];
  const Positions& s = path[term.center];
  mid.previous_part.resize(0);
  mid.next_part.resize(0);
  if (!TryEnergyGradient(space_, s, mid.m, ShellSide::kReference,
                         &mid.center_part)) {
    return false;
  }
  if (!spec_.is_free[term.previous] && !spec_.is_free[term.next]) {
    return true;
  }
  // H_k p_k = -D_2 W[s_k, m_k] modulo rigid motions; the mixed blocks
  // applied to p_k as directional derivatives of the gradients.
  Eigen::VectorXd rhs, p;
  if (!TryEnergyGradient(space_, s, mid.m, ShellSide::kDeformed, &rhs) ||
      !mid.hessian.Solve(-rhs, kAdjointTolerance, &p)) {
    return false;
  }
  if (spec_.is_free[term.previous] &&
      !TryEnergyGradientDerivative(space_, path[term.previous], mid.m,
                                   ShellSide::kReference, ShellSide::kDeformed,
                                   p, &mid.previous_part)) {
    return false;
  }
  if (spec_.is_free[term.next] &&
      !TryEnergyGradientDerivative(space_, mid.m, path[term.next],
                                   ShellSide::kDeformed, ShellSide::kReference,
                                   p, &mid.next_part)) {
    return false;
  }
  return true;
}

bool SplineObjective::Evaluate(const double* parameters, double* cost,
                               double* gradient) const {
  // A degenerate shape or midpoint rejects the point (false): every energy
  // and derivative below is the non-throwing Try twin.
  const ShellPath path = PathFrom(parameters);
  const double K = spec_.steps;
  const double scale = spec_.sigma * 4 * K * K * K;
  if (!SolveMidpoints(path, gradient != nullptr)) return false;
  if (!RegressionCost(path, cost)) return false;
  if (gradient == nullptr) return true;

  const auto clock = std::chrono::steady_clock::now();
  const int n3 = 3 * space_.num_vertices;
  std::vector<Eigen::VectorXd> grad(path.size(), Eigen::VectorXd::Zero(n3));
  Eigen::VectorXd part;
  for (const SplineDatum& d : spec_.data) {
    if (!TryEnergyGradient(space_, d.shape, path[d.index],
                           ShellSide::kDeformed, &part)) {
      return false;
    }
    grad[d.index] += part;
  }
  // Per term, in parallel (each writes only its own Midpoint), then summed
  // in term order.
  std::vector<char> ok(terms_.size(), 0);
  ParallelFor(static_cast<int>(terms_.size()), inner_settings_.num_threads,
              [&](int t) {
                if (SolveAdjointTerm(path, t)) ok[t] = 1;
              });
  for (size_t t = 0; t < terms_.size(); ++t) {
    if (!ok[t]) return false;
    const Term& term = terms_[t];
    const Midpoint& mid = *midpoints_[t];
    grad[term.center] += scale * mid.center_part;
    if (mid.previous_part.size()) grad[term.previous] += scale * mid.previous_part;
    if (mid.next_part.size()) grad[term.next] += scale * mid.next_part;
  }
  for (size_t i = 0; i < free_shapes_.size(); ++i) {
    Eigen::Map<Eigen::VectorXd>(gradient + i * n3, n3) = grad[free_shapes_[i]];
  }
  timings_.gradient_seconds += SecondsSince(clock);
  return true;
}

}  // namespace shellspace
