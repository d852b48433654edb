// Helpers that let the per-element formulas be written once for double and for
// ceres::Jet (used to differentiate the analytic gradients into Hessians).
#ifndef SHELLSPACE_GEOMETRY_SCALAR_TRAITS_H_
#define SHELLSPACE_GEOMETRY_SCALAR_TRAITS_H_

#include <ceres/jet.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace shellspace {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

// The plain double value of a scalar (its real part for a Jet); used only to
// choose between algebraically equal branches (series vs closed form).
inline double ScalarValue(double x) { return x; }
template <typename T, int N>
inline double ScalarValue(const ceres::Jet<T, N>& x) {
  return ScalarValue(x.a);
}

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_SCALAR_TRAITS_H_
