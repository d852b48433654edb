// Interpolating cubic splines of many scalar series at once (docs/math.md,
// "Riemannian splines", LΘA spline: every edge length, area and dihedral angle
// is one series over the keyframes).
//
// Knots t_0 < ... < t_{m-1} with values y_j. On [t_j, t_{j+1}], h_j =
// t_{j+1} - t_j, the spline in terms of its second derivatives M_j is
//
//   S(t) = M_j (t_{j+1} - t)^3 / (6 h_j) + M_{j+1} (t - t_j)^3 / (6 h_j)
//        + (y_j / h_j - M_j h_j / 6) (t_{j+1} - t)
//        + (y_{j+1} / h_j - M_{j+1} h_j / 6) (t - t_j),
//
// and C^2 continuity gives, at every interior knot,
//
//   h_{j-1} M_{j-1} + 2 (h_{j-1} + h_j) M_j + h_j M_{j+1}
//     = 6 ((y_{j+1} - y_j) / h_j - (y_j - y_{j-1}) / h_{j-1}).
//
// - Natural: M_0 = M_{m-1} = 0. Outside [t_0, t_{m-1}] the spline continues
//   linearly (S'' = 0 there too). m = 1: constant; m = 2: linear.
// - Periodic with period P > t_{m-1} - t_0: the knots are taken modulo P
//   (t_m = t_0 + P, y_m = y_0) and the equations above hold at every knot,
//   indices mod m (a cyclic system). m = 1: constant.
//
// The spline is linear in the data, so it is computed as a weight matrix
// (one row per evaluation time, one column per knot) applied to the values.
#ifndef SHELLSPACE_PROBLEMS_SPLINES_CUBIC_SPLINE_H_
#define SHELLSPACE_PROBLEMS_SPLINES_CUBIC_SPLINE_H_

#include <Eigen/Core>
#include <vector>

namespace shellspace {

enum class SplineEnds { kNatural, kPeriodic };

// The matrix W (times.size() x knots.size()) with S(times[r]) = sum_j W(r, j)
// y_j for every data y. `knots` strictly increasing (at least one);
// `period` is used only for kPeriodic and must exceed knots.back() -
// knots.front(). Throws InputError on bad knots or period.
Eigen::MatrixXd CubicSplineWeights(const std::vector<double>& knots,
                                   const std::vector<double>& times,
                                   SplineEnds ends, double period = 0);

// Interpolates many series at once: `values` has one row per knot and one
// column per series; returns one row per time (W * values).
Eigen::MatrixXd InterpolateCubicSpline(const std::vector<double>& knots,
                                       const Eigen::MatrixXd& values,
                                       const std::vector<double>& times,
                                       SplineEnds ends, double period = 0);

// The spline through values at integer knots `at`, evaluated at the integer
// times 0, 1, ..., steps (periodic: period `steps`, knots in [0, steps), and
// row `steps` equals row 0).
Eigen::MatrixXd InterpolateCubicSplineAtSteps(const std::vector<int>& at,
                                              const Eigen::MatrixXd& values,
                                              int steps, SplineEnds ends);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINES_CUBIC_SPLINE_H_
