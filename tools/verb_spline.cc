// `shellspace spline` and `shellspace regress`: Riemannian splines through
// keyframes (nonlinear or LΘA) and shape regression.
#include <gflags/gflags.h>

#include <chrono>
#include <iostream>

#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/path_summary.h"
#include "shellspace/tools/shell_inputs.h"
#include "shellspace/tools/verb.h"

DEFINE_string(keyframes, "", "spline: comma-separated keyframe shells");
DEFINE_string(method, "nonlinear",
              "spline: nonlinear (L-BFGS on F_K from the LTheta spline) or "
              "ltheta (the fast approximation alone)");
DEFINE_bool(periodic, false, "spline: closed path (indices mod K)");
DEFINE_double(sigma, 1.0, "regress: weight of the spline energy F_K (>= 0)");

namespace shellspace {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since)
      .count();
}

std::vector<int> ParseIndices(const std::string& list) {
  std::vector<int> at;
  for (const std::string& item : SplitList(list, "at")) {
    char* end = nullptr;
    const long value = std::strtol(item.c_str(), &end, 10);
    if (*end != '\0') throw InputError("--at: not an integer: '" + item + "'");
    at.push_back(static_cast<int>(value));
  }
  return at;
}

// Loads a comma list of compatible shells; returns them and the first mesh.
std::vector<Positions> LoadShells(const std::string& list,
                                  const std::string& flag, Mesh* first) {
  const std::vector<std::string> paths = SplitList(list, flag);
  *first = LoadShell(paths[0]);
  std::vector<Positions> shapes = {first->positions};
  for (size_t i = 1; i < paths.size(); ++i) {
    shapes.push_back(LoadCompatibleShell(paths[i], *first, paths[0]).positions);
  }
  return shapes;
}

SplineSettings SplineSettingsFromFlags(const std::string& label) {
  SplineSettings settings;
  settings.inner = SettingsFromFlags(label + " midpoint");
  settings.inner.progress = false;
  settings.inner.gradient_tolerance = 1e-10;
  settings.max_iterations = FLAGS_max_iterations;
  settings.gradient_tolerance = FLAGS_tolerance;
  settings.progress = !FLAGS_quiet;
  settings.progress_label = label;
  return settings;
}

void Report(const Faces& faces,
            const SplineResult& result, double seconds, JsonObject extra) {
  WritePathOutputs(FLAGS_output, faces, result.path);
  if (FLAGS_json) {
    std::cout << extra.Add("spline_energy", result.spline_energy)
                     .Add("data_energy", result.data_energy)
                     .Add("objective", result.objective)
                     .Add("iterations",
                          static_cast<int>(result.summary.iterations.size()))
                     .Add("termination",
                          result.summary.iterations.size() > 1
                              ? ceres::TerminationTypeToString(
                                    result.summary.termination_type)
                              : "not optimised")
                     .Add("seconds", seconds)
                     .Add("frames", static_cast<int>(result.path.size()))
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  } else if (!FLAGS_quiet) {
    std::cout << "F_K = " << result.spline_energy << "; wrote " << FLAGS_output
              << "/shape_*.ply\n";
  }
}

int RunSpline() {
  RequireFlag("keyframes", FLAGS_keyframes);
  RequireFlag("at", FLAGS_at);
  RequireFlag("output", FLAGS_output);
  if (FLAGS_method != "nonlinear" && FLAGS_method != "ltheta") {
    throw InputError("--method must be nonlinear or ltheta");
  }
  if (FLAGS_steps < 2) throw InputError("--steps must be at least 2");
  const auto clock = std::chrono::steady_clock::now();
  Mesh first;
  const std::vector<Positions> keyframes =
      LoadShells(FLAGS_keyframes, "keyframes", &first);
  const std::vector<int> at = ParseIndices(FLAGS_at);
  const ShellSpace space = SpaceFromFlags(first);
  SolverSettings ltheta_settings = SettingsFromFlags("ltheta");
  ltheta_settings.progress = false;
  const ShellPath ltheta = LThetaSpline(space, keyframes, at, FLAGS_steps,
                                        FLAGS_periodic, ltheta_settings);
  const double ltheta_seconds = Seconds(clock);
  SplineSettings settings = SplineSettingsFromFlags("spline");
  if (FLAGS_method == "ltheta") settings.max_iterations = 0;
  SplineResult result = SolveSpline(space, keyframes, at, FLAGS_steps,
                                    FLAGS_periodic, ltheta, settings);
  Report(first.faces, result, Seconds(clock),
         JsonObject()
             .Add("method", FLAGS_method)
             .Add("ltheta_seconds", ltheta_seconds));
  return 0;
}

int RunRegress() {
  RequireFlag("inputs", FLAGS_inputs);
  RequireFlag("at", FLAGS_at);
  RequireFlag("output", FLAGS_output);
  if (FLAGS_steps < 2) throw InputError("--steps must be at least 2");
  const auto clock = std::chrono::steady_clock::now();
  Mesh first;
  const std::vector<Positions> inputs =
      LoadShells(FLAGS_inputs, "inputs", &first);
  const std::vector<int> at = ParseIndices(FLAGS_at);
  const ShellSpace space = SpaceFromFlags(first);
  const SplineResult result =
      SolveRegression(space, inputs, at, FLAGS_steps, FLAGS_sigma, {},
                      SplineSettingsFromFlags("regress"));
  Report(first.faces, result, Seconds(clock),
         JsonObject().Add("sigma", FLAGS_sigma));
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "spline",
    "spline --keyframes a.ply,b.ply,c.ply --at 0,4,8 --steps 8 --output DIR "
    "[--method nonlinear|ltheta] [--periodic] [--json] [--png strip.png]",
    shellspace::RunSpline);
SHELLSPACE_REGISTER_VERB(
    "regress",
    "regress --inputs a.ply,b.ply,... --at 0,3,... --steps K --sigma S "
    "--output DIR [--json] [--png strip.png]",
    shellspace::RunRegress);
