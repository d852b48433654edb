// StopToken: a caller's request to stop early (an interrupt, a time limit,
// a cancelled call), handed down to whatever may take long.
#ifndef SHELLSPACE_RUNTIME_STOP_TOKEN_H_
#define SHELLSPACE_RUNTIME_STOP_TOKEN_H_

#include <functional>
#include <memory>
#include <utility>

namespace shellspace {

// The stopping rule of a caller, passed down explicitly: the solvers ask it
// between iterations (SolverSettings::stop), the readers between chunks of
// a file and every few thousand lines or rows (io/input_file.h), the loops
// of the problems and workflows between their steps. When it says stop, a
// solve ends at its current iterate (Ceres: the best accepted one; Newton:
// the last accepted point), a loop keeps what it completed, and a reader
// throws ReadStopped. The library keeps no stop state of its own: a front
// end makes the token from its own (the CLI's signals and --time_limit, the
// Python module's time_limit and KeyboardInterrupt).
//
// The default token never says stop. A token wraps a poll that any thread
// may call, often (it should be cheap: an atomic and the clock); copies
// share the poll (a copy costs a reference count). A run that no token
// stops computes the same numbers with or without one.
class StopToken {
 public:
  // A token that never says stop.
  StopToken() = default;
  // A token that says stop whenever `poll` returns true (an empty `poll`:
  // never).
  explicit StopToken(std::function<bool()> poll)
      : poll_(poll ? std::make_shared<const std::function<bool()>>(
                         std::move(poll))
                   : nullptr) {}

  // True if the caller asks to stop now.
  bool stop_requested() const { return poll_ && (*poll_)(); }
  // False for a token that never says stop: work done only so that a stop
  // can be seen (a Ceres iteration callback) can be skipped.
  bool stop_possible() const { return poll_ != nullptr; }

 private:
  std::shared_ptr<const std::function<bool()>> poll_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_RUNTIME_STOP_TOKEN_H_
