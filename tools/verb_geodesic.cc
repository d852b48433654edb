// `shellspace geodesic`: discrete geodesic interpolation between two shells.
#include <gflags/gflags.h>

#include <chrono>
#include <iostream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/geodesic_solve.h"
#include "shellspace/tools/path_summary.h"
#include "shellspace/tools/shell_inputs.h"
#include "shellspace/tools/verb.h"

namespace shellspace {
namespace {

FlagTable GeodesicFlags() {
  return Flags(
      {{
           TextFlag("start", "first shell s_0 of the path").Required(),
           TextFlag("end", "last shell s_K of the path").Required(),
           IntegerFlag("steps", "number of time steps K (K + 1 shapes)", 1),
           TextFlag("output", "directory of the frames shape_000.ply ...")
               .Required(),
           TextFlag("mask",
                    "vertex mask file (one 0-based index per line, '#' "
                    "comments): vertices held at their linearly "
                    "interpolated positions"),
           TextFlag("png", "also write a PNG film strip of the frames here"),
           GltfFlag(),
           TextFlag("report", "print Ceres' full report on stderr"),
           MultiresFlag(),
           LinearSolverFlag(),
       },
       MaterialFlags(), SolverFlags(), JsonFlag()});
}

int RunGeodesic() {
  const auto clock = std::chrono::steady_clock::now();
  const auto [start, end] = LoadStartEndFromFlags();
  const ShellSpace space = SpaceFromFlags(start);
  GeodesicInput input;
  input.start = start.mesh.positions;
  input.end = end.positions;
  input.steps = FLAGS_steps;
  input.fixed_vertices = MaskFromFlags(start.mesh.num_vertices());
  const MultiresolutionResult multires =
      SolveGeodesicFromFlags(space, input, SettingsFromFlags("geodesic"));
  const GeodesicResult& result = multires.geodesic;
  if (result.summary.termination_type == ceres::FAILURE) {
    throw InputError("solver failed: " + result.summary.message);
  }
  if (FLAGS_report) std::cerr << result.summary.FullReport() << "\n";
  WritePathOutputs(FLAGS_output, start.mesh.faces, result.path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock)
          .count();
  if (FLAGS_json) {
    std::cout << GeodesicJson(result)
                     .Raw("multires_levels", MultiresolutionJson(multires))
                     .Add("seconds", seconds)
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  } else if (!FLAGS_quiet) {
    std::cerr << result.summary.BriefReport() << "\n";
    std::cout << "E_K = " << result.path_energy << " over " << FLAGS_steps
              << " steps (" << result.iterations << " iterations, |grad| "
              << result.final_gradient << "); wrote " << FLAGS_output
              << "/shape_*.ply\n";
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "geodesic",
    "geodesic --start A.ply --end B.ply --steps K --output DIR [--mask M.txt] "
    "[--eta E] [--multires auto|off|LEVELS] "
    "[--linear_solver auto|direct|block-jacobi] [--json] [--png strip.png] "
    "[--gltf path.glb]",
    shellspace::GeodesicFlags(), shellspace::RunGeodesic);
