#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/problems/splines/spline_energy.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/problems/calculus/path_hessian.h"
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
    lower_ = 0.5 * assembler.Assemble({a, m, b}, {basis_}, threads);
    vertex_of_ = BasisColumnVertices(basis_);
  }
  // H p = rhs to relative residual `tolerance`; false if H is not positive
  // definite (modulo rigid motions).
  bool Solve(const Eigen::VectorXd& rhs, double tolerance,
             Eigen::VectorXd* p) {
    Eigen::VectorXd q;
    const Eigen::VectorXd reduced = basis_.transpose() * rhs;
    if (!solver_.Solve(lower_, vertex_of_, basis_.rows() / 3, reduced,
                       tolerance, &q)) {
      return false;
    }
    *p = basis_ * q;
    return true;
  }
  const ReusableCholesky::Stats& stats() const { return solver_.stats(); }

 private:
  SparseMatrix basis_, lower_;
  std::vector<int> vertex_of_;
  ReusableCholesky solver_;
};

// Relative residual of the linear solves: Newton steps (tighter as |G|
// falls) and the adjoint.
double NewtonForcing(double norm, double scale) {
  return std::clamp(norm / scale, 1e-12, 1e-3);
}
constexpr double kAdjointTolerance = 1e-10;

}  // namespace

// m_k, and (when `has_adjoint`) H_k at m_k for the adjoint gradient.
struct SplineObjective::Midpoint {
  Positions m;
  bool has_adjoint = false;
  MidpointHessian hessian;  // H_k = D_2^2 W[s_{k-1}, m] + D_1^2 W[m, s_{k+1}]
};

SplineObjective::~SplineObjective() = default;

SplineTimings SplineObjective::timings() const {
  SplineTimings t = timings_;
  for (const auto& mid : midpoints_) {
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

bool SplineObjective::SolveMidpoint(const Positions& a, const Positions& b,
                                    const Positions& cold_start, bool adjoint,
                                    Midpoint* mid) const {
  // LM runs: from a warm start, first one capped at kMaxWarmLmIterations,
  // then (if Newton still fails) one with the full inner settings; from no
  // warm start, one full run from `cold_start`.
  bool lm_done = false;  // the full run is done: no more LM
  int lm_runs = 0;
  const auto run_lm = [&]() {
    SolverSettings settings = inner_settings_;
    if (mid->m.size() == 0) {
      mid->m = cold_start;
      lm_done = true;
    } else if (lm_runs == 0) {
      settings.max_iterations =
          std::min(settings.max_iterations, kMaxWarmLmIterations);
    } else {
      lm_done = true;
    }
    ++lm_runs;
    const auto clock = std::chrono::steady_clock::now();
    ceres::Solver::Summary summary;
    mid->m = SolveWeightedMidpoint(space_, a, b, 1.0, 1.0, mid->m, {}, settings,
                                   &summary);
    timings_.lm_seconds += SecondsSince(clock);
    ++timings_.lm_solves;
    timings_.lm_iterations += static_cast<int>(summary.iterations.size());
    mid->has_adjoint = false;
    return summary.IsSolutionUsable();
  };
  const auto residual = [&](const Positions& m, double* scale) {
    const Eigen::VectorXd g_a =
        EnergyGradient(space_, a, m, ShellSide::kDeformed);
    *scale = std::max(MaxNorm(g_a), 1e-300);
    return Eigen::VectorXd(g_a +
                           EnergyGradient(space_, m, b, ShellSide::kReference));
  };
  mid->has_adjoint = false;
  if (mid->m.size() == 0 && !run_lm()) return false;
  double scale = 0;
  Eigen::VectorXd g = residual(mid->m, &scale);
  const auto clock = std::chrono::steady_clock::now();
  const double lm_seconds_before = timings_.lm_seconds;
  bool converged = false;
  for (int step = 0; step < kMaxNewtonSteps && !converged; ++step) {
    const double norm = MaxNorm(g);
    if (norm <= kNewtonTolerance * scale && (mid->has_adjoint || !adjoint)) {
      converged = true;
      break;
    }
    // H_k at the current iterate.
    mid->hessian.Assemble(*assembler_, a, mid->m, b,
                          inner_settings_.num_threads);
    ++timings_.newton_steps;
    mid->has_adjoint = true;
    if (norm <= kNewtonTolerance * scale) {
      converged = true;  // H_k was needed for the adjoint only
      break;
    }
    Eigen::VectorXd dm;
    if (!mid->hessian.Solve(-g, NewtonForcing(norm, scale), &dm)) {
      mid->has_adjoint = false;
      if (lm_done || !run_lm()) break;  // H_k indefinite even after LM
      g = residual(mid->m, &scale);
      continue;
    }
    Positions candidate = mid->m;
    Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) += dm;
    double candidate_scale = 0;
    const Eigen::VectorXd g_new = residual(candidate, &candidate_scale);
    const double new_norm = MaxNorm(g_new);
    if (!(new_norm <= 0.5 * norm)) {
      if (norm <= kRoundOffFloor * scale) {
        converged = true;  // at round-off; H_k is at mid->m
        continue;
      }
      if (!lm_done) {  // far from the midpoint: LM from here
        if (!run_lm()) break;
        g = residual(mid->m, &scale);
        continue;
      }
      if (!(new_norm < norm)) {
        // Damped Newton: H_k is positive definite, so dm descends the
        // midpoint energy E(m) = W[a, m] + W[m, b]; halve it until E drops.
        const auto energy = [&](const Positions& m) {
          return EvaluateDeformationEnergy(space_, a, m).total +
                 EvaluateDeformationEnergy(space_, m, b).total;
        };
        const double e0 = energy(mid->m);
        bool decreased = false;
        for (int halving = 1; halving <= 20 && !decreased; ++halving) {
          candidate = mid->m;
          Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) +=
              std::ldexp(1.0, -halving) * dm;
          decreased = energy(candidate) < e0;
        }
        if (!decreased) break;  // not a usable midpoint
        mid->m = candidate;
        g = residual(mid->m, &scale);
        mid->has_adjoint = false;
        continue;
      }
      // A decrease after the full LM solve: take it.
    }
    mid->m = candidate;
    g = g_new;
    scale = candidate_scale;
    // H_k from before the step serves the adjoint only after a small step.
    const double diagonal =
        (mid->m.colwise().maxCoeff() - mid->m.colwise().minCoeff()).norm();
    if (MaxNorm(dm) > kReuseHessianBelow * diagonal) mid->has_adjoint = false;
  }
  if (!converged && MaxNorm(g) <= kRoundOffFloor * scale &&
      (mid->has_adjoint || !adjoint)) {
    converged = true;
  }
  timings_.newton_seconds +=
      SecondsSince(clock) - (timings_.lm_seconds - lm_seconds_before);
  return converged;
}

