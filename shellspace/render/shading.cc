#include "shellspace/render/shading.h"

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/named_values.h"
#include "shellspace/io/ascii_lowercase.h"

namespace shellspace {

namespace {

constexpr NamedValue<Shading> kShadingNames[] = {
    {Shading::kFlat, "flat"}, {Shading::kGouraud, "gouraud"}};

}  // namespace

Shading ParseShading(const std::string& text) {
  return ParseNamedValue(kShadingNames, AsciiLowercase(text), "the shading");
}

std::string ShadingName(Shading shading) {
  return NameOf(kShadingNames, shading);
}

}  // namespace shellspace
