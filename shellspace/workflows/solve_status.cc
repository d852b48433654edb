#include "shellspace/workflows/solve_status.h"

#include <utility>

namespace shellspace {
namespace workflows {

const char* SolveStatusName(SolveStatus::Code code) {
  switch (code) {
    case SolveStatus::Code::kConverged:
      return "converged";
    case SolveStatus::Code::kNotConverged:
      return "not converged";
    case SolveStatus::Code::kStopped:
      return "stopped";
    case SolveStatus::Code::kFailed:
      return "failed";
  }
  return "";
}

SolveStatus StatusOf(std::vector<std::string> failures, bool stopped) {
  SolveStatus status;
  for (size_t i = 0; i < failures.size(); ++i) {
    status.message += (i ? "; " : "") + failures[i];
  }
  status.failures = std::move(failures);
  if (stopped) {
    status.code = SolveStatus::Code::kStopped;
    if (status.message.empty()) status.message = "stopped by request";
  } else if (!status.failures.empty()) {
    status.code = SolveStatus::Code::kNotConverged;
  }
  return status;
}

SolveStatus FailedStatus(const std::string& what, const std::string& why) {
  SolveStatus status;
  status.code = SolveStatus::Code::kFailed;
  status.message = what + " failed: " + why;
  return status;
}

}  // namespace workflows
}  // namespace shellspace
