#include "shellspace/problems/splines/cubic_spline.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "shellspace/geometry/mesh.h"

namespace shellspace {
namespace {

// The matrix G (m x m) with M = G y: the knot second derivatives of the
// spline through y (cubic_spline.h). `h[j]` = length of interval j (m - 1
// intervals for natural ends, m for periodic ones).
Eigen::MatrixXd SecondDerivativeOperator(const std::vector<double>& h, int m,
                                         SplineEnds ends) {
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m, m);
  if (ends == SplineEnds::kNatural) {
    if (m < 3) return g;  // constant or linear: M = 0
    const int n = m - 2;  // unknowns M_1 .. M_{m-2}
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, m);
    for (int j = 1; j <= m - 2; ++j) {
      const int r = j - 1;
      if (r > 0) a(r, r - 1) = h[j - 1];
      a(r, r) = 2 * (h[j - 1] + h[j]);
      if (r < n - 1) a(r, r + 1) = h[j];
      d(r, j - 1) = 6 / h[j - 1];
      d(r, j) = -6 / h[j - 1] - 6 / h[j];
      d(r, j + 1) = 6 / h[j];
    }
    g.middleRows(1, n) = a.partialPivLu().solve(d);
    return g;
  }
  if (m < 2) return g;  // constant
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m, m);
  for (int j = 0; j < m; ++j) {
    const int prev = (j + m - 1) % m, next = (j + 1) % m;
    const double h_prev = h[prev], h_next = h[j];
    // "+=": with m = 2 the previous and the next knot coincide.
    a(j, prev) += h_prev;
    a(j, j) += 2 * (h_prev + h_next);
    a(j, next) += h_next;
    d(j, prev) += 6 / h_prev;
    d(j, j) += -6 / h_prev - 6 / h_next;
    d(j, next) += 6 / h_next;
  }
  return a.partialPivLu().solve(d);
}

}  // namespace

Eigen::MatrixXd CubicSplineWeights(const std::vector<double>& knots,
                                   const std::vector<double>& times,
                                   SplineEnds ends, double period) {
  const int m = static_cast<int>(knots.size());
  if (m < 1) throw InputError("cubic spline: no knots");
  for (int j = 0; j < m; ++j) {
    if (!std::isfinite(knots[j]) || (j > 0 && !(knots[j] > knots[j - 1]))) {
      throw InputError(
          "cubic spline: knots must be finite and strictly "
          "increasing");
    }
  }
  const bool periodic = ends == SplineEnds::kPeriodic;
  if (periodic &&
      !(period > knots.back() - knots.front() && std::isfinite(period))) {
    throw InputError("cubic spline: the period " + std::to_string(period) +
                     " must exceed the knot span");
  }
  const int intervals = periodic ? m : m - 1;
  std::vector<double> h(intervals);
  for (int j = 0; j < intervals; ++j) {
    const double next = j + 1 < m ? knots[j + 1] : knots.front() + period;
    h[j] = next - knots[j];
  }
  const Eigen::MatrixXd g = SecondDerivativeOperator(h, m, ends);

  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(times.size(), m);
  for (size_t r = 0; r < times.size(); ++r) {
    if (m == 1) {
      w(r, 0) = 1;
      continue;
    }
    double t = times[r];
    if (periodic) {
      double s = std::fmod(t - knots.front(), period);
      if (s < 0) s += period;
      t = knots.front() + s;
    } else if (t < knots.front() || t > knots.back()) {
      // Natural ends: linear continuation with the end slope,
      // S'(t_0) = (y_1 - y_0)/h_0 - h_0 (2 M_0 + M_1)/6,
      // S'(t_n) = (y_n - y_{n-1})/h + h (M_{n-1} + 2 M_n)/6.
      const bool left = t < knots.front();
      const int j = left ? 0 : m - 2;  // the end interval
      const double hj = h[j];
      Eigen::RowVectorXd slope = Eigen::RowVectorXd::Zero(m);
      slope(j) -= 1 / hj;
      slope(j + 1) += 1 / hj;
      if (left) {
        slope -= hj / 6 * (2 * g.row(j) + g.row(j + 1));
      } else {
        slope += hj / 6 * (g.row(j) + 2 * g.row(j + 1));
      }
      const int end = left ? 0 : m - 1;
      w.row(r) = (t - knots[end]) * slope;
      w(r, end) += 1;
      continue;
    }
    // The interval [t_j, t_{j+1}] holding t (the last one for t = t_{m-1}).
    const int upper = static_cast<int>(
        std::upper_bound(knots.begin(), knots.end(), t) - knots.begin());
    const int j = std::min(std::max(upper - 1, 0), intervals - 1);
    const int jn = (j + 1) % m;
    const double hj = h[j];
    const double s = t - knots[j], u = hj - s;  // t - t_j, t_{j+1} - t
    w(r, j) += u / hj;
    w(r, jn) += s / hj;
    w.row(r) += (u * u * u / (6 * hj) - hj * u / 6) * g.row(j) +
                (s * s * s / (6 * hj) - hj * s / 6) * g.row(jn);
  }
  return w;
}

Eigen::MatrixXd InterpolateCubicSpline(const std::vector<double>& knots,
                                       const Eigen::MatrixXd& values,
                                       const std::vector<double>& times,
                                       SplineEnds ends, double period) {
  if (values.rows() != static_cast<Eigen::Index>(knots.size())) {
    throw InputError("cubic spline: " + std::to_string(values.rows()) +
                     " value rows for " + std::to_string(knots.size()) +
                     " knots");
  }
  return CubicSplineWeights(knots, times, ends, period) * values;
}

Eigen::MatrixXd InterpolateCubicSplineAtSteps(const std::vector<int>& at,
                                              const Eigen::MatrixXd& values,
                                              int steps, SplineEnds ends) {
  if (steps < 1) throw InputError("cubic spline: steps must be >= 1");
  std::vector<double> knots(at.begin(), at.end());
  std::vector<double> times(steps + 1);
  for (int k = 0; k <= steps; ++k) times[k] = k;
  return InterpolateCubicSpline(knots, values, times, ends, steps);
}

}  // namespace shellspace
