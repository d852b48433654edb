#include "shellspace/workflows/spline.h"

#include <sstream>
#include <utility>

#include "shellspace/geometry/named_values.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/workflows/regress.h"

namespace shellspace {
namespace workflows {
namespace {

// What a path that is the LΘA spline alone failed to reach: "" if every
// frame's reconstruction converged.
std::string LThetaFailure(const LThetaSplineReport& report, double tolerance,
                          int max_iterations) {
  const std::vector<int> frames = report.unconverged_frames();
  if (frames.empty()) return "";
  std::string list;
  for (size_t i = 0; i < frames.size(); ++i) {
    list += (i ? ", " : "") + std::to_string(frames[i]);
  }
  return "spline: the LΘA reconstruction of frame(s) " + list +
         " stopped short of the tolerance " + ShortNumber(tolerance) + " (" +
         std::to_string(max_iterations) + " LM iterations each at most)";
}

void Log(const SplineOptions& options, const std::string& line) {
  if (options.log) options.log(line);
}

}  // namespace

namespace {

constexpr NamedValue<SplineMethod> kSplineMethodNames[] = {
    {SplineMethod::kNonlinear, "nonlinear"}, {SplineMethod::kLTheta, "ltheta"}};

}  // namespace

SplineMethod ParseSplineMethod(const std::string& value,
                               const std::string& name) {
  return ParseNamedValue(kSplineMethodNames, value, name);
}

const char* SplineMethodName(SplineMethod method) {
  return NameOf(kSplineMethodNames, method);
}

void CheckSplineMethod(SplineMethod method, SplineInit init,
                       const std::string& method_name,
                       const std::string& init_name) {
  if (method == SplineMethod::kLTheta && init != SplineInit::kLTheta) {
    throw InputError(init_name + " " + SplineInitName(init) + " needs " +
                     method_name + " nonlinear (" + method_name +
                     " ltheta is the LΘA spline itself)");
  }
}

SplineResult RunSpline(const SplineOptions& options) {
  CheckSplineMethod(options.method, options.init, "method", "init");
  const bool alone = options.method == SplineMethod::kLTheta;
  SplineResult result;
  result.reference = options.reference;
  result.method = SplineMethodName(options.method);
  result.material = options.material;
  const ShellSpace space(options.reference, options.topology,
                         options.material.material);
  SolverSettings init_settings = options.init_settings;
  SplineSettings settings = options.settings;
  const StopRecorder init_stop(&init_settings);
  const StopRecorder spline_stop(&settings.stop);

  Log(options, options.init == SplineInit::kLTheta ? "LTheta spline"
                                                   : "piecewise geodesic");
  result.initial =
      MakeSplineInitialPath(options.init, space, options.keyframes, options.at,
                            options.steps, options.periodic, init_settings);
  const SplineInitialPath& initial = result.initial;
  for (const GeodesicSegment& g : initial.segments) {
    std::ostringstream line;
    line << "geodesic " << g.from << "-" << g.to << ": E " << g.path_energy
         << ", " << g.iterations << " iterations"
         << (g.converged ? "" : ", NOT converged (kept as the guess)");
    Log(options, line.str());
  }
  if (options.init == SplineInit::kLTheta) {
    std::ostringstream line;
    line << "LTheta spline done (" << initial.seconds << " s, "
         << initial.ltheta.lm_iterations() << " LM iterations over "
         << initial.ltheta.solved_frames.size() << " frames)";
    Log(options, line.str());
    if (!alone && !initial.ltheta.unconverged_frames().empty() &&
        !init_stop.stopped()) {  // not the cap: the stop
      Log(options,
          "some LTheta frames stopped at their iteration cap, a far-off "
          "initial path (keyframes far apart?); init geodesic starts from "
          "the piecewise geodesic");
    }
  }
  std::vector<std::string> failures;
  const std::string ltheta_failure =
      alone ? LThetaFailure(initial.ltheta, settings.gradient_tolerance,
                            init_settings.max_iterations)
            : "";
  if (!ltheta_failure.empty()) failures.push_back(ltheta_failure);
  if (alone && !options.evaluate_energy) {
    result.spline.path = initial.path;
    result.spline.converged = ltheta_failure.empty();
  } else {
    if (alone) settings.max_iterations = 0;
    result.spline = SolveSpline(space, options.keyframes, options.at,
                                options.steps, options.periodic, initial.path,
                                settings);
    result.energy_evaluated = true;
    result.optimised = !alone;
    if (alone) {
      result.spline.converged = ltheta_failure.empty();
    } else {
      const std::string shortfall = SplineShortfall(
          "spline", result.spline, options.settings.gradient_tolerance);
      if (!shortfall.empty()) failures.push_back(shortfall);
    }
  }
  result.stopped = init_stop.stopped() || spline_stop.stopped();
  result.energy_split = PathEnergySplit(space, result.spline.path);
  result.status = StatusOf(std::move(failures), result.stopped);
  return result;
}

JsonObject ToJson(const SplineResult& result, double seconds) {
  JsonObject head;
  head.Add("method", result.method);
  AddSplineInitJson(head, result.initial);
  head.Add("energy_split", EnergySplitJson(result.energy_split));
  if (!result.energy_evaluated) {
    return head.Add("iterations", 0)
        .Add("converged", result.spline.converged)
        .Add("termination", "not optimised")
        .Add("seconds", seconds)
        .Add("frames", static_cast<int>(result.spline.path.size()));
  }
  return SplineJson(std::move(head), result.spline, seconds);
}

}  // namespace workflows
}  // namespace shellspace
