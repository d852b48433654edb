#include "tools/run/flag_repeats.h"

#include <gflags/gflags.h>

#include <map>

namespace shellspace {
namespace {

bool Known(const std::string& name, bool* is_bool) {
  gflags::CommandLineFlagInfo info;
  if (!gflags::GetCommandLineFlagInfo(name.c_str(), &info)) return false;
  *is_bool = info.type == "bool";
  return true;
}

std::string Shown(const std::string& value) {
  return value.empty() ? "set" : value;
}

}  // namespace

std::string RepeatedFlagProblem(const std::vector<std::string>& args) {
  std::map<std::string, std::string> seen;  // flag name -> its value
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") break;  // the rest are not flags
    if (arg.size() < 2 || arg[0] != '-') continue;
    std::string name = arg.substr(arg[1] == '-' ? 2 : 1);
    std::string value;
    bool has_value = false, is_bool = false;
    const size_t equals = name.find('=');
    if (equals != std::string::npos) {
      value = name.substr(equals + 1);
      name = name.substr(0, equals);
      has_value = true;
    }
    if (!Known(name, &is_bool)) {
      // --noquiet: the boolean --quiet set to false.
      if (name.rfind("no", 0) != 0 || !Known(name.substr(2), &is_bool) ||
          !is_bool) {
        continue;  // not a flag (gflags has refused it already)
      }
      name = name.substr(2);
      value = "false";
      has_value = true;
    }
    if (!has_value && !is_bool && i + 1 < args.size()) {
      value = args[++i];  // "--steps 4"
    }
    const auto [it, added] = seen.emplace(name, value);
    if (!added) {
      return "--" + name + " is given twice (" + Shown(it->second) +
             ", then " + Shown(value) + "): give each flag once";
    }
  }
  return "";
}

}  // namespace shellspace
