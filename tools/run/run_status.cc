#include "tools/run/run_status.h"

#include "tools/run/stop_request.h"

#include <gflags/gflags.h>

#include <cstdio>
#include <iostream>

#include "tools/run/common_flags.h"

DEFINE_bool(allow_unconverged, false,
            "see `shellspace VERB --help`");
DEFINE_bool(allow_unsolved, false, "see `shellspace VERB --help`");

namespace shellspace {
namespace {

// StoppedRunFailures(): written once, by the verb's thread, after its solves.
std::string g_stopped_failures;  // NOLINT(runtime/string)

}  // namespace

void RunStatus::Require(bool met, const std::string& what) {
  if (!met) failures_.push_back(what);
}

void RunStatus::Warn(const std::string& text) {
  warnings_.push_back(text);
  if (!FLAGS_quiet) std::cerr << verb_ << ": warning: " << text << "\n";
}

int RunStatus::Finish() const {
  if (ok()) return 0;
  std::string line;
  for (size_t i = 0; i < failures_.size(); ++i) {
    line += (i ? "; " : "") + failures_[i];
  }
  // A run cut short by a time limit or a signal: main reports the stop and
  // these failures in one line ("stopped (...)", exit 124, 130 or 143).
  if (ObservedStopCause() != StopCause::kNone) {
    g_stopped_failures = line;
    return 0;
  }
  if (FLAGS_allow_unconverged || FLAGS_allow_unsolved) {
    std::cerr << "shellspace " << verb_ << ": warning: not converged: " << line
              << "\n";
    return 0;
  }
  std::cerr << "shellspace " << verb_ << ": not converged: " << line << "\n";
  return kExitNotConverged;
}

std::string StoppedRunFailures() { return g_stopped_failures; }

std::string Short(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

std::string GradientAboveTarget(double gradient, double target) {
  return "|grad| " + Short(gradient) + " above the target " + Short(target);
}

}  // namespace shellspace
