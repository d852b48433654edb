// `shellspace shoot`, `log` and `transport`: the exponential map, the
// logarithm and parallel transport on the command line.
#include <gflags/gflags.h>

#include <chrono>
#include <iostream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/path_summary.h"
#include "shellspace/tools/shell_inputs.h"
#include "shellspace/tools/verb.h"

DEFINE_string(first, "", "shoot: the shell s_0");
DEFINE_string(second, "",
              "shoot: the shell s_1 (s_1 - s_0 is the initial velocity / K)");
DEFINE_bool(backward, false, "shoot: extrapolate backward in time, before s_0");
DEFINE_string(path, "",
              "transport: directory of the path's frames shape_000.ply ...");
DEFINE_string(
    variation, "",
    "transport: shell s_0 + xi_0 (the variation xi_0 at the first frame)");

namespace shellspace {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since)
      .count();
}

std::vector<int> MaskOrEmpty(int num_vertices) {
  return FLAGS_mask.empty() ? std::vector<int>{}
                            : ReadMask(FLAGS_mask, num_vertices);
}

int RunShoot() {
  RequireFlag("first", FLAGS_first);
  RequireFlag("second", FLAGS_second);
  RequireFlag("output", FLAGS_output);
  if (FLAGS_steps < 1) throw InputError("--steps must be at least 1");
  const auto clock = std::chrono::steady_clock::now();
  const Mesh first = LoadShell(FLAGS_first);
  const Mesh second = LoadCompatibleShell(FLAGS_second, first, FLAGS_first);
  const ShellSpace space = SpaceFromFlags(first);
  std::vector<ceres::Solver::Summary> summaries;
  const ShellPath path =
      Shoot(space, first.positions, second.positions, FLAGS_steps,
            FLAGS_backward ? StepDirection::kBackward : StepDirection::kForward,
            MaskOrEmpty(first.num_vertices()), SettingsFromFlags("shoot"),
            &summaries);
  for (const auto& s : summaries) {
    if (s.termination_type == ceres::FAILURE) {
      throw InputError("EXP step failed: " + s.message);
    }
  }
  WritePathOutputs(FLAGS_output, first.faces, path);
  if (FLAGS_json) {
    std::cout << PathSummary(space, path, summaries, Seconds(clock))
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  }
  return 0;
}

int RunLog() {
  const auto clock = std::chrono::steady_clock::now();
  const auto [start, end] = LoadStartEndFromFlags();
  const ShellSpace space = SpaceFromFlags(start);
  GeodesicResult geodesic;
  const Positions log = LogK(space, start.positions, end.positions, FLAGS_steps,
                             MaskOrEmpty(start.num_vertices()),
                             SettingsFromFlags("log"), &geodesic);
  WriteMesh(Mesh{start.positions + log, start.faces}, FLAGS_output);
  if (FLAGS_json) {
    std::cout << PathSummary(space, geodesic.path, {geodesic.summary},
                             Seconds(clock))
                     .Add("log_max_norm", log.cwiseAbs().maxCoeff())
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  }
  return 0;
}

int RunTransport() {
  RequireFlag("path", FLAGS_path);
  RequireFlag("variation", FLAGS_variation);
  RequireFlag("output", FLAGS_output);
  if (!(FLAGS_epsilon > 0)) throw InputError("--epsilon must be positive");
  const auto clock = std::chrono::steady_clock::now();
  const std::vector<std::string> files = ListFrameFiles(FLAGS_path);
  if (files.size() < 2)
    throw InputError(FLAGS_path + ": need at least 2 frames");
  const Mesh first = LoadShell(files[0]);
  ShellPath path = {first.positions};
  for (size_t k = 1; k < files.size(); ++k) {
    path.push_back(LoadCompatibleShell(files[k], first, files[0]).positions);
  }
  const Mesh varied = LoadCompatibleShell(FLAGS_variation, first, files[0]);
  const ShellSpace space = SpaceFromFlags(first);
  const TransportResult result = ParallelTransport(
      space, path, varied.positions - first.positions, FLAGS_epsilon,
      MaskOrEmpty(first.num_vertices()), SettingsFromFlags("transport"));
  WritePathOutputs(FLAGS_output, first.faces, result.shapes);
  if (FLAGS_json) {
    std::vector<double> norms;
    for (const Positions& xi : result.variations) {
      norms.push_back(xi.cwiseAbs().maxCoeff());
    }
    std::cout << JsonObject()
                     .Add("variation_max_norms", norms)
                     .Add("exp_residuals", result.exp_residuals)
                     .Add("epsilon", FLAGS_epsilon)
                     .Add("frames", static_cast<int>(result.shapes.size()))
                     .Add("seconds", Seconds(clock))
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "shoot",
    "shoot --first S0.ply --second S1.ply --steps K --output DIR [--backward] "
    "[--mask M.txt] [--json] [--png strip.png]",
    shellspace::RunShoot);
SHELLSPACE_REGISTER_VERB(
    "log",
    "log --start A.ply --end B.ply --steps K --output V.ply (writes A + LOG_K)",
    shellspace::RunLog);
SHELLSPACE_REGISTER_VERB(
    "transport",
    "transport --path DIR --variation P0.ply --output DIR [--epsilon 1] "
    "[--json] [--png strip.png]",
    shellspace::RunTransport);
