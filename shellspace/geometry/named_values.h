// The names of an enumeration's values, spelled once: a fixed table that both
// the parser of a user's text and the printer of a report read, so the two
// cannot drift apart and an error message lists exactly what is accepted.
//
//   constexpr NamedValue<Shading> kShadingNames[] = {
//       {Shading::kFlat, "flat"}, {Shading::kGouraud, "gouraud"}};
//   NameOf(kShadingNames, Shading::kGouraud)   // "gouraud"
//   ValueNamed(kShadingNames, "flat")          // Shading::kFlat
//   NameChoices(kShadingNames)                 // "flat or gouraud"
//   ParseNamedValue(kShadingNames, "phong", "--shading")
//       // InputError "--shading must be flat or gouraud, got 'phong'"
//
// A value may stand in several entries (aliases such as "+x" for "x"); its
// first entry is its canonical name, the one NameOf prints and NameChoices
// lists. Lookups are linear: the tables have a handful of entries.
#ifndef SHELLSPACE_GEOMETRY_NAMED_VALUES_H_
#define SHELLSPACE_GEOMETRY_NAMED_VALUES_H_

#include <cstddef>
#include <optional>
#include <string>

#include "shellspace/geometry/mesh.h"  // InputError

namespace shellspace {

template <class Enum>
struct NamedValue {
  Enum value;
  const char* name;
};

// The canonical name of `value`, or `otherwise` when the table lacks it.
template <class Enum, std::size_t N>
const char* NameOf(const NamedValue<Enum> (&table)[N], Enum value,
                   const char* otherwise = "unknown") {
  for (const NamedValue<Enum>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return otherwise;
}

// The value whose entry spells `name` exactly (callers fold case first where
// they accept any case), or nullopt.
template <class Enum, std::size_t N>
std::optional<Enum> ValueNamed(const NamedValue<Enum> (&table)[N],
                               const std::string& name) {
  for (const NamedValue<Enum>& entry : table) {
    if (name == entry.name) return entry.value;
  }
  return std::nullopt;
}

// The canonical names in table order, as a sentence's list: "a", "a or b",
// "a, b or c". Aliases are not listed.
template <class Enum, std::size_t N>
std::string NameChoices(const NamedValue<Enum> (&table)[N]) {
  std::string canonical[N];
  std::size_t count = 0;
  for (const NamedValue<Enum>& entry : table) {
    if (NameOf(table, entry.value) == entry.name) {
      canonical[count++] = entry.name;
    }
  }
  std::string list;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) list += i + 1 == count ? " or " : ", ";
    list += canonical[i];
  }
  return list;
}

// The value `text` names, or an InputError in one line that names what was
// being read (`what`: a flag, a keyword) and the choices:
// "--lm must be auto, ceres or engine, got 'newton'".
template <class Enum, std::size_t N>
Enum ParseNamedValue(const NamedValue<Enum> (&table)[N],
                     const std::string& text, const std::string& what) {
  if (const std::optional<Enum> named = ValueNamed(table, text)) return *named;
  throw InputError(what + " must be " + NameChoices(table) + ", got '" + text +
                   "'");
}

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_NAMED_VALUES_H_
