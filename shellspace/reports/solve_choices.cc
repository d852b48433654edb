#include "shellspace/reports/solve_choices.h"

#include <cstdlib>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/named_values.h"

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

namespace {

constexpr NamedValue<PathLinearSolver> kPathLinearSolverNames[] = {
    {PathLinearSolver::kAuto, "auto"}, {PathLinearSolver::kDirect, "direct"},
    {PathLinearSolver::kBlockJacobi, "block-jacobi"}};
constexpr NamedValue<GeodesicLm> kGeodesicLmNames[] = {
    {GeodesicLm::kAuto, "auto"}, {GeodesicLm::kCeres, "ceres"},
    {GeodesicLm::kEngine, "engine"}};

}  // namespace

PathLinearSolver ParsePathLinearSolver(const std::string& value,
                                       const std::string& name) {
  return ParseNamedValue(kPathLinearSolverNames, value, name);
}

GeodesicLm ParseGeodesicLm(const std::string& value, const std::string& name) {
  return ParseNamedValue(kGeodesicLmNames, value, name);
}

GeodesicInit ParseGeodesicInit(const std::string& value,
                               const std::string& name) {
  return ParseNamedValue(kGeodesicInitNames, value, name);
}

}  // namespace shellspace
