#include "tools/verbs/verb_flags.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/solvers/solver_settings.h"
#include "tools/run/run_status.h"

namespace shellspace {
namespace {

std::string Number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

std::string FlagDefault(int value) { return std::to_string(value); }

std::string FlagDefault(double value) {
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

std::string FlagDefault(const std::string& value) { return value; }

std::string BoolFlagDefault(bool value) { return value ? "true" : "false"; }

FlagSpec TextFlag(const std::string& name, const std::string& meaning) {
  FlagSpec spec;
  spec.name = name;
  spec.meaning = meaning;
  return spec;
}

FlagSpec IntegerFlag(const std::string& name, const std::string& meaning,
                     long min, long max) {
  std::string range = max == std::numeric_limits<int>::max()
                          ? "an integer >= " + std::to_string(min)
                          : "an integer in [" + std::to_string(min) + ", " +
                                std::to_string(max) + "]";
  return CheckedFlag(name, meaning, range, [min, max](double value) {
    return value == std::floor(value) && value >= min && value <= max;
  });
}

FlagSpec RealFlag(const std::string& name, const std::string& meaning,
                  double min, End min_end, double max, End max_end) {
  const bool lower_open = min_end == End::kOpen || std::isinf(min);
  const bool upper_open = max_end == End::kOpen || std::isinf(max);
  std::string range;
  if (std::isinf(max)) {
    range = std::string(lower_open ? "> " : ">= ") + Number(min);
  } else {
    range = std::string(lower_open ? "(" : "[") + Number(min) + ", " +
            Number(max) + (upper_open ? ")" : "]");
  }
  return CheckedFlag(name, meaning, "a number " + range,
                     [=](double value) {
                       const bool above = lower_open ? value > min : value >= min;
                       const bool below = upper_open ? value < max : value <= max;
                       return above && below;
                     });
}

FlagSpec CheckedFlag(const std::string& name, const std::string& meaning,
                     const std::string& range,
                     std::function<bool(double)> valid) {
  FlagSpec spec = TextFlag(name, meaning);
  spec.range = range;
  spec.valid = std::move(valid);
  return spec;
}

FlagTable Flags(std::initializer_list<FlagTable> parts) {
  FlagTable table;
  for (const FlagTable& part : parts) {
    table.insert(table.end(), part.begin(), part.end());
  }
  return table;
}

FlagTable MaterialFlags() {
  const ShellMaterial material;
  return {
      TextFlag("membrane",
               "membrane law: " + MembraneLawNames() + " (see docs/math.md)")
          .Default(MembraneLawName(material.membrane_law)),
      RealFlag("mu", "membrane Lame weight mu", 0, End::kOpen)
          .Default(FlagDefault(material.mu)),
      RealFlag("lambda", "membrane Lame weight lambda", 0, End::kOpen)
          .Default(FlagDefault(material.lambda)),
      RealFlag("eta",
               "absolute bending weight eta of W = W_mem + eta W_bend; "
               "replaces relative_eta x area (not both)",
               0, End::kClosed)
          .ShownDefault("relative_eta x area of the reference shell"),
      RealFlag("relative_eta",
               "bending weight relative to the size: eta = relative_eta x "
               "the surface area of the reference shell (the first input), "
               "the same material at any scale (W_mem scales like area, "
               "W_bend not at all)",
               0, End::kClosed)
          .Default(FlagDefault(kDefaultRelativeEta)),
      TextFlag("bending",
               "bending model: discrete-shells (default) or shape-operator")
          .Default(BendingModelName(material.bending_model)),
  };
}

FlagTable SolverFlags() {
  const SolverSettings settings;
  return {
      RealFlag("tolerance",
               "stop when the gradient max-norm falls below this times "
               "max(1, its initial value)",
               0, End::kOpen, 1, End::kOpen)
          .Default(FlagDefault(settings.gradient_tolerance)),
      IntegerFlag("max_iterations",
                  "maximum iterations of the verb's outer solver (LM "
                  "iterations summed over its stages; spline: L-BFGS); inner "
                  "solves keep their own limits",
                  1)
          .Default(FlagDefault(settings.max_iterations)),
      IntegerFlag("threads", "threads of the solves", 1, kMaxSolverThreads)
          .Default(FlagDefault(settings.num_threads)),
      TextFlag("quiet", "suppress progress output"),
      AllowUnconvergedFlag(),
      TimeLimitFlag(),
  };
}

FlagSpec TimeLimitFlag() {
  return RealFlag("time_limit",
                  "stop the solves after this many seconds of wall clock (or "
                  "at SIGINT/SIGTERM/SIGHUP), write the best state so far "
                  "marked \"partial\": true, exit 124 (130 SIGINT, 143 "
                  "SIGTERM, 129 SIGHUP); 0 (or above about 146 years): no "
                  "limit",
                  0, End::kClosed);
}

FlagTable JsonFlag() {
  return {TextFlag("json", "print a JSON summary on stdout")};
}

FlagSpec AllowUnconvergedFlag() {
  return TextFlag("allow_unconverged",
                  "exit 0 (with a warning line) even if a solve missed its "
                  "stopping criterion; without it such a run writes its "
                  "outputs and exits " +
                      std::to_string(kExitNotConverged));
}

FlagSpec AllowUnsolvedFlag() {
  return TextFlag("allow_unsolved",
                  "exit 0 (with a warning line naming the step) even if an "
                  "EXP step has no solution; without it exit " +
                      std::to_string(kExitNotConverged));
}

const FlagSpec* FindFlag(const FlagTable& table, const std::string& name) {
  for (const FlagSpec& spec : table) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

}  // namespace shellspace
