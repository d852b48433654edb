#include "shellspace/reports/solve_choices.h"

#include <cstdlib>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

MultiresolutionSettings ParseMultiresolution(const std::string& value,
                                             int num_vertices,
                                             const std::string& name) {
  MultiresolutionSettings settings;
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
      throw InputError(name + " must be auto, off or a number of levels "
                       "from 0 to 8, got '" + value + "'");
    }
    settings.levels = static_cast<int>(levels);
    settings.min_vertices = 20;
  }
  return settings;
}

PathLinearSolver ParsePathLinearSolver(const std::string& value,
                                       const std::string& name) {
  if (value == "auto") return PathLinearSolver::kAuto;
  if (value == "direct") return PathLinearSolver::kDirect;
  if (value == "block-jacobi") return PathLinearSolver::kBlockJacobi;
  throw InputError(name + " must be auto, direct or block-jacobi, got '" +
                   value + "'");
}

const char* PathLinearSolverName(PathLinearSolver solver) {
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

GeodesicLm ParseGeodesicLm(const std::string& value, const std::string& name) {
  if (value == "auto") return GeodesicLm::kAuto;
  if (value == "ceres") return GeodesicLm::kCeres;
  if (value == "engine") return GeodesicLm::kEngine;
  throw InputError(name + " must be auto, ceres or engine, got '" + value +
                   "'");
}

}  // namespace shellspace
