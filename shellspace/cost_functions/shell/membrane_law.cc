#include "shellspace/cost_functions/shell/membrane_law.h"

#include <optional>

#include "shellspace/geometry/named_values.h"

namespace shellspace {
namespace {

#define SHELLSPACE_MEMBRANE_LAW_NAME(type, value, name) \
  {MembraneLaw::value, name},
constexpr NamedValue<MembraneLaw> kMembraneLawNames[] = {
    SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_LAW_NAME)};
#undef SHELLSPACE_MEMBRANE_LAW_NAME

}  // namespace

const char* MembraneLawName(MembraneLaw law) {
  return NameOf(kMembraneLawNames, law);
}

bool ParseMembraneLaw(const std::string& name, MembraneLaw* law) {
  const std::optional<MembraneLaw> named = ValueNamed(kMembraneLawNames, name);
  if (named) *law = *named;
  return named.has_value();
}

std::string MembraneLawNames() { return NameChoices(kMembraneLawNames); }

}  // namespace shellspace
