#include "problems/spline_energy.h"

#include <cmath>

#include "cost_functions/energy_derivatives.h"
#include "problems/gauge_reduced_solve.h"

namespace shellspace {

namespace {

// Up to two Newton steps on G(m) = D_2 W[a, m] + D_1 W[m, b] = 0 with the
// exact Hessian: LM stops with |m - m*| ~ sqrt(eps) relative, which makes
// F_K noisy at 1e-8; Newton's quadratic convergence brings m to round-off.
void PolishMidpoint(const ShellSpace& space, const Positions& a,
                    const Positions& b, Positions* m) {
  for (int step = 0; step < 2; ++step) {
    const Eigen::VectorXd g =
        EnergyGradient(space, a, *m, ShellSide::kDeformed) +
        EnergyGradient(space, *m, b, ShellSide::kReference);
    const double scale = EnergyGradient(space, a, *m, ShellSide::kDeformed)
                             .cwiseAbs()
                             .maxCoeff();
    if (g.cwiseAbs().maxCoeff() <= 1e-13 * std::max(scale, 1e-300)) return;
    const SparseMatrix h =
        EnergyHessianColumns(space, a, *m, ShellSide::kDeformed).second +
        EnergyHessianColumns(space, *m, b, ShellSide::kReference).first;
    const Eigen::VectorXd dm = SolveModuloRigidMotions(h, -g, *m);
    Positions candidate = *m;
    Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) += dm;
    const Eigen::VectorXd g_new =
        EnergyGradient(space, a, candidate, ShellSide::kDeformed) +
        EnergyGradient(space, candidate, b, ShellSide::kReference);
    if (!(g_new.cwiseAbs().maxCoeff() < g.cwiseAbs().maxCoeff())) return;
    *m = candidate;
  }
}

}  // namespace

SplineObjective::SplineObjective(const ShellSpace& space, SplineSpec spec,
                                 const SolverSettings& inner_settings)
    : space_(space), spec_(std::move(spec)), inner_settings_(inner_settings) {
  const int K = spec_.steps;
  const int shapes = spec_.periodic ? K : K + 1;
  if (K < 2) throw InputError("--steps must be at least 2 for a spline");
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
  midpoints_.resize(terms_.size());
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

double SplineObjective::SplineEnergyOf(const ShellPath& path) const {
  const double K = spec_.steps;
  double sum = 0;
  for (size_t t = 0; t < terms_.size(); ++t) {
    const Term& term = terms_[t];
    const Positions& a = path[term.previous];
    const Positions& b = path[term.next];
    const Positions initial =
        midpoints_[t].size() ? midpoints_[t] : Positions(0.5 * (a + b));
    ceres::Solver::Summary summary;
    midpoints_[t] = SolveWeightedMidpoint(space_, a, b, 1.0, 1.0, initial, {},
                                          inner_settings_, &summary);
    if (!summary.IsSolutionUsable()) return NAN;
    PolishMidpoint(space_, a, b, &midpoints_[t]);
    sum += EvaluateDeformationEnergy(space_, path[term.center], midpoints_[t])
               .total;
  }
  return 4 * K * K * K * sum;
}

bool SplineObjective::Evaluate(const double* parameters, double* cost,
                               double* gradient) const {
  const ShellPath path = PathFrom(parameters);
  const double K = spec_.steps;
  const double scale = spec_.sigma * 4 * K * K * K;
  try {
    const double spline = SplineEnergyOf(path);
    if (!std::isfinite(spline)) return false;
    double data = 0;
    for (const SplineDatum& d : spec_.data) {
      data += EvaluateDeformationEnergy(space_, d.shape, path[d.index]).total;
    }
    *cost = data + spec_.sigma * spline;
    if (gradient == nullptr) return true;

    const int n3 = 3 * space_.num_vertices;
    std::vector<Eigen::VectorXd> grad(path.size(), Eigen::VectorXd::Zero(n3));
    for (const SplineDatum& d : spec_.data) {
      grad[d.index] +=
          EnergyGradient(space_, d.shape, path[d.index], ShellSide::kDeformed);
    }
    for (size_t t = 0; t < terms_.size(); ++t) {
      const Term& term = terms_[t];
      const Positions& m = midpoints_[t];
      const Positions& s = path[term.center];
      grad[term.center] +=
          scale * EnergyGradient(space_, s, m, ShellSide::kReference);
      if (!spec_.is_free[term.previous] && !spec_.is_free[term.next]) continue;
      // W[s_{k-1}, m] with columns on m: (d_m D_1 W = mixed, D_2^2 W).
      const auto left = EnergyHessianColumns(space_, path[term.previous], m,
                                             ShellSide::kDeformed);
      // W[m, s_{k+1}] with columns on s_{k+1}: (d_{s_{k+1}} D_1 W, ...) and
      // with columns on m: (D_1^2 W, d_m D_2 W).
      const auto right_m = EnergyHessianColumns(space_, m, path[term.next],
                                                ShellSide::kReference);
      const SparseMatrix h = left.second + right_m.first;
      const Eigen::VectorXd rhs =
          -EnergyGradient(space_, s, m, ShellSide::kDeformed);
      const Eigen::VectorXd p = SolveModuloRigidMotions(h, rhs, m);
      // left.first = d_m D_1 W[s_{k-1}, m]: rows s_{k-1}, columns m.
      grad[term.previous] += scale * (left.first * p);
      // right_m.second = d_m D_2 W[m, s_{k+1}]: rows s_{k+1}, columns m.
      grad[term.next] += scale * (right_m.second * p);
    }
    for (size_t i = 0; i < free_shapes_.size(); ++i) {
      Eigen::Map<Eigen::VectorXd>(gradient + i * n3, n3) =
          grad[free_shapes_[i]];
    }
  } catch (const InputError&) {
    return false;  // a degenerate shape or midpoint: reject the point
  }
  return true;
}

}  // namespace shellspace
