// The colour ramp of scalar maps on the surface (film strips coloured by
// displacement): a hand-picked viridis-like ramp, violet through blue, teal
// and green to yellow, with its lightness rising monotonically and kept
// away from black so the shading stays readable on top of it.
#ifndef SHELLSPACE_RENDER_COLOR_RAMP_H_
#define SHELLSPACE_RENDER_COLOR_RAMP_H_

#include <Eigen/Core>

namespace shellspace {

// The colour (RGB in [0, 1]) of the value s in [0, 1]: piecewise linear
// between five stops at s = 0, 0.25, 0.5, 0.75, 1,
//   (0.36, 0.30, 0.62)  violet
//   (0.25, 0.50, 0.72)  blue
//   (0.18, 0.66, 0.62)  teal
//   (0.50, 0.82, 0.36)  green
//   (0.99, 0.90, 0.15)  yellow
// (relative luminance 0.34, 0.46, 0.56, 0.72, 0.87). s is clamped to [0, 1];
// NaN gives the first stop.
Eigen::Vector3d RampColor(double s);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_COLOR_RAMP_H_
