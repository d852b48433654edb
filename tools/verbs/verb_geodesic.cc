// `shellspace geodesic`: discrete geodesic interpolation between two shells.
#include <gflags/gflags.h>

#include <chrono>
#include <iostream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/workflows/geodesic.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "tools/verbs/geodesic_solve.h"
#include "tools/verbs/path_summary.h"
#include "tools/run/run_paths.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb.h"

namespace shellspace {
namespace {

FlagTable GeodesicFlags() {
  return Flags(
      {GeodesicEndsFlags("first shell s_0 of the path",
                         "last shell s_K of the path"),
       {
           GeodesicStepsFlag("number of time steps K (K + 1 shapes; K = 1: "
                             "the two ends, nothing to solve)"),
           TextFlag("output", "directory of the frames shape_000.ply ...")
               .Required(),
           TextFlag("mask",
                    "vertex mask file (one 0-based index per line, '#' "
                    "comments): vertices held at their linearly "
                    "interpolated positions"),
           PngFlag(),
           GltfFlag(),
           HtmlFlag(),
           TextFlag("report", "print Ceres' full report on stderr"),
           MultiresFlag(),
           LinearSolverFlag(),
           GeodesicLmFlag(),
           GeodesicInitFlag(),
       },
       MaterialFlags(), SolverFlags(), JsonFlag(), FilmStripFlags()});
}

// Flags -> options -> the workflow -> files and summary.
int RunGeodesic() {
  const auto clock = std::chrono::steady_clock::now();
  GeodesicInputPaths()
      .OutputDirectory("output", FLAGS_output)
      .OutputPng("png", FLAGS_png)
      .OutputGlb("gltf", FLAGS_gltf)
      .OutputHtml("html", FLAGS_html)
      .Check();
  const workflows::GeodesicOptions options =
      GeodesicOptionsFromFlags("geodesic");
  CheckPngMemory(FLAGS_steps + 1);
  const workflows::GeodesicResult result = workflows::RunGeodesic(options);
  if (result.status.failed()) return FailedSolveExit("geodesic", result.status);
  const ceres::Solver::Summary& ceres = result.geodesic().summary;
  const bool ceres_ran = !ceres.iterations.empty();
  if (FLAGS_report && ceres_ran) std::cerr << ceres.FullReport() << "\n";
  RunStatus status("geodesic");
  RecordWorkflow(result.status, result.warnings, "geodesic", &status);
  RunDirectory output(FLAGS_output);
  WritePathOutputs(&output, result.start.faces, result.path());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock)
          .count();
  CommitPathRun(&output,
                workflows::ToJson(result).Add(
                    "material", workflows::MaterialChoiceJson(result.material,
                                                              result.start)),
                seconds);
  if (!FLAGS_json && !FLAGS_quiet) {
    if (ceres_ran) std::cerr << ceres.BriefReport() << "\n";
    std::cout << "E_K = " << result.path_energy() << " over " << FLAGS_steps
              << " steps (" << result.geodesic().iterations
              << " iterations, |grad| " << result.geodesic().final_gradient
              << "); wrote " << FLAGS_output << "/shape_*.ply\n";
  }
  return status.Finish();
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "geodesic",
    "geodesic --start A.ply --end B.ply --steps K --output DIR [--mask M.txt] "
    "[--eta E] [--multires auto|off|LEVELS] "
    "[--linear_solver auto|direct|block-jacobi] [--json] [--png strip.png] "
    "[--gltf path.glb] [--html path.html]",
    shellspace::GeodesicFlags(), shellspace::RunGeodesic);
