// `shellspace demo`: the built-in example. A procedural finger and the same
// finger bent by 90 degrees; the discrete geodesic between them (K = 8, base
// held fixed), extrapolated 4 more steps by the exponential map; PLY frames,
// a JSON summary, a PNG film strip and the viewer page (viewer.html) in
// --output (default ./demo-output).
#include <gflags/gflags.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/render/html_viewer.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/reports/relative_gradient.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "tools/verbs/geodesic_solve.h"
#include "tools/verbs/path_summary.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/run/run_output.h"
#include "tools/run/run_paths.h"
#include "tools/verbs/verb.h"

DEFINE_int32(extrapolate, 4, "demo: EXP steps beyond the end shape");

namespace shellspace {
namespace {

const char* const kDemoPathModel = "64 MB + 200 B x #V x (K + E + 1)";

FlagTable DemoFlags() {
  return Flags({{
                    TextFlag("output",
                             "directory of frames/, film_strip.png, "
                             "viewer.html and summary.json")
                        .Default("demo-output"),
                    IntegerFlag("steps",
                                "time steps K of the geodesic (K + 1 shapes)" +
                                    StepsBoundText(kGeodesicModel),
                                2, kMaxSteps),
                    IntegerFlag("extrapolate",
                                "EXP steps E beyond the end shape" +
                                    StepsBoundText(kDemoPathModel),
                                0, kMaxSteps),
                    GltfFlag(),
                },
                MaterialFlags(), SolverFlags(), FilmStripFlags()});
}

// Refuses --steps and --extrapolate whose geodesic or path would not fit in
// memory on `finger`.
void CheckDemoMemory(const Mesh& finger) {
  const std::string size =
      " on " + std::to_string(finger.num_vertices()) + " vertices";
  CheckMemory(GeodesicBytes(finger.num_vertices(), FLAGS_steps),
              "--steps " + std::to_string(FLAGS_steps) + size, kGeodesicModel);
  CheckMemory(
      PathBytes(finger.num_vertices(), FLAGS_steps + FLAGS_extrapolate + 1),
      "--steps " + std::to_string(FLAGS_steps) + " --extrapolate " +
          std::to_string(FLAGS_extrapolate) + size,
      kDemoPathModel);
}

// The film strip's options (the flags', seen from the front, 7 frames a
// row), its memory checked for every frame of the demo.
RenderOptions DemoFilmStripOptions() {
  RenderOptions options = FilmStripOptionsFromFlags();
  options.view = ParseView("front");  // the bend lies in the x-y plane
  options.max_per_row = 7;
  CheckFilmStripMemory(FLAGS_steps + FLAGS_extrapolate + 1, options,
                       "film_strip.png");
  return options;
}

// Extends `frames` (the geodesic) by --extrapolate EXP steps from its last
// two shapes, the base held fixed; the shot (empty without --extrapolate).
ShootResult ExtrapolateDemoPath(const ShellSpace& space,
                                const std::vector<int>& base,
                                SolverSettings* settings, ShellPath* frames) {
  ShootResult shot;
  if (FLAGS_extrapolate > 0) {
    settings->progress_label = "demo exp";
    const int K = FLAGS_steps;
    shot = ShootWithReport(space, (*frames)[K - 1], (*frames)[K],
                           FLAGS_extrapolate + 1, StepDirection::kForward, base,
                           *settings);
    frames->insert(frames->end(), shot.path.begin() + 2, shot.path.end());
  }
  return shot;
}

// Writes the viewer page, the PLY frames, the glTF animation (with --gltf)
// and the film strip of `frames` into `output`.
void WriteDemoFiles(RunDirectory* output, const Mesh& finger,
                    const ShellPath& frames, const RenderOptions& options) {
  output->AddFileOfSummary(
      "viewer.html", [&finger, &frames](const std::string& text) {
        return EncodeHtmlViewer(frames, finger.faces, "shellspace demo", text);
      });
  WriteFrames(output->File("frames"), finger.faces, frames);
  if (!FLAGS_gltf.empty()) {
    output->AddOutside(FLAGS_gltf,
                       EncodeGltfMorphAnimation(frames, finger.faces));
  }
  WriteFilmStrip(frames, finger.faces, options, output->File("film_strip.png"));
}

// The demo's summary.json: the geodesic's report, with the EXP steps of the
// extrapolation added to iterations and stages; the extrapolated steps'
// energies (the shot's, after its first step, which is the geodesic's last)
// beside it.
JsonObject DemoSummary(const GeodesicResult& geodesic, const ShootResult& shot,
                       int frames, double seconds, const std::string& dir,
                       const workflows::MaterialChoice& material,
                       const Mesh& finger) {
  const ShootTotals totals = TotalsOf(shot);
  const int shot_iterations = totals.iterations;
  const bool shot_converged = totals.converged;
  std::vector<JsonObject> stages = GeodesicStages(geodesic);
  for (const JsonObject& stage : ExpStepStages(shot)) stages.push_back(stage);
  const std::vector<double> extrapolated(shot.step_energies.empty()
                                             ? shot.step_energies.end()
                                             : shot.step_energies.begin() + 1,
                                         shot.step_energies.end());
  JsonObject summary;
  summary.Add("path_energy", geodesic.path_energy)
      .Add("step_energies", geodesic.step_energies)
      .Add("extrapolated_step_energies", extrapolated)
      .Add("iterations", geodesic.iterations + shot_iterations)
      .Add("geodesic_iterations", geodesic.iterations)
      .Add("extrapolation_iterations", shot_iterations)
      .Add("initial_gradient_norm", geodesic.initial_gradient)
      .Add("final_gradient_norm", geodesic.final_gradient)
      .Add("relative_gradient_norm",
           RelativeGradientNorm(geodesic.final_gradient,
                                geodesic.initial_gradient))
      .Add("converged", geodesic.converged && shot_converged)
      .Add("geodesic_converged", geodesic.converged)
      .Add("extrapolation_converged", shot_converged)
      .Add("step_energy_ratio", geodesic.step_energy_ratio)
      .Add("uneven_steps", geodesic.uneven_steps)
      .Add("stages", stages)
      .Add("newton_steps", geodesic.newton.steps)
      .Add("factorizations", geodesic.newton.factorizations)
      .Add("cg_iterations", geodesic.newton.cg_iterations)
      .Add("seconds", seconds)
      .Add("frames", frames)
      .Add("geodesic_steps", FLAGS_steps)
      .Add("extrapolated_steps", FLAGS_extrapolate)
      .Add("vertices", finger.num_vertices())
      .Add("frames_dir", dir + "/frames")
      .Add("film_strip", dir + "/film_strip.png");
  if (!FLAGS_gltf.empty()) summary.Add("gltf", FLAGS_gltf);
  summary.Add("viewer", dir + "/viewer.html")
      .Add("material", workflows::MaterialChoiceJson(material, finger));
  return summary;
}

// The geodesic workflow's options of the demo: the procedural finger to
// the finger bent by 90 degrees about its base, --steps, the base held
// fixed, the material and solver flags; the other choices their defaults.
workflows::GeodesicOptions DemoGeodesicOptions(const Mesh& finger) {
  workflows::GeodesicOptions options;
  options.start = finger;
  options.topology = ValidateShell(finger, "procedural finger");
  options.end = BendAlongY(finger.positions, 4.0, 0.5 * std::acos(-1.0));
  options.steps = FLAGS_steps;
  options.fixed_vertices = FingerBaseVertices();
  options.material = MaterialChoiceFromFlags(finger);
  options.settings = SettingsFromFlags("demo geodesic");
  return options;
}

// Flags -> the geodesic workflow -> the extrapolation -> files and summary.
int RunDemo() {
  const std::string dir = FLAGS_output;
  RunPaths()
      .OutputDirectory("output", dir)
      .OutputGlb("gltf", FLAGS_gltf)
      .Check();
  const auto clock = std::chrono::steady_clock::now();
  const Mesh finger = MakeFinger();
  CheckDemoMemory(finger);
  const RenderOptions options = DemoFilmStripOptions();
  const workflows::GeodesicOptions geodesic_options =
      DemoGeodesicOptions(finger);
  const workflows::GeodesicResult result =
      workflows::RunGeodesic(geodesic_options);
  if (result.status.failed()) return FailedSolveExit("demo", result.status);

  const ShellSpace space(finger, geodesic_options.topology,
                         result.material.material);
  SolverSettings settings = geodesic_options.settings;
  ShellPath frames = result.path();
  const ShootResult shot = ExtrapolateDemoPath(
      space, geodesic_options.fixed_vertices, &settings, &frames);
  RunStatus status("demo");
  RecordWorkflow(result.status, result.warnings, "demo: the geodesic",
                 &status);
  CheckShoot(shot, &status);
  RunDirectory output(dir);
  WriteDemoFiles(&output, finger, frames, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock)
          .count();
  const JsonObject summary =
      DemoSummary(result.geodesic(), shot, static_cast<int>(frames.size()),
                  seconds, dir, result.material, finger);
  const std::string json = output.Commit(summary);
  std::cout << json << "\n";
  return status.Finish();
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "demo",
    "demo [--output demo-output] [--steps 8] [--extrapolate 4] "
    "[--gltf path.glb]: procedural "
    "finger -> bent finger geodesic, extrapolated, with a PNG film strip",
    shellspace::DemoFlags(), shellspace::RunDemo);