bool SplineObjective::SolveMidpoints(const ShellPath& path,
                                     bool adjoint) const {
  ++timings_.evaluations;
  if (adjoint) ++timings_.gradient_evaluations;
  for (size_t t = 0; t < terms_.size(); ++t) {
    const Term& term = terms_[t];
    const bool needs_adjoint =
        adjoint && (spec_.is_free[term.previous] || spec_.is_free[term.next]);
    // Without a warm start: from the average of the neighbours, else (it
    // can be crumpled, e.g. cactus9 and cactus15) from s_k.
    const Positions& a = path[term.previous];
    const Positions& b = path[term.next];
    Midpoint* mid = midpoints_[t].get();
    const bool cold = mid->m.size() == 0;
    if (SolveMidpoint(a, b, Positions(0.5 * (a + b)), needs_adjoint, mid)) {
      continue;
    }
    if (!cold) return false;
    mid->m.resize(0, 3);
    if (!SolveMidpoint(a, b, path[term.center], needs_adjoint, mid)) {
      return false;
    }
  }
  return true;
}

double SplineObjective::SplineEnergyOf(const ShellPath& path) const {
  if (!SolveMidpoints(path, false)) return NAN;
  double sum = 0;
  for (size_t t = 0; t < terms_.size(); ++t) {
    sum += EvaluateDeformationEnergy(space_, path[terms_[t].center],
                                     midpoints_[t]->m)
               .total;
  }
  const double K = spec_.steps;
  return 4 * K * K * K * sum;
}

bool SplineObjective::Evaluate(const double* parameters, double* cost,
                               double* gradient) const {
  const ShellPath path = PathFrom(parameters);
  const double K = spec_.steps;
  const double scale = spec_.sigma * 4 * K * K * K;
  try {
    if (!SolveMidpoints(path, gradient != nullptr)) return false;
    double spline = 0;
    for (size_t t = 0; t < terms_.size(); ++t) {
      spline += EvaluateDeformationEnergy(space_, path[terms_[t].center],
                                          midpoints_[t]->m)
                    .total;
    }
    spline *= 4 * K * K * K;
    if (!std::isfinite(spline)) return false;
    double data = 0;
    for (const SplineDatum& d : spec_.data) {
      data += EvaluateDeformationEnergy(space_, d.shape, path[d.index]).total;
    }
    *cost = data + spec_.sigma * spline;
    if (gradient == nullptr) return true;

    const auto clock = std::chrono::steady_clock::now();
    const int n3 = 3 * space_.num_vertices;
    std::vector<Eigen::VectorXd> grad(path.size(), Eigen::VectorXd::Zero(n3));
    for (const SplineDatum& d : spec_.data) {
      grad[d.index] +=
          EnergyGradient(space_, d.shape, path[d.index], ShellSide::kDeformed);
    }
    for (size_t t = 0; t < terms_.size(); ++t) {
      const Term& term = terms_[t];
      Midpoint& mid = *midpoints_[t];
      const Positions& s = path[term.center];
      grad[term.center] +=
          scale * EnergyGradient(space_, s, mid.m, ShellSide::kReference);
      if (!spec_.is_free[term.previous] && !spec_.is_free[term.next]) continue;
      // H_k p_k = -D_2 W[s_k, m_k] modulo rigid motions; the mixed blocks
      // applied to p_k as directional derivatives of the gradients.
      Eigen::VectorXd p;
      if (!mid.hessian.Solve(
              -EnergyGradient(space_, s, mid.m, ShellSide::kDeformed),
              kAdjointTolerance, &p)) {
        return false;
      }
      if (spec_.is_free[term.previous]) {
        grad[term.previous] +=
            scale * EnergyGradientDerivative(space_, path[term.previous], mid.m,
                                             ShellSide::kReference,
                                             ShellSide::kDeformed, p);
      }
      if (spec_.is_free[term.next]) {
        grad[term.next] +=
            scale * EnergyGradientDerivative(space_, mid.m, path[term.next],
                                             ShellSide::kDeformed,
                                             ShellSide::kReference, p);
      }
    }
    for (size_t i = 0; i < free_shapes_.size(); ++i) {
      Eigen::Map<Eigen::VectorXd>(gradient + i * n3, n3) =
          grad[free_shapes_[i]];
    }
    timings_.gradient_seconds += SecondsSince(clock);
  } catch (const InputError&) {
    return false;  // a degenerate shape or midpoint: reject the point
  }
  return true;
}

}  // namespace shellspace
