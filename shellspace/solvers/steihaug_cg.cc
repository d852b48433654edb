#include "shellspace/solvers/steihaug_cg.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shellspace {
namespace {

// The tau >= 0 with |p + tau d|_M = radius, from p^T M p, p^T M d, d^T M d
// (|p|_M <= radius, d != 0).
double StepToBoundary(double pmp, double pmd, double dmd, double radius) {
  const double c = pmp - radius * radius;  // <= 0
  const double discriminant = std::max(0.0, pmd * pmd - dmd * c);
  // The positive root of dmd tau^2 + 2 pmd tau + c, in the form without
  // cancellation.
  const double root = std::sqrt(discriminant);
  if (pmd >= 0) return -c / (pmd + root > 0 ? pmd + root : 1e-300);
  return (root - pmd) / dmd;
}

}  // namespace

SteihaugResult SolveSteihaugCg(const Eigen::SparseMatrix<double>& lower,
                               const Eigen::VectorXd& g,
                               const Preconditioner& preconditioner,
                               double radius, double tolerance,
                               int max_iterations) {
  const auto h = lower.selfadjointView<Eigen::Lower>();
  const int n = static_cast<int>(g.size());
  const bool bounded = std::isfinite(radius);
  SteihaugResult result;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd r = g;  // the model's gradient g + H p
  Eigen::VectorXd z = preconditioner.Apply(r);
  Eigen::VectorXd d = -z;
  double rz = r.dot(z);
  // M-inner products of p and d (M z = r and r_{j+1} . d_j = 0 give the
  // recurrences below without products with M).
  double pmp = 0, pmd = 0, dmd = rz;
  const double target = tolerance * g.norm();
  Eigen::VectorXd hd(n);
  const auto finish = [&](SteihaugResult::Stop stop) {
    result.stop = stop;
    result.step = p;
    result.step_norm = std::sqrt(std::max(0.0, pmp));
    // -m(p) = -(g . p + 1/2 p^T H p) = -1/2 (g + r) . p with r = g + H p.
    result.model_decrease = -0.5 * (g + r).dot(p);
    return result;
  };
  if (!(g.norm() > 0) || !(rz > 0)) return finish(SteihaugResult::Stop::kConverged);
  for (int j = 0; j < max_iterations; ++j) {
    hd.noalias() = h * d;
    ++result.iterations;
    const double curvature = d.dot(hd);
    if (!(curvature > 0)) {
      if (bounded) {
        const double tau = StepToBoundary(pmp, pmd, dmd, radius);
        p += tau * d;
        r += tau * hd;
        pmp = radius * radius;
      } else if (j == 0) {
        p = d;  // the preconditioned steepest-descent step
        r += hd;
        pmp = dmd;
      }
      return finish(SteihaugResult::Stop::kNegativeCurvature);
    }
    const double alpha = rz / curvature;
    const double next_pmp = pmp + 2 * alpha * pmd + alpha * alpha * dmd;
    if (bounded && next_pmp >= radius * radius) {
      const double tau = StepToBoundary(pmp, pmd, dmd, radius);
      p += tau * d;
      r += tau * hd;
      pmp = radius * radius;
      return finish(SteihaugResult::Stop::kBoundary);
    }
    p += alpha * d;
    r += alpha * hd;
    pmp = next_pmp;
    if (r.norm() <= target) return finish(SteihaugResult::Stop::kConverged);
    z = preconditioner.Apply(r);
    const double rz_next = r.dot(z);
    const double beta = rz_next / rz;
    rz = rz_next;
    pmd = beta * (pmd + alpha * dmd);
    dmd = rz + beta * beta * dmd;
    d = -z + beta * d;
  }
  return finish(SteihaugResult::Stop::kMaxIterations);
}

}  // namespace shellspace
