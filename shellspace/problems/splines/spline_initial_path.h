// A nonlinear spline's initial path (SolveSpline's `initial`): the LΘA
// spline, as the spec prescribes, or the piecewise geodesic through the
// keyframes -- and what making it took, for the reports.
#ifndef SHELLSPACE_PROBLEMS_SPLINES_SPLINE_INITIAL_PATH_H_
#define SHELLSPACE_PROBLEMS_SPLINES_SPLINE_INITIAL_PATH_H_

#include <string>
#include <vector>

#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"

namespace shellspace {

// The LThetaSpline (ltheta_spline.h) or PiecewiseGeodesicPath (below).
enum class SplineInit { kLTheta, kGeodesic };
// "ltheta" or "geodesic"; throws InputError for any other name.
SplineInit ParseSplineInit(const std::string& name);
// The name ParseSplineInit reads: "ltheta" or "geodesic".
const char* SplineInitName(SplineInit init);

// One segment of PiecewiseGeodesicPath: the geodesic from path index `from`
// to `to` (periodic: `to` may exceed K, indices taken mod K) and how its
// solve ended.
struct GeodesicSegment {
  int from = 0, to = 0;
  double path_energy = 0;  // E of the segment's to - from steps
  int iterations = 0;      // all stages of its SolveGeodesic
  bool converged = false;
};

// The piecewise geodesic through `keyframes` at `at` (SolveSpline's
// conventions, CheckSplineKeyframes): between consecutive keyframes, and if
// periodic from the last back to the first across index K, the discrete
// geodesic of at[i+1] - at[i] steps (SolveGeodesic with `settings`, no
// mask, rigid gauge). Its keyframes are exact and it has no acceleration
// inside a segment, so F_K comes only from the kinks at the inner
// keyframes: through cactus 2, 10, 17 at 0, 4, 8 (relative eta 1e-4, all
// solves to a relative gradient of 1e-10) its F_K is 1.10 against 71.0 for
// the LThetaSpline, three of whose reconstructions end at their iteration
// cap (14 s against 49 s to make).
// K + 1 shapes (K if periodic, as PiecewiseLinearPath). `segments`, if
// given, receives one record per segment solved, in order. A stop request
// (settings.stop) ends the loop after the current segment; the segments
// not solved keep the piecewise linear interpolation.
ShellPath PiecewiseGeodesicPath(const ShellSpace& space,
                                const std::vector<Positions>& keyframes,
                                const std::vector<int>& at, int steps,
                                bool periodic, const SolverSettings& settings,
                                std::vector<GeodesicSegment>* segments =
                                    nullptr);

// The initial path by `init` and its report: `ltheta` (LThetaSpline's,
// kLTheta) or `segments` (kGeodesic) filled, `seconds` of wall time spent.
struct SplineInitialPath {
  SplineInit init = SplineInit::kLTheta;
  ShellPath path;
  LThetaSplineReport ltheta;
  std::vector<GeodesicSegment> segments;
  double seconds = 0;
};
SplineInitialPath MakeSplineInitialPath(SplineInit init,
                                        const ShellSpace& space,
                                        const std::vector<Positions>& keyframes,
                                        const std::vector<int>& at, int steps,
                                        bool periodic,
                                        const SolverSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINES_SPLINE_INITIAL_PATH_H_
