#include "tools/verbs/geodesic_solve.h"

#include <cstdio>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/validation.h"
#include "tools/run/common_flags.h"
#include "tools/run/memory_limits.h"
#include "tools/verbs/path_summary.h"

namespace shellspace {

FlagSpec MultiresFlag() {
  return TextFlag(
      "multires",
      "auto|off|LEVELS: solve the geodesic on LEVELS decimated meshes first "
      "(each 1/4 of the vertices of the one above), prolongate, finish on the "
      "input mesh; auto: as many levels as keep the coarsest at >= " +
          std::to_string(kAutoMinVertices) + " vertices")
      .Default("auto");
}

MultiresolutionSettings MultiresFromFlags(int num_vertices) {
  return ParseMultiresolution(FLAGS_multires, num_vertices, "--multires");
}

FlagTable GeodesicEndsFlags(const std::string& start, const std::string& end) {
  return {TextFlag("start", start).Required(), TextFlag("end", end).Required()};
}

FlagSpec GeodesicStepsFlag(const std::string& what) {
  return IntegerFlag("steps", what + StepsBoundText(kGeodesicModel), 1,
                     kMaxSteps);
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
      .Default("auto");
}

FlagSpec GeodesicLmFlag() {
  return TextFlag("lm",
                  "auto|ceres|engine: the solver of the LM stages; ceres: "
                  "Ceres' sparse LM (a Cholesky factorisation of the whole "
                  "space-time J^T J per iteration); engine: the same "
                  "Gauss-Newton model solved by --linear_solver (block-jacobi: "
                  "memory O(K x one shape)); auto: engine where the linear "
                  "solver is block-jacobi")
      .Default("auto");
}

FlagSpec GeodesicInitFlag() {
  char ratio[16];
  std::snprintf(ratio, sizeof ratio, "%g", kDegenerateAreaRatio);
  return TextFlag("init",
                  "auto|linear|ltheta: the initial path; linear: positions "
                  "interpolated after removing the rigid motion between the "
                  "ends (none with --mask, or below " +
                      std::to_string(static_cast<int>(kRigidBlendMinDegrees)) +
                      " degree); ltheta: shells reconstructed from "
                      "interpolated edge lengths, areas and dihedral angles; "
                      "auto: linear unless a triangle of it keeps less than " +
                      ratio +
                      " of its area or turns over, then ltheta")
      .Default("auto");
}

GeodesicInit GeodesicInitFromFlags() {
  return ParseGeodesicInit(FLAGS_init, "--init");
}

PathLinearSolver LinearSolverFromFlags() {
  return ParsePathLinearSolver(FLAGS_linear_solver, "--linear_solver");
}

MultiresolutionResult SolveGeodesicFromFlags(const ShellSpace& space,
                                             const GeodesicInput& input,
                                             const SolverSettings& settings) {
  GeodesicInput with_solver = input;
  with_solver.linear_solver = LinearSolverFromFlags();
  with_solver.lm = ParseGeodesicLm(FLAGS_lm, "--lm");
  with_solver.init = GeodesicInitFromFlags();
  return SolveGeodesicMultiresolution(space, with_solver, settings,
                                      MultiresFromFlags(space.num_vertices));
}

RunPaths GeodesicInputPaths() {
  RunPaths paths;
  paths.InputFile("start", FLAGS_start)
      .InputFile("end", FLAGS_end)
      .InputFile("mask", FLAGS_mask);
  return paths;
}

GeodesicOfFlags SolveGeodesicOfFlags(const std::string& verb) {
  const auto [start, end] = LoadShellPair(FLAGS_start, FLAGS_end);
  CheckMemory(GeodesicBytes(start.mesh.num_vertices(), FLAGS_steps),
              "--steps " + std::to_string(FLAGS_steps) + " on " +
                  std::to_string(start.mesh.num_vertices()) + " vertices",
              kGeodesicModel);
  // Legal, but a path may crush them: named once, before the solve.
  const SliverFaces slivers = FindSliverFaces(start.mesh);
  if (!slivers.empty() && !FLAGS_quiet) {
    std::fprintf(stderr, "warning: %s: %s\n", FLAGS_start.c_str(),
                 slivers.Describe().c_str());
  }
  ShellSpace space = SpaceFromFlags(start);
  GeodesicInput input;
  input.start = start.mesh.positions;
  input.end = end.positions;
  input.steps = FLAGS_steps;
  input.fixed_vertices = MaskFromFlags(start.mesh.num_vertices());
  MultiresolutionResult multires =
      SolveGeodesicFromFlags(space, input, SettingsFromFlags(verb));
  return {start, std::move(space), std::move(multires)};
}

}  // namespace shellspace
