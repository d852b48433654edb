// How a workflow's solves ended, in its result: numerical failure is an
// outcome, not an exception (InputError is for bad input only).
#ifndef SHELLSPACE_WORKFLOWS_SOLVE_STATUS_H_
#define SHELLSPACE_WORKFLOWS_SOLVE_STATUS_H_

#include <string>
#include <vector>

namespace shellspace {
namespace workflows {

struct SolveStatus {
  enum class Code {
    kConverged,     // every solve met its stopping criterion
    kNotConverged,  // a solve stopped short of it (iterations, stagnation)
    kStopped,       // the stop token (SolverSettings::stop) ended the solves
    kFailed,        // a solve could not run (Ceres' FAILURE, a degenerate
                    // start): the result holds what there was before it
  };
  Code code = Code::kConverged;
  // One line: "" when converged, else what went wrong (the failures joined
  // by "; ", or the failure of the solve that could not run).
  std::string message;
  // What missed its stopping criterion, one line each (the front ends'
  // verdicts: the CLI's "not converged: A; B", NotConvergedError.failures).
  std::vector<std::string> failures;

  bool ok() const { return code == Code::kConverged; }
  bool failed() const { return code == Code::kFailed; }
};

// "converged", "not converged", "stopped", "failed".
const char* SolveStatusName(SolveStatus::Code code);

// The status of solves with these failures (kNotConverged if any, message
// their join), stopped by the token or not (kStopped wins over
// kNotConverged: a stopped solve is short of its criterion by choice).
SolveStatus StatusOf(std::vector<std::string> failures, bool stopped);

// The status of a solve that could not run: kFailed, message
// "WHAT failed: WHY".
SolveStatus FailedStatus(const std::string& what, const std::string& why);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_SOLVE_STATUS_H_
