// `shellspace spline` and `shellspace regress`: Riemannian splines through
// keyframes (nonlinear or LΘA) and shape regression.
#include <gflags/gflags.h>

#include <algorithm>
#include <chrono>
#include <iostream>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/splines/spline_initial_path.h"
#include "shellspace/workflows/regress.h"
#include "shellspace/workflows/spline.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "tools/verbs/geodesic_solve.h"
#include "tools/verbs/path_summary.h"
#include "tools/run/run_paths.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb.h"

DEFINE_string(keyframes, "", "spline: keyframe shells");
DEFINE_string(method, "nonlinear", "spline: nonlinear or ltheta");
DEFINE_bool(periodic, false, "spline: closed path");
DEFINE_double(sigma, 1.0, "regress: weight of F_K");
DEFINE_bool(energy, true, "spline --method ltheta: evaluate F_K");

namespace {
// The inner solves of spline and regress (each midpoint of F_K, each LΘA
// reconstruction) have their own iteration limit, not --max_iterations
// (which caps the outer L-BFGS only).
constexpr int kInnerMaxIterations = 200;
}  // namespace

namespace shellspace {
namespace {

const char* const kSplineModel =
    "64 MB + 24 B x (K + 1)^2 + 20 KB x #V x (K + 1)";

// The path flags of spline and regress, --steps defaulting to `steps`.
FlagTable PathFlags(int steps) {
  return {
      IntegerFlag("steps",
                  "number of time steps K (K + 1 shapes)" +
                      StepsBoundText(kSplineModel),
                  2, kMaxSteps)
          .Default(FlagDefault(steps)),
      TextFlag("output", "directory of the frames shape_000.ply ...")
          .Required(),
      PngFlag(),
      GltfFlag(),
      HtmlFlag(),
  };
}

FlagTable SplineFlags() {
  return Flags(
      {{
           TextFlag("keyframes", "comma-separated keyframe shells").Required(),
           TextFlag("at",
                    "comma-separated time indices of the keyframes "
                    "(0 and K among them unless --periodic)")
               .Required(),
           TextFlag("method",
                    "nonlinear (L-BFGS on F_K from the LTheta "
                    "spline) or ltheta (the fast approximation "
                    "alone)")
               .Default(workflows::SplineMethodName(workflows::SplineOptions().method)),
           TextFlag("init",
                    "the initial path of --method nonlinear: ltheta "
                    "(the LTheta spline) or geodesic (the piecewise "
                    "geodesic through the keyframes: no LM "
                    "reconstructions, zero acceleration between "
                    "keyframes; try it when keyframes are far apart "
                    "and the LTheta frames stop at their iteration "
                    "cap). Either start's solves (LM per LTheta "
                    "frame, or per geodesic segment) stop at "
                    "--tolerance, " +
                        std::to_string(kInnerMaxIterations) +
                        " iterations each at most")
               .Default(SplineInitName(workflows::SplineOptions().init))
               .Check([](const std::string& name) { ParseSplineInit(name); }),
           TextFlag("periodic", "closed path (indices mod K)")
               .Default(BoolFlagDefault(workflows::SplineOptions().periodic)),
           TextFlag("energy",
                    "--method ltheta: also evaluate F_K of the "
                    "result for the report (one midpoint solve per "
                    "step; --energy=false skips it)")
               .Default(
                   BoolFlagDefault(workflows::SplineOptions().evaluate_energy)),
       },
       PathFlags(workflows::SplineOptions().steps),
       MaterialFlags(),
       SolverFlags(),
       JsonFlag(),
       FilmStripFlags()});
}

FlagTable RegressFlags() {
  return Flags(
      {{
           TextFlag("inputs", "comma-separated input shells").Required(),
           TextFlag("at", "comma-separated time indices of the inputs")
               .Required(),
           RealFlag("sigma", "weight of the spline energy F_K", 0, End::kClosed)
               .Default(FlagDefault(workflows::RegressOptions().sigma)),
       },
       PathFlags(workflows::RegressOptions().steps),
       MaterialFlags(),
       SolverFlags(),
       JsonFlag(),
       FilmStripFlags()});
}

// --steps within the memory estimate of the spline (and, for
// --init geodesic, of its longest geodesic segment), before any solve.
void CheckSplineMemory(int vertices, const std::vector<int>& at,
                       bool geodesic_init) {
  const std::string size = "--steps " + std::to_string(FLAGS_steps) + " on " +
                           std::to_string(vertices) + " vertices";
  CheckMemory(SplineBytes(vertices, FLAGS_steps), size, kSplineModel);
  CheckPngMemory(FLAGS_steps + 1);
  if (!geodesic_init || at.empty()) return;
  int longest = FLAGS_periodic ? at.front() + FLAGS_steps - at.back() : 0;
  for (size_t i = 1; i < at.size(); ++i) {
    longest = std::max(longest, at[i] - at[i - 1]);
  }
  CheckMemory(GeodesicBytes(vertices, longest),
              "--init geodesic: a segment of " + std::to_string(longest) +
                  " steps on " + std::to_string(vertices) + " vertices",
              kGeodesicModel);
}

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
    if (!at.empty() && value <= at.back()) {
      throw InputError("--at must be strictly increasing, got " + list);
    }
    at.push_back(static_cast<int>(value));
  }
  return at;
}

