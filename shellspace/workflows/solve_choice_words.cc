#include "shellspace/workflows/solve_choice_words.h"

#include <cstdlib>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/named_values.h"

namespace shellspace {
namespace {

constexpr NamedValue<PathLinearSolver> kPathLinearSolverNames[] = {
    {PathLinearSolver::kAuto, "auto"}, {PathLinearSolver::kDirect, "direct"},
    {PathLinearSolver::kBlockJacobi, "block-jacobi"}};
constexpr NamedValue<GeodesicLm> kGeodesicLmNames[] = {
    {GeodesicLm::kAuto, "auto"}, {GeodesicLm::kCeres, "ceres"},
    {GeodesicLm::kEngine, "engine"}};

}  // namespace

MultiresolutionChoice ParseMultiresolution(const std::string& value,
                                           const std::string& name) {
  if (value == "auto") return MultiresolutionChoice::Automatic();
  if (value == "off") return MultiresolutionChoice::Levels(0);
  char* end = nullptr;
  const long levels = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || levels < 0 || levels > 8) {
    throw InputError(name + " must be auto, off or a number of levels "
                     "from 0 to 8, got '" + value + "'");
  }
  return MultiresolutionChoice::Levels(static_cast<int>(levels));
}

std::string MultiresolutionWord(const MultiresolutionChoice& choice) {
  if (choice.automatic) return "auto";
  return choice.levels == 0 ? "off" : std::to_string(choice.levels);
}

PathLinearSolver ParsePathLinearSolver(const std::string& value,
                                       const std::string& name) {
  return ParseNamedValue(kPathLinearSolverNames, value, name);
}

std::string PathLinearSolverWord(PathLinearSolver solver) {
  return NameOf(kPathLinearSolverNames, solver);
}

GeodesicLm ParseGeodesicLm(const std::string& value, const std::string& name) {
  return ParseNamedValue(kGeodesicLmNames, value, name);
}

std::string GeodesicLmWord(GeodesicLm lm) {
  return NameOf(kGeodesicLmNames, lm);
}

GeodesicInit ParseGeodesicInit(const std::string& value,
                               const std::string& name) {
  return ParseNamedValue(kGeodesicInitNames, value, name);
}

}  // namespace shellspace
