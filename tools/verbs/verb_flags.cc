#include "tools/verbs/verb_flags.h"

#include "shellspace/solvers/solver_settings.h"
#include "tools/run/run_status.h"

#include <cmath>
#include <sstream>

namespace shellspace {
namespace {

std::string Number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

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
  return {
      RealFlag("mu", "membrane Lame weight mu", 0, End::kOpen),
      RealFlag("lambda", "membrane Lame weight lambda", 0, End::kOpen),
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
               0, End::kClosed),
      TextFlag("bending",
               "bending model: discrete-shells (default) or shape-operator"),
  };
}

FlagTable SolverFlags() {
  return {
      RealFlag("tolerance",
               "stop when the gradient max-norm falls below this times "
               "max(1, its initial value)",
               0, End::kOpen, 1, End::kOpen),
      IntegerFlag("max_iterations",
                  "maximum iterations of the verb's outer solver (LM "
                  "iterations summed over its stages; spline: L-BFGS); inner "
                  "solves keep their own limits",
                  1),
      IntegerFlag("threads", "threads of the solves", 1, kMaxSolverThreads),
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
