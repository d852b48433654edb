// `shellspace shoot`, `log` and `transport`: the exponential map, the
// logarithm and parallel transport on the command line.
#include <gflags/gflags.h>

#include <chrono>
#include <iostream>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/shoot.h"
#include "shellspace/workflows/transport.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "tools/verbs/geodesic_solve.h"
#include "tools/verbs/path_summary.h"
#include "tools/run/run_paths.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb.h"

DEFINE_string(first, "", "shoot: the shell s_0");
DEFINE_string(second, "", "shoot: the shell s_1");
DEFINE_bool(backward, false, "shoot: extrapolate backward in time");
DEFINE_string(path, "", "transport: directory of the path's frames");
DEFINE_string(variation, "", "transport: shell s_0 + xi_0");

namespace shellspace {
namespace {

const char* const kPathModel = "64 MB + 200 B x #V x (K + 1)";

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since)
      .count();
}

FlagSpec MaskFlag() {
  return TextFlag("mask",
                  "vertex mask file (one 0-based index per line, '#' "
                  "comments): vertices held fixed");
}

FlagTable ShootFlags() {
  return Flags(
      {{
           TextFlag("first", "the shell s_0").Required(),
           TextFlag("second",
                    "the shell s_1 (s_1 - s_0 is the initial velocity / K)")
               .Required(),
           IntegerFlag("steps",
                       "number of time steps K (K + 1 shapes; K = 1: s_0, "
                       "s_1, nothing to solve)" +
                           StepsBoundText(kPathModel),
                       1, kMaxSteps)
               .Default(FlagDefault(workflows::ShootOptions().steps)),
           TextFlag("output", "directory of the frames shape_000.ply ...")
               .Required(),
           TextFlag("backward", "extrapolate backward in time, before s_0")
               .Default(BoolFlagDefault(workflows::ShootOptions().backward)),
           MaskFlag(),
           PngFlag(),
           AllowUnsolvedFlag(),
           GltfFlag(),
           HtmlFlag(),
       },
       MaterialFlags(),
       SolverFlags(),
       JsonFlag(),
       FilmStripFlags()});
}

FlagTable LogFlags() {
  return Flags(
      {GeodesicEndsFlags("the shell A at which LOG_K is taken", "the shell B"),
       {
           GeodesicStepsFlag("K of LOG_K (the geodesic's time steps; K = 1: "
                             "B - A, nothing to solve)"),
           TextFlag("output", "the shell A + LOG_K(A -> B): PLY, OBJ or OFF")
               .Required(),
           MaskFlag(),
           LinearSolverFlag(),
           GeodesicLmFlag(),
           GeodesicInitFlag(),
       },
       MaterialFlags(), SolverFlags(), JsonFlag()});
}

FlagTable TransportFlags() {
  return Flags(
      {{
           TextFlag("path", "directory of the path's frames shape_000.ply ...")
               .Required(),
           TextFlag("variation",
                    "shell s_0 + xi_0 (the variation xi_0 at the first frame)")
               .Required(),
           TextFlag("output",
                    "directory of the transported shapes s_k + eps xi_k")
               .Required(),
           RealFlag("epsilon",
                    "transport step epsilon: 1 transports a finite shape "
                    "difference, small values the tangent vector",
                    0, End::kOpen)
               .Default(FlagDefault(workflows::TransportOptions().epsilon)),
           MaskFlag(),
           PngFlag(),
           AllowUnsolvedFlag(),
           GltfFlag(),
           HtmlFlag(),
       },
       MaterialFlags(),
       SolverFlags(),
       JsonFlag(),
       FilmStripFlags()});
}

// Flags -> options -> the workflow -> frames and summary.
int RunShoot() {
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputFile("first", FLAGS_first)
      .InputFile("second", FLAGS_second)
      .InputFile("mask", FLAGS_mask)
      .OutputDirectory("output", FLAGS_output)
      .OutputPng("png", FLAGS_png)
      .OutputGlb("gltf", FLAGS_gltf)
      .OutputHtml("html", FLAGS_html)
      .Check();
  const auto [first, second] = LoadShellPair(FLAGS_first, FLAGS_second);
  CheckMemory(PathBytes(first.mesh.num_vertices(), FLAGS_steps + 1),
              "--steps " + std::to_string(FLAGS_steps) + " on " +
                  std::to_string(first.mesh.num_vertices()) + " vertices",
              kPathModel);
  CheckPngMemory(FLAGS_steps + 1);
  workflows::ShootOptions options;
  options.first = first.mesh;
  options.topology = first.topology;
  options.second = second.positions;
  options.steps = FLAGS_steps;
  options.backward = FLAGS_backward;
  options.material = MaterialChoiceFromFlags(first.mesh);
  options.fixed_vertices = MaskFromFlags(first.mesh.num_vertices());
  options.settings = SettingsFromFlags("shoot");
  const workflows::ShootResult result = workflows::RunShoot(options);
  RunStatus status("shoot");
  RecordWorkflow(result.status, {}, "shoot", &status);
  RunDirectory output(FLAGS_output);
  WritePathOutputs(&output, first.mesh.faces, result.path());
  CommitPathRun(&output,
                workflows::ToJson(result).Add(
                    "material", workflows::MaterialChoiceJson(options.material,
                                                              first.mesh)),
                Seconds(clock));
  return status.Finish();
}

