#include "shellspace/render/shading.h"

#include <cctype>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

Shading ParseShading(const std::string& text) {
  std::string name = text;
  for (char& c : name) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (name == "flat") return Shading::kFlat;
  if (name == "gouraud") return Shading::kGouraud;
  throw InputError("bad shading '" + text + "' (expected flat or gouraud)");
}

std::string ShadingName(Shading shading) {
  return shading == Shading::kFlat ? "flat" : "gouraud";
}

}  // namespace shellspace
