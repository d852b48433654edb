#include "shellspace/problems/splines/spline_initial_path.h"

#include <chrono>

#include "shellspace/geometry/named_values.h"
#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {

namespace {

constexpr NamedValue<SplineInit> kSplineInitNames[] = {
    {SplineInit::kLTheta, "ltheta"}, {SplineInit::kGeodesic, "geodesic"}};

}  // namespace

SplineInit ParseSplineInit(const std::string& name) {
  return ParseNamedValue(kSplineInitNames, name, "the initial path");
}

const char* SplineInitName(SplineInit init) {
  return NameOf(kSplineInitNames, init);
}

ShellPath PiecewiseGeodesicPath(const ShellSpace& space,
                                const std::vector<Positions>& keyframes,
                                const std::vector<int>& at, int steps,
                                bool periodic, const SolverSettings& settings,
                                std::vector<GeodesicSegment>* segments) {
  CheckSplineKeyframes(keyframes.size(), at, steps, periodic);
  const int n = static_cast<int>(at.size());
  const int count = periodic ? steps : steps + 1;
  // Linear where a stop request leaves segments unsolved.
  ShellPath path = PiecewiseLinearPath(keyframes, at, steps, periodic);
  if (segments != nullptr) segments->clear();
  const int segments_to_solve = periodic ? n : n - 1;
  for (int i = 0;
       i < segments_to_solve && !settings.stop.stop_requested(); ++i) {
    const int next = (i + 1) % n;
    GeodesicSegment segment;
    segment.from = at[i];
    segment.to = i + 1 < n ? at[i + 1] : at[0] + steps;
    GeodesicInput input = GeodesicInput::Between(
        keyframes[i], keyframes[next], segment.to - segment.from);
    SolverSettings segment_settings = settings;
    segment_settings.progress_label =
        settings.progress_label + " segment " + std::to_string(segment.from) +
        "-" + std::to_string(segment.to);
    const GeodesicResult g = SolveGeodesic(space, input, segment_settings);
    for (int k = segment.from; k <= segment.to; ++k) {
      path[k % count] = g.path[k - segment.from];
    }
    segment.path_energy = g.path_energy;
    segment.iterations = g.iterations;
    segment.converged = g.converged;
    if (segments != nullptr) segments->push_back(segment);
  }
  // The keyframes exactly (a geodesic's ends are data, this makes it plain).
  for (int i = 0; i < n; ++i) path[at[i]] = keyframes[i];
  return path;
}

SplineInitialPath MakeSplineInitialPath(SplineInit init,
                                        const ShellSpace& space,
                                        const std::vector<Positions>& keyframes,
                                        const std::vector<int>& at, int steps,
                                        bool periodic,
                                        const SolverSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  SplineInitialPath out;
  out.init = init;
  out.path = init == SplineInit::kGeodesic
                 ? PiecewiseGeodesicPath(space, keyframes, at, steps, periodic,
                                         settings, &out.segments)
                 : LThetaSpline(space, keyframes, at, steps, periodic,
                                settings, &out.ltheta);
  out.seconds = std::chrono::duration<double>(
                    std::chrono::steady_clock::now() - start)
                    .count();
  return out;
}

}  // namespace shellspace
