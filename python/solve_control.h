// How a Python call that solves ends early, and how it says so: the
// keyword time_limit, KeyboardInterrupt (SIGINT), and unconverged results.
//
// A call's solves ask the stop token SolveControl::Token() between
// iterations (SolverSettings::stop): it says stop once the call's time
// limit has passed or SIGINT arrived since the call began. They then end
// at their best state, which the call returns (or writes) marked
// "partial": true with "stop_reason" in its summary, as the CLI does for
// --time_limit and SIGINT. Asking the token reads two atomics and the
// clock: any thread may ask it, without the GIL, and a run it does not
// stop computes the same digits as without it.
//
// Other signals: the polls of the calling thread run Python's signal
// handlers every 100 ms (the GIL taken for that moment); a handler that
// raises (a SIGALRM handler's TimeoutError) stops the solves, and the call
// raises that exception with its result attached, as for SIGINT.
//
// SIGINT: while a solve runs (the GIL released) a C handler chained in
// front of Python's own counts the signal and calls Python's handler, so
// the interpreter sees the signal as always. After the solves the call
// builds its result and writes its files, then PyErr_CheckSignals() runs
// Python's handler: by default KeyboardInterrupt, raised with the call's
// result attached as its `result` attribute. (If Python's SIGINT handler
// is SIG_IGN or SIG_DFL, nothing is chained: the signal does what the user
// asked for.)
//
// Unconverged: a call whose solves missed their stopping criterion, or
// that the time limit cut short, raises shellspace.NotConvergedError (a
// RuntimeError) carrying the result -- the CLI's exit 4 (124 after a time
// limit) -- unless allow_unconverged=True, when it returns the result.
#ifndef SHELLSPACE_PYTHON_SOLVE_CONTROL_H_
#define SHELLSPACE_PYTHON_SOLVE_CONTROL_H_

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "python/strict_numbers.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// The Python type shellspace.NotConvergedError, created at import.
void RegisterNotConvergedError(pybind11::module_& module);

class SolveControl {
 public:
  // time_limit: None or 0 for none; seconds > 0 (a limit beyond the
  // clock's range, inf or 1e10, is none). Negative or NaN: InputError.
  // The clock starts here.
  explicit SolveControl(std::optional<double> time_limit);
  ~SolveControl();
  SolveControl(const SolveControl&) = delete;
  SolveControl& operator=(const SolveControl&) = delete;

  // The call's token, for SolverSettings::stop (any thread may ask it,
  // without the GIL).
  StopToken Token() const;
  // The token said stop: the solves were cut short.
  bool stopped() const;
  // "time limit 2 s", "SIGINT" for a stop the token said, else "".
  std::string stop_reason() const;

  // While alive: the GIL released and SIGINT counted for the polls. At
  // its end (the GIL taken back) Python's SIGINT handler runs at once
  // (PyErr_CheckSignals), before any Python code of the call could raise
  // its exception without the result; what it raised is kept for Finish.
  class Solving {
   public:
    explicit Solving(SolveControl& control);
    ~Solving();
    Solving(const Solving&) = delete;
    Solving& operator=(const Solving&) = delete;

   private:
    SolveControl& control_;
    std::optional<pybind11::gil_scoped_release> release_;
  };

  // The end of a call (the GIL held, outputs written): `result` returned,
  // or raised -- the exception of Python's SIGINT handler if it raised
  // (at the end of Solving, or now), or NotConvergedError(verb: failures) if `failures` is not
  // empty or the time limit stopped the solves, unless allow_unconverged
  // -- with `result` attached (attribute `result`; NotConvergedError also
  // has `summary`, `failures`, `stop_reason`). `summary` is the result's
  // summary dict.
  pybind11::object Finish(pybind11::object result, pybind11::object summary,
                          const std::string& verb,
                          std::vector<std::string> failures,
                          bool allow_unconverged);

 private:
  struct State {
    std::atomic<int> cause{0};  // 0 none, 1 time limit, 2 SIGINT, 3 raised
    unsigned sigint_count = 0;  // the count when the call began
    // The thread of the call: its polls run Python's signal handlers
    // (PyErr_CheckSignals, the GIL taken) at most every 100 ms, so that a
    // handler (SIGALRM, SIGTERM, ...) runs within a second during a solve;
    // what a handler raised stops the solves and is raised by Finish.
    std::thread::id caller;
    std::chrono::steady_clock::time_point next_signal_check;
    PyObject* raised_type = nullptr;
    PyObject* raised_value = nullptr;
    PyObject* raised_trace = nullptr;
    bool has_deadline = false;
    std::chrono::steady_clock::time_point deadline;
  };
  std::shared_ptr<State> state_;
  double time_limit_ = 0;
  // What Python's SIGINT handler raised at the end of Solving (owned
  // references; null: nothing), for Finish.
  PyObject* pending_type_ = nullptr;
  PyObject* pending_value_ = nullptr;
  PyObject* pending_trace_ = nullptr;
};

// "%.3g".
std::string Short(double value);

}  // namespace shellspace

#endif  // SHELLSPACE_PYTHON_SOLVE_CONTROL_H_