// Flags -> options -> the workflow -> the file and summary.
int RunLog() {
  const auto clock = std::chrono::steady_clock::now();
  GeodesicInputPaths().OutputMesh("output", FLAGS_output).Check();
  const workflows::LogResult result =
      workflows::RunLog(GeodesicOptionsFromFlags("log"));
  const workflows::GeodesicResult& geodesic = result.geodesic;
  if (geodesic.status.failed()) return FailedSolveExit("log", geodesic.status);
  RunStatus status("log");
  RecordWorkflow(geodesic.status, geodesic.warnings, "log: the geodesic",
                 &status);
  WriteMesh(Mesh{geodesic.start.positions + result.log, geodesic.start.faces},
            FLAGS_output);
  if (FLAGS_json) {
    JsonObject json = workflows::ToJson(result);
    json.Add("material",
             workflows::MaterialChoiceJson(geodesic.material, geodesic.start))
        .Add("bending_model", FLAGS_bending)
        .Add("seconds", Seconds(clock))
        .Add("output", FLAGS_output);
    std::cout << AddRunFields(json).str() << "\n";
  }
  return status.Finish();
}

// Flags -> options -> the workflow -> frames and summary.
int RunTransport() {
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputFrames("path", FLAGS_path)
      .InputFile("variation", FLAGS_variation)
      .InputFile("mask", FLAGS_mask)
      .OutputDirectory("output", FLAGS_output)
      .OutputPng("png", FLAGS_png)
      .OutputGlb("gltf", FLAGS_gltf)
      .OutputHtml("html", FLAGS_html)
      .Check();
  const std::vector<std::string> files = ListFrameFiles(FLAGS_path);
  if (files.size() < 2) {
    throw InputError(FLAGS_path + ": need at least 2 frames");
  }
  CheckPngMemory(static_cast<int>(files.size()));
  const Shell first = LoadShell(files[0]);
  workflows::TransportOptions options;
  options.first = first.mesh;
  options.topology = first.topology;
  options.path = {first.mesh.positions};
  for (size_t k = 1; k < files.size(); ++k) {
    options.path.push_back(LoadCompatibleShell(files[k], first).positions);
  }
  options.variation = LoadCompatibleShell(FLAGS_variation, first).positions;
  options.epsilon = FLAGS_epsilon;
  options.material = MaterialChoiceFromFlags(first.mesh);
  options.fixed_vertices = MaskFromFlags(first.mesh.num_vertices());
  options.settings = SettingsFromFlags("transport");
  const workflows::TransportResult result = workflows::RunTransport(options);
  RunStatus status("transport");
  RecordWorkflow(result.status, {}, "transport", &status);
  for (const std::string& warning : result.warnings) status.Warn(warning);
  RunDirectory output(FLAGS_output);
  WritePathOutputs(&output, first.mesh.faces, result.shapes());
  CommitPathRun(&output,
                workflows::ToJson(result).Add(
                    "material", workflows::MaterialChoiceJson(options.material,
                                                              first.mesh)),
                Seconds(clock));
  return status.Finish();
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "shoot",
    "shoot --first S0.ply --second S1.ply --steps K --output DIR [--backward] "
    "[--mask M.txt] [--json] [--png strip.png] [--gltf path.glb] [--html path.html]",
    shellspace::ShootFlags(), shellspace::RunShoot);
SHELLSPACE_REGISTER_VERB(
    "log",
    "log --start A.ply --end B.ply --steps K --output V.ply "
    "[--linear_solver auto|direct|block-jacobi] (writes A + LOG_K)",
    shellspace::LogFlags(), shellspace::RunLog);
SHELLSPACE_REGISTER_VERB(
    "transport",
    "transport --path DIR --variation P0.ply --output DIR [--epsilon 1] "
    "[--json] [--png strip.png] [--gltf path.glb] [--html path.html]",
    shellspace::TransportFlags(), shellspace::RunTransport);
