// The verdict of a solving verb: which of its solves missed their stopping
// criterion. A verb that did not converge still writes its outputs and its
// --json summary, then prints one line naming what did not converge and
// exits with kExitNotConverged -- or, with --allow_unconverged (transport
// and shoot: also --allow_unsolved), prints that line as a warning and
// exits 0.
#ifndef SHELLSPACE_TOOLS_RUN_RUN_STATUS_H_
#define SHELLSPACE_TOOLS_RUN_RUN_STATUS_H_

#include <string>
#include <utility>
#include <vector>

namespace shellspace {

// The exit code of a run whose outputs were written but whose solves did
// not all meet their stopping criterion (1: bad input, 2: bad flags, 3:
// internal error).
inline constexpr int kExitNotConverged = 4;

class RunStatus {
 public:
  explicit RunStatus(std::string verb) : verb_(std::move(verb)) {}
  // Records `what` (e.g. "geodesic: relative gradient 5.4e-01 > tolerance
  // 1e-08 after 2 iterations") unless `met`.
  void Require(bool met, const std::string& what);
  // A warning line on stderr ("VERB: warning: TEXT") unless --quiet; also
  // kept for the JSON.
  void Warn(const std::string& text);
  bool ok() const { return failures_.empty(); }
  const std::vector<std::string>& failures() const { return failures_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  // After the outputs: 0 if ok; else one line "shellspace VERB: not
  // converged: A; B" on stderr and kExitNotConverged, or, with
  // --allow_unconverged / --allow_unsolved, the same line as a warning and
  // 0. A run cut short by a time limit or a signal returns 0 and leaves
  // "A; B" to StoppedRunFailures(): main's one "stopped (...)" line names
  // them.
  int Finish() const;

 private:
  std::string verb_;
  std::vector<std::string> failures_;
  std::vector<std::string> warnings_;
};

// The failures ("A; B") of the last RunStatus that finished in a run cut
// short by a time limit or a signal; "" if none.
std::string StoppedRunFailures();

// "%.3g" of a number, for the failure texts.
std::string Short(double value);

// "|grad| G above the target T" (both Short): how the failure text of a
// solve that stopped above its gradient target begins.
std::string GradientAboveTarget(double gradient, double target);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_RUN_STATUS_H_
