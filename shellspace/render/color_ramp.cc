#include "shellspace/render/color_ramp.h"

#include <algorithm>
#include <cmath>

namespace shellspace {

Eigen::Vector3d RampColor(double s) {
  static const Eigen::Vector3d kStops[] = {
      {0.36, 0.30, 0.62}, {0.25, 0.50, 0.72}, {0.18, 0.66, 0.62},
      {0.50, 0.82, 0.36}, {0.99, 0.90, 0.15}};
  constexpr int kSegments = 4;
  if (!(s > 0)) return kStops[0];  // also NaN
  if (s >= 1) return kStops[kSegments];
  const double at = s * kSegments;
  const int k = std::min(kSegments - 1, static_cast<int>(std::floor(at)));
  const double f = at - k;
  return (1 - f) * kStops[k] + f * kStops[k + 1];
}

}  // namespace shellspace
