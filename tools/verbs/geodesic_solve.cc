#include "tools/verbs/geodesic_solve.h"

#include <gflags/gflags.h>

#include <cstdio>
#include <string>
#include <vector>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/validation.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/path_summary.h"

namespace shellspace {

FlagSpec MultiresFlag() {
  return TextFlag(
             "multires",
             "auto|off|LEVELS: solve the geodesic on LEVELS decimated meshes "
             "first (each 1/4 of the vertices of the one above), prolongate, "
             "finish on the input mesh; auto: as many levels as keep the "
             "coarsest at >= " +
                 std::to_string(kAutoMinVertices) + " vertices")
      .Default(MultiresolutionWord(workflows::GeodesicOptions().multires));
}

FlagTable GeodesicEndsFlags(const std::string& start, const std::string& end) {
  return {TextFlag("start", start).Required(), TextFlag("end", end).Required()};
}

FlagSpec GeodesicStepsFlag(const std::string& what) {
  return IntegerFlag("steps", what + StepsBoundText(kGeodesicModel), 1,
                     kMaxSteps)
      .Default(FlagDefault(workflows::GeodesicOptions().steps));
}

FlagSpec LinearSolverFlag() {
  return TextFlag(
             "linear_solver",
             "auto|direct|block-jacobi: the linear solver of the Newton "
             "finish; direct: Cholesky of the whole space-time Hessian; "
             "block-jacobi: CG preconditioned by one-shape Cholesky factors "
             "(memory O(K x one shape)); auto: block-jacobi from " +
                 std::to_string(kBlockJacobiFromUnknowns) +
                 " unknowns ((K - 1) x free coordinates per shape)")
      .Default(PathLinearSolverWord(workflows::GeodesicOptions().linear_solver));
}

FlagSpec GeodesicLmFlag() {
  return TextFlag("lm",
                  "auto|ceres|engine: the solver of the LM stages; ceres: "
                  "Ceres' sparse LM (a Cholesky factorisation of the whole "
                  "space-time J^T J per iteration); engine: the same "
                  "Gauss-Newton model solved by --linear_solver (block-jacobi: "
                  "memory O(K x one shape)); auto: engine where the linear "
                  "solver is block-jacobi")
      .Default(GeodesicLmWord(workflows::GeodesicOptions().lm));
}

FlagSpec GeodesicInitFlag() {
  char ratio[16];
  std::snprintf(ratio, sizeof ratio, "%g", kDegenerateAreaRatio);
  return TextFlag("init",
                  "auto|linear|ltheta|rotations: the initial path; linear: "
                  "positions interpolated after removing the rigid motion "
                  "between the ends (none with --mask, or below " +
                      std::to_string(static_cast<int>(kRigidBlendMinDegrees)) +
                      " degree); ltheta: shells reconstructed from "
                      "interpolated edge lengths, areas and dihedral angles; "
                      "rotations: every triangle turned and stretched by the "
                      "interpolated polar factors of its deformation "
                      "gradient, the shell fitted to them; auto: linear "
                      "unless a triangle of it keeps less than " +
                      ratio +
                      " of its area or turns over, then rotations unless the "
                      "same holds of it, then ltheta")
      .Default(GeodesicInitName(workflows::GeodesicOptions().init));
}

RunPaths GeodesicInputPaths() {
  RunPaths paths;
  paths.InputFile("start", FLAGS_start)
      .InputFile("end", FLAGS_end)
      .InputFile("mask", FLAGS_mask);
  return paths;
}

workflows::GeodesicOptions GeodesicOptionsFromFlags(const std::string& verb) {
  const auto [start, end] = LoadShellPair(FLAGS_start, FLAGS_end);
  const int vertices = start.mesh.num_vertices();
  CheckMemory(GeodesicBytes(vertices, FLAGS_steps),
              "--steps " + std::to_string(FLAGS_steps) + " on " +
                  std::to_string(vertices) + " vertices",
              kGeodesicModel);
  workflows::GeodesicOptions options;
  options.start = start.mesh;
  options.topology = start.topology;
  options.end = end.positions;
  options.steps = FLAGS_steps;
  options.fixed_vertices = MaskFromFlags(vertices);
  options.material = MaterialChoiceFromFlags(start.mesh);
  options.multires = ParseMultiresolution(FLAGS_multires, "--multires");
  options.linear_solver =
      ParsePathLinearSolver(FLAGS_linear_solver, "--linear_solver");
  options.lm = ParseGeodesicLm(FLAGS_lm, "--lm");
  options.init = ParseGeodesicInit(FLAGS_init, "--init");
  options.settings = SettingsFromFlags(verb);
  // Legal, but a path may crush them: named once, before the solve.
  if (!FLAGS_quiet) {
    options.warn = [](const std::string& input, const std::string& text) {
      std::fprintf(stderr, "warning: %s: %s\n",
                   (input == "end" ? FLAGS_end : FLAGS_start).c_str(),
                   text.c_str());
    };
  }
  return options;
}

}  // namespace shellspace