// --at gives one index per shape of the list `flag`.
void CheckIndexCount(const std::vector<int>& at, size_t shapes,
                     const std::string& flag) {
  if (at.size() != shapes) {
    throw InputError("--at gives " + std::to_string(at.size()) +
                     " indices for " + std::to_string(shapes) + " --" + flag);
  }
}

SplineSettings SplineSettingsFromFlags(const std::string& label) {
  SplineSettings settings;
  settings.inner = SettingsFromFlags(label + " midpoint");
  settings.inner.progress = false;
  settings.inner.gradient_tolerance = 1e-10;
  settings.inner.max_iterations = kInnerMaxIterations;
  settings.stop = settings.inner.stop;  // the outer loop stops,
  settings.inner.stop = StopToken();     // every F_K evaluation is exact
  settings.max_iterations = FLAGS_max_iterations;
  settings.gradient_tolerance = FLAGS_tolerance;
  settings.progress = !FLAGS_quiet;
  settings.progress_label = label;
  return settings;
}

// Writes the frames and `summary` (a spline's SplineJson) with the verb's
// last keys, prints it or the one-line result; returns the exit code.
int CommitSplineRun(const RunStatus& status, const Faces& faces,
                    const SplineResult& result, JsonObject summary) {
  RunDirectory output(FLAGS_output);
  WritePathOutputs(&output, faces, result.path);
  const std::string text = output.Commit(std::move(
      summary.Add("bending_model", FLAGS_bending).Add("output", FLAGS_output)));
  if (FLAGS_json) {
    std::cout << text << "\n";
  } else if (!FLAGS_quiet) {
    if (result.evaluated) {
      std::cout << "F_K = " << result.spline_energy;
    } else {
      std::cout << "F_K not evaluated (stopped before its first evaluation "
                   "finished)";
    }
    std::cout << "; wrote " << FLAGS_output << "/shape_*.ply\n";
  }
  return status.Finish();
}

