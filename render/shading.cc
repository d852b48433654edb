#include "shellspace/render/shading.h"

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/ascii_lowercase.h"

namespace shellspace {

Shading ParseShading(const std::string& text) {
  const std::string name = AsciiLowercase(text);
  if (name == "flat") return Shading::kFlat;
  if (name == "gouraud") return Shading::kGouraud;
  throw InputError("bad shading '" + text + "' (expected flat or gouraud)");
}

std::string ShadingName(Shading shading) {
  return shading == Shading::kFlat ? "flat" : "gouraud";
}

}  // namespace shellspace
