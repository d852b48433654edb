#include "shellspace/render/view.h"

#include <cmath>
#include <cstdlib>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/ascii_lowercase.h"

namespace shellspace {
namespace {

// Parses a whole string as a finite double; returns false otherwise.
bool ParseNumber(const std::string& text, double* value) {
  size_t begin = text.find_first_not_of(" \t");
  size_t end = text.find_last_not_of(" \t");
  if (begin == std::string::npos) return false;
  const std::string trimmed = text.substr(begin, end - begin + 1);
  char* stop = nullptr;
  *value = std::strtod(trimmed.c_str(), &stop);
  return stop == trimmed.c_str() + trimmed.size() && std::isfinite(*value);
}

}  // namespace

ViewAngles ParseView(const std::string& text) {
  const std::string name = AsciiLowercase(text);
  if (name == "front") return {0, 0};
  if (name == "back") return {180, 0};
  if (name == "side" || name == "right") return {90, 0};
  if (name == "left") return {-90, 0};
  if (name == "top") return {0, 90};
  if (name == "bottom") return {0, -90};
  if (name == "iso") {
    return {45, std::atan(1 / std::sqrt(2.0)) * 180 / M_PI};
  }
  const std::string expected =
      " (expected front, back, side, left, top, bottom, iso or "
      "AZIMUTH,ELEVATION in degrees)";
  const size_t comma = name.find(',');
  ViewAngles view;
  if (comma == std::string::npos ||
      !ParseNumber(name.substr(0, comma), &view.azimuth) ||
      !ParseNumber(name.substr(comma + 1), &view.elevation)) {
    throw InputError("bad view '" + text + "'" + expected);
  }
  if (view.elevation < -90 || view.elevation > 90) {
    throw InputError("bad view '" + text +
                     "': elevation must be in [-90, 90] degrees");
  }
  return view;
}

}  // namespace shellspace