// Flags -> options -> the workflow -> frames and summary.
int RunSpline() {
  const workflows::SplineMethod method =
      workflows::ParseSplineMethod(FLAGS_method, "--method");
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputList("keyframes", FLAGS_keyframes)
      .OutputDirectory("output", FLAGS_output)
      .OutputPng("png", FLAGS_png)
      .OutputGlb("gltf", FLAGS_gltf)
      .OutputHtml("html", FLAGS_html)
      .Check();
  const ShellSet set = LoadShellList(FLAGS_keyframes, "keyframes");
  workflows::SplineOptions options;
  options.at = ParseIndices(FLAGS_at);
  CheckIndexCount(options.at, set.shapes.size(), "keyframes");
  options.init = ParseSplineInit(FLAGS_init);
  workflows::CheckSplineMethod(method, options.init, "--method", "--init");
  CheckSplineMemory(set.first.mesh.num_vertices(), options.at,
                    options.init == SplineInit::kGeodesic);
  options.reference = set.first.mesh;
  options.topology = set.first.topology;
  options.keyframes = set.shapes;
  options.steps = FLAGS_steps;
  options.periodic = FLAGS_periodic;
  options.method = method;
  options.evaluate_energy = FLAGS_energy;
  options.material = MaterialChoiceFromFlags(set.first.mesh);
  options.init_settings = SettingsFromFlags("spline " + FLAGS_init);
  options.init_settings.progress = false;
  options.init_settings.max_iterations = kInnerMaxIterations;
  options.settings = SplineSettingsFromFlags("spline");
  if (!FLAGS_quiet) {
    options.log = [](const std::string& line) {
      std::cerr << "spline: " << line << "\n";
    };
  }
  const workflows::SplineResult result = workflows::RunSpline(options);
  RunStatus status("spline");
  RecordWorkflow(result.status, {}, "spline", &status);
  if (!result.energy_evaluated) {
    RunDirectory output(FLAGS_output);
    WritePathOutputs(&output, set.first.mesh.faces, result.path());
    const std::string summary = output.Commit(
        workflows::ToJson(result, Seconds(clock))
            .Add("material", workflows::MaterialChoiceJson(options.material,
                                                           set.first.mesh))
            .Add("bending_model", FLAGS_bending)
            .Add("output", FLAGS_output));
    if (FLAGS_json) std::cout << summary << "\n";
    return status.Finish();
  }
  return CommitSplineRun(
      status, set.first.mesh.faces, result.spline,
      workflows::ToJson(result, Seconds(clock))
          .Add("material", workflows::MaterialChoiceJson(options.material,
                                                         set.first.mesh)));
}

// Flags -> options -> the workflow -> frames and summary.
int RunRegress() {
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputList("inputs", FLAGS_inputs)
      .OutputDirectory("output", FLAGS_output)
      .OutputPng("png", FLAGS_png)
      .OutputGlb("gltf", FLAGS_gltf)
      .OutputHtml("html", FLAGS_html)
      .Check();
  const ShellSet set = LoadShellList(FLAGS_inputs, "inputs");
  workflows::RegressOptions options;
  options.at = ParseIndices(FLAGS_at);
  CheckIndexCount(options.at, set.shapes.size(), "inputs");
  CheckSplineMemory(set.first.mesh.num_vertices(), options.at, false);
  options.reference = set.first.mesh;
  options.topology = set.first.topology;
  options.inputs = set.shapes;
  options.steps = FLAGS_steps;
  options.sigma = FLAGS_sigma;
  options.material = MaterialChoiceFromFlags(set.first.mesh);
  options.settings = SplineSettingsFromFlags("regress");
  const workflows::RegressResult result = workflows::RunRegress(options);
  RunStatus status("regress");
  RecordWorkflow(result.status, {}, "regress", &status);
  return CommitSplineRun(
      status, set.first.mesh.faces, result.spline,
      workflows::ToJson(result, Seconds(clock))
          .Add("material", workflows::MaterialChoiceJson(options.material,
                                                         set.first.mesh)));
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "spline",
    "spline --keyframes a.ply,b.ply,c.ply --at 0,4,8 --steps 8 --output DIR "
    "[--method nonlinear|ltheta] [--init ltheta|geodesic] [--energy=false] "
    "[--periodic] [--json] [--png strip.png] [--gltf path.glb] [--html path.html]",
    shellspace::SplineFlags(), shellspace::RunSpline);
SHELLSPACE_REGISTER_VERB(
    "regress",
    "regress --inputs a.ply,b.ply,... --at 0,3,... --steps K --sigma S "
    "--output DIR [--json] [--png strip.png] [--gltf path.glb] [--html path.html]",
    shellspace::RegressFlags(), shellspace::RunRegress);
