#include "python/solve_control.h"

#include <signal.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <sstream>
#include <utility>

#include "shellspace/geometry/mesh.h"

namespace py = pybind11;

namespace shellspace {
namespace {

static_assert(std::atomic<unsigned>::is_always_lock_free,
              "the signal handler needs a lock-free atomic");

constexpr int kTimeLimit = 1;
constexpr int kInterrupt = 2;
constexpr int kRaised = 3;

// shellspace.NotConvergedError (a new reference kept for the process).
PyObject* g_not_converged = nullptr;

// The SIGINT chain: installed while at least one call solves (g_solving),
// counting the signals for the polls and calling Python's handler.
std::atomic<unsigned> g_sigint_count{0};
std::mutex g_chain_mutex;
int g_solving = 0;             // calls inside Solving, under the mutex
bool g_chained = false;        // our handler is installed
struct sigaction g_python_action;  // Python's, set while g_chained

extern "C" void OnSigint(int signal_number, siginfo_t* info, void* context) {
  g_sigint_count.fetch_add(1);
  if (g_python_action.sa_flags & SA_SIGINFO) {
    g_python_action.sa_sigaction(signal_number, info, context);
  } else {
    g_python_action.sa_handler(signal_number);
  }
}

bool IsHandlerFunction(const struct sigaction& action) {
  if (action.sa_flags & SA_SIGINFO) return action.sa_sigaction != nullptr;
  return action.sa_handler != SIG_DFL && action.sa_handler != SIG_IGN &&
         action.sa_handler != nullptr;
}

void EnterSolving() {
  std::lock_guard<std::mutex> lock(g_chain_mutex);
  if (g_solving++ > 0) return;
  struct sigaction current {};
  if (sigaction(SIGINT, nullptr, &current) != 0 || !IsHandlerFunction(current)) {
    return;  // SIG_IGN / SIG_DFL: the user's choice stands
  }
  g_python_action = current;
  struct sigaction chained {};
  chained.sa_sigaction = OnSigint;
  sigemptyset(&chained.sa_mask);
  chained.sa_flags = SA_SIGINFO | SA_RESTART | (current.sa_flags & SA_ONSTACK);
  g_chained = sigaction(SIGINT, &chained, nullptr) == 0;
}

void LeaveSolving() {
  std::lock_guard<std::mutex> lock(g_chain_mutex);
  if (--g_solving > 0 || !g_chained) return;
  struct sigaction current {};
  // Restored only if ours is still the handler (not replaced meanwhile).
  if (sigaction(SIGINT, nullptr, &current) == 0 &&
      (current.sa_flags & SA_SIGINFO) && current.sa_sigaction == OnSigint) {
    sigaction(SIGINT, &g_python_action, nullptr);
  }
  g_chained = false;
}

// Attaches `result` to the exception being raised (as `result`).
void AttachResult(const py::object& result) {
  PyObject *type = nullptr, *value = nullptr, *trace = nullptr;
  PyErr_Fetch(&type, &value, &trace);
  PyErr_NormalizeException(&type, &value, &trace);
  if (value != nullptr &&
      PyObject_SetAttrString(value, "result", result.ptr()) != 0) {
    PyErr_Clear();  // an exception without attributes: raised as it is
  }
  PyErr_Restore(type, value, trace);
}

std::string Join(const std::vector<std::string>& items) {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i) text += (i ? "; " : "") + items[i];
  return text;
}

}  // namespace

