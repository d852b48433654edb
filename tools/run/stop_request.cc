#include "tools/run/stop_request.h"

#include <signal.h>

#include <atomic>
#include <chrono>
#include <sstream>

namespace shellspace {
namespace {

static_assert(std::atomic<int>::is_always_lock_free,
              "the signal handler needs a lock-free atomic");

// The run's stop state: the one a signal handler needs to exist for the
// whole process (it can reach nothing else), with the time limit set once
// by InstallStopHandlers before the verb runs.
struct RunStopState {
  std::atomic<int> signal{0};    // the first signal received, or 0
  std::atomic<int> observed{0};  // a StopCause, once a token said stop
  double time_limit = 0;
  bool has_deadline = false;  // false: no limit, or one beyond the clock
  std::chrono::steady_clock::time_point deadline;
};
RunStopState g_stop;

extern "C" void OnStopSignal(int signal_number) {
  int none = 0;
  if (!g_stop.signal.compare_exchange_strong(none, signal_number)) {
    // A second signal: the default action (terminate) now.
    ::signal(signal_number, SIG_DFL);
    ::raise(signal_number);
  }
}

StopCause CauseOfSignal(int signal_number) {
  if (signal_number == SIGINT) return StopCause::kInterrupt;
  if (signal_number == SIGTERM) return StopCause::kTerminate;
  if (signal_number == SIGHUP) return StopCause::kHangup;
  return StopCause::kNone;
}

void Observe(StopCause cause) {
  int none = 0;
  g_stop.observed.compare_exchange_strong(none, static_cast<int>(cause));
}

// A deadline `seconds` after `now`, or false if it lies beyond the clock's
// range (about 292 years of nanoseconds from the clock's epoch): such a
// limit never fires, so there is none. (Adding the duration unchecked
// overflowed for 1e10 s into a deadline in the past: an immediate stop.)
bool DeadlineAfter(double seconds,
                   std::chrono::steady_clock::time_point now,
                   std::chrono::steady_clock::time_point* deadline) {
  using Clock = std::chrono::steady_clock;
  const double room =
      std::chrono::duration<double>(Clock::time_point::max() - now).count();
  if (!(seconds < 0.5 * room)) return false;
  *deadline = now + std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>(seconds));
  return true;
}

// What the solves' token asks.
bool SolvesShouldStop() {
  const int signal_number = g_stop.signal.load();
  if (signal_number != 0) {
    Observe(CauseOfSignal(signal_number));
    return true;
  }
  if (g_stop.observed.load() != 0) return true;  // the time limit, latched
  if (g_stop.has_deadline &&
      std::chrono::steady_clock::now() >= g_stop.deadline) {
    Observe(StopCause::kTimeLimit);
    return true;
  }
  return false;
}

}  // namespace

void InstallStopHandlers(double time_limit_seconds) {
  g_stop.time_limit = time_limit_seconds;
  g_stop.has_deadline =
      time_limit_seconds > 0 &&
      DeadlineAfter(time_limit_seconds, std::chrono::steady_clock::now(),
                    &g_stop.deadline);
  struct sigaction action {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // writes in progress are not interrupted
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal ignored by whoever started the run (nohup, a background
    // job of a script) stays ignored.
    struct sigaction inherited {};
    if (sigaction(signal_number, nullptr, &inherited) == 0 &&
        inherited.sa_handler == SIG_IGN) {
      continue;
    }
    sigaction(signal_number, &action, nullptr);
  }
}

StopToken SolveStopToken() { return StopToken(SolvesShouldStop); }

StopToken ReadStopToken() {
  return StopToken([] { return RequestedStopCause() != StopCause::kNone; });
}

StopCause ObservedStopCause() {
  return static_cast<StopCause>(g_stop.observed.load());
}

StopCause RequestedStopCause() {
  const StopCause observed = ObservedStopCause();
  if (observed != StopCause::kNone) return observed;
  return CauseOfSignal(g_stop.signal.load());
}

std::string StopCauseText(StopCause cause) {
  switch (cause) {
    case StopCause::kNone:
      return "";
    case StopCause::kTimeLimit: {
      std::ostringstream text;
      text << "time limit " << g_stop.time_limit << " s";
      return text.str();
    }
    case StopCause::kInterrupt:
      return "SIGINT";
    case StopCause::kTerminate:
      return "SIGTERM";
    case StopCause::kHangup:
      return "SIGHUP";
  }
  return "";
}

int StopExitCode(StopCause cause) {
  switch (cause) {
    case StopCause::kNone:
      return 0;
    case StopCause::kTimeLimit:
      return 124;
    case StopCause::kInterrupt:
      return 130;
    case StopCause::kTerminate:
      return 143;
    case StopCause::kHangup:
      return 129;
  }
  return 0;
}

}  // namespace shellspace
