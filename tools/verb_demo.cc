// `shellspace demo`: the built-in example. A procedural finger and the same
// finger bent by 90 degrees; the discrete geodesic between them (K = 8, base
// held fixed), extrapolated 4 more steps by the exponential map; PLY frames,
// a JSON summary and a PNG film strip in --output (default ./demo-output).
#include <gflags/gflags.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/path_summary.h"
#include "shellspace/tools/shell_inputs.h"
#include "shellspace/tools/verb.h"

DEFINE_int32(extrapolate, 4, "demo: EXP steps beyond the end shape");

namespace shellspace {
namespace {

int RunDemo() {
  const std::string dir = FLAGS_output.empty() ? "demo-output" : FLAGS_output;
  if (FLAGS_steps < 2) throw InputError("--steps must be at least 2");
  if (FLAGS_extrapolate < 0) throw InputError("--extrapolate must be >= 0");
  const auto clock = std::chrono::steady_clock::now();
  const Mesh finger = MakeFinger();
  const double pi = std::acos(-1.0);
  const Positions bent = BendAlongY(finger.positions, 4.0, 0.5 * pi);
  const ShellSpace space(finger, Topology::Build(finger), MaterialFromFlags());
  const std::vector<int> base = FingerBaseVertices();
  SolverSettings settings = SettingsFromFlags("demo geodesic");

  GeodesicInput input;
  input.start = finger.positions;
  input.end = bent;
  input.steps = FLAGS_steps;
  input.fixed_vertices = base;
  const GeodesicResult geodesic = SolveGeodesic(space, input, settings);
  std::vector<ceres::Solver::Summary> summaries = {geodesic.summary};

  ShellPath frames = geodesic.path;
  if (FLAGS_extrapolate > 0) {
    settings.progress_label = "demo exp";
    const int K = FLAGS_steps;
    const ShellPath shot =
        Shoot(space, frames[K - 1], frames[K], FLAGS_extrapolate + 1,
              StepDirection::kForward, base, settings, &summaries);
    frames.insert(frames.end(), shot.begin() + 2, shot.end());
  }
  MakeDirectory(dir);
  WriteFrames(dir + "/frames", finger.faces, frames);
  RenderOptions options;
  options.view = ParseView("front");  // the bend lies in the x-y plane
  options.max_per_row = 7;
  WriteFilmStrip(frames, finger.faces, options, dir + "/film_strip.png");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock)
          .count();
  const std::string json =
      PathSummary(space, frames, summaries, seconds)
          .Add("geodesic_path_energy", geodesic.path_energy)
          .Add("geodesic_steps", FLAGS_steps)
          .Add("extrapolated_steps", FLAGS_extrapolate)
          .Add("vertices", finger.num_vertices())
          .Add("frames_dir", dir + "/frames")
          .Add("film_strip", dir + "/film_strip.png")
          .str();
  {
    std::ofstream out(dir + "/summary.json");
    out << json << "\n";
  }
  std::cout << json << "\n";
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "demo",
    "demo [--output demo-output] [--steps 8] [--extrapolate 4]: procedural "
    "finger -> bent finger geodesic, extrapolated, with a PNG film strip",
    shellspace::RunDemo);