std::string Short(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

void RegisterNotConvergedError(py::module_& module) {
  if (g_not_converged == nullptr) {
    g_not_converged = PyErr_NewExceptionWithDoc(
        "shellspace.NotConvergedError",
        "A solve missed its stopping criterion, or time_limit cut it short "
        "(the CLI's exit 4 / 124). Attributes: result (what the call would "
        "have returned), summary (its summary dict, with 'partial' and "
        "'stop_reason'), failures (what did not converge), stop_reason. "
        "allow_unconverged=True returns the result instead.",
        PyExc_RuntimeError, nullptr);
    if (g_not_converged == nullptr) throw py::error_already_set();
  }
  module.attr("NotConvergedError") =
      py::reinterpret_borrow<py::object>(g_not_converged);
}

SolveControl::SolveControl(std::optional<double> time_limit)
    : state_(std::make_shared<State>()) {
  state_->sigint_count = g_sigint_count.load();
  state_->caller = std::this_thread::get_id();
  state_->next_signal_check = std::chrono::steady_clock::now();
  if (!time_limit) return;
  const double seconds = *time_limit;
  if (std::isnan(seconds) || seconds < 0) {
    std::ostringstream text;
    text << "time_limit must be >= 0 seconds (0 or None: no limit), got "
         << seconds;
    throw InputError(text.str());
  }
  if (seconds == 0) return;
  time_limit_ = seconds;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point now = Clock::now();
  // The seconds the clock can still count: a limit beyond half of them
  // (inf, 1e10 s; the clock's range is ~292 years) is no limit, and
  // converting it to the clock's ticks cannot overflow.
  const double room =
      std::chrono::duration<double>(Clock::time_point::max() - now).count();
  if (!(seconds < 0.5 * room)) return;
  state_->has_deadline = true;
  state_->deadline =
      now + std::chrono::duration_cast<Clock::duration>(
                std::chrono::duration<double>(seconds));
}

SolveControl::~SolveControl() {
  Py_XDECREF(state_->raised_type);
  Py_XDECREF(state_->raised_value);
  Py_XDECREF(state_->raised_trace);
  state_->raised_type = state_->raised_value = state_->raised_trace = nullptr;
  if (pending_type_ == nullptr) return;
  // Not raised (the call failed otherwise after its solves): the
  // interrupt is delivered again, so that it is not lost.
  const bool interrupt =
      PyErr_GivenExceptionMatches(pending_type_, PyExc_KeyboardInterrupt);
  Py_XDECREF(pending_type_);
  Py_XDECREF(pending_value_);
  Py_XDECREF(pending_trace_);
  if (interrupt) PyErr_SetInterrupt();
}

StopToken SolveControl::Token() const {
  std::shared_ptr<State> state = state_;
  return StopToken([state] {
    if (state->cause.load() != 0) return true;
    int none = 0;
    if (g_sigint_count.load() != state->sigint_count) {
      state->cause.compare_exchange_strong(none, kInterrupt);
      return true;
    }
    const auto now = std::chrono::steady_clock::now();
    if (state->has_deadline && now >= state->deadline) {
      state->cause.compare_exchange_strong(none, kTimeLimit);
      return true;
    }
    // Python's handlers of other signals, from the calling thread (the
    // only one they run in), at most every 100 ms.
    if (std::this_thread::get_id() == state->caller &&
        now >= state->next_signal_check && Py_IsInitialized()) {
      state->next_signal_check = now + std::chrono::milliseconds(100);
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        PyErr_Fetch(&state->raised_type, &state->raised_value,
                    &state->raised_trace);
        state->cause.compare_exchange_strong(none, kRaised);
        return true;
      }
    }
    return false;
  });
}

bool SolveControl::stopped() const { return state_->cause.load() != 0; }

std::string SolveControl::stop_reason() const {
  switch (state_->cause.load()) {
    case kTimeLimit: {
      std::ostringstream text;
      text << "time limit " << time_limit_ << " s";
      return text.str();
    }
    case kInterrupt:
      return "SIGINT";
    case kRaised:
      return "a signal handler raised";
    default:
      return "";
  }
}

SolveControl::Solving::Solving(SolveControl& control) : control_(control) {
  EnterSolving();
  release_.emplace();
}

SolveControl::Solving::~Solving() {
  release_.reset();  // the GIL again
  LeaveSolving();
  // An exception leaving the solve: the interpreter handles the signal at
  // its next check.
  if (std::uncaught_exceptions() > 0 || control_.pending_type_ != nullptr) {
    return;
  }
  State& state = *control_.state_;
  if (state.raised_type != nullptr) {
    // What a signal handler raised in a poll: raised by Finish.
    control_.pending_type_ = std::exchange(state.raised_type, nullptr);
    control_.pending_value_ = std::exchange(state.raised_value, nullptr);
    control_.pending_trace_ = std::exchange(state.raised_trace, nullptr);
    return;
  }
  if (PyErr_CheckSignals() != 0) {
    PyErr_Fetch(&control_.pending_type_, &control_.pending_value_,
                &control_.pending_trace_);
  }
}

py::object SolveControl::Finish(py::object result, py::object summary,
                                const std::string& verb,
                                std::vector<std::string> failures,
                                bool allow_unconverged) {
  // What Python's SIGINT handler raised, with the result.
  if (pending_type_ != nullptr) {
    PyErr_Restore(pending_type_, pending_value_, pending_trace_);
    pending_type_ = pending_value_ = pending_trace_ = nullptr;
    AttachResult(result);
    throw py::error_already_set();
  }
  if (PyErr_CheckSignals() != 0) {
    AttachResult(result);
    throw py::error_already_set();
  }
  const std::string reason = stop_reason();
  if (allow_unconverged || (failures.empty() && reason.empty())) {
    return result;
  }
  std::string message = verb + ": ";
  if (!reason.empty()) {
    message += "stopped (" + reason + ")" +
               (failures.empty() ? ": the result is partial"
                                 : ", not converged: " + Join(failures));
  } else {
    message += "not converged: " + Join(failures);
  }
  message += " (allow_unconverged=True returns it)";
  py::object type = py::reinterpret_borrow<py::object>(g_not_converged);
  py::object error = type(message);
  error.attr("result") = result;
  error.attr("summary") = summary;
  py::list failure_list;
  for (const std::string& failure : failures) failure_list.append(failure);
  error.attr("failures") = failure_list;
  error.attr("stop_reason") = reason;
  PyErr_SetObject(g_not_converged, error.ptr());
  throw py::error_already_set();
}

}  // namespace shellspace
