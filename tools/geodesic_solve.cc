#include "shellspace/tools/geodesic_solve.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/path_summary.h"

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
  MultiresolutionSettings settings;
  const std::string& value = FLAGS_multires;
  if (value == "off") {
    settings.levels = 0;
  } else if (value == "auto") {
    settings.levels = 0;
    settings.min_vertices = kAutoMinVertices;
    for (double n = 0.25 * num_vertices; n >= kAutoMinVertices; n *= 0.25) {
      ++settings.levels;
    }
  } else {
    char* end = nullptr;
    const long levels = std::strtol(value.c_str(), &end, 10);
    if (value.empty() || *end != '\0' || levels < 0 || levels > 8) {
      throw InputError("--multires must be auto, off or a number of levels "
                       "from 0 to 8, got '" + value + "'");
    }
    settings.levels = static_cast<int>(levels);
    settings.min_vertices = 20;
  }
  return settings;
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

PathLinearSolver LinearSolverFromFlags() {
  const std::string& value = FLAGS_linear_solver;
  if (value == "auto") return PathLinearSolver::kAuto;
  if (value == "direct") return PathLinearSolver::kDirect;
  if (value == "block-jacobi") return PathLinearSolver::kBlockJacobi;
  throw InputError("--linear_solver must be auto, direct or block-jacobi, "
                   "got '" + value + "'");
}

const char* LinearSolverName(PathLinearSolver solver) {
  switch (solver) {
    case PathLinearSolver::kAuto:
      return "auto";
    case PathLinearSolver::kDirect:
      return "direct";
    case PathLinearSolver::kBlockJacobi:
      return "block-jacobi";
  }
  return "auto";
}

MultiresolutionResult SolveGeodesicFromFlags(const ShellSpace& space,
                                             const GeodesicInput& input,
                                             const SolverSettings& settings) {
  GeodesicInput with_solver = input;
  with_solver.linear_solver = LinearSolverFromFlags();
  return SolveGeodesicMultiresolution(space, with_solver, settings,
                                      MultiresFromFlags(space.num_vertices));
}

std::string MultiresolutionJson(const MultiresolutionResult& result) {
  std::vector<std::string> levels;
  for (const MultiresolutionLevel& level : result.levels) {
    levels.push_back(JsonObject()
                         .Add("vertices", level.vertices)
                         .Add("faces", level.faces)
                         .Add("iterations", level.iterations)
                         .Add("path_energy", level.path_energy)
                         .Add("final_gradient_norm", level.final_gradient)
                         .Add("converged", level.converged)
                         .Add("seconds", level.seconds)
                         .str());
  }
  return JsonArray(levels);
}

}  // namespace shellspace
