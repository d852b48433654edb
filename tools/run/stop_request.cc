#include "tools/run/stop_request.h"

#include <signal.h>

#include <atomic>
#include <chrono>
#include <sstream>

namespace shellspace {
namespace {

static_assert(std::atomic<int>::is_always_lock_free,
              "the signal handler needs a lock-free atomic");

std::atomic<int> g_signal{0};    // the first signal received, or 0
std::atomic<int> g_observed{0};  // a StopCause, once a poll returned true
double g_time_limit = 0;
bool g_has_deadline = false;  // false: no limit, or one beyond the clock
std::chrono::steady_clock::time_point g_deadline;

extern "C" void OnStopSignal(int signal_number) {
  int none = 0;
  if (!g_signal.compare_exchange_strong(none, signal_number)) {
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
  g_observed.compare_exchange_strong(none, static_cast<int>(cause));
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

bool Poll() {
  const int signal_number = g_signal.load();
  if (signal_number != 0) {
    Observe(CauseOfSignal(signal_number));
    return true;
  }
  if (g_observed.load() != 0) return true;  // the time limit, latched
  if (g_has_deadline && std::chrono::steady_clock::now() >= g_deadline) {
    Observe(StopCause::kTimeLimit);
    return true;
  }
  return false;
}

}  // namespace

void InstallStopHandlers(double time_limit_seconds) {
  g_time_limit = time_limit_seconds;
  g_has_deadline =
      time_limit_seconds > 0 &&
      DeadlineAfter(time_limit_seconds, std::chrono::steady_clock::now(),
                    &g_deadline);
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

StopPoll StopPollForRun() { return [] { return Poll(); }; }

StopCause ObservedStop() { return static_cast<StopCause>(g_observed.load()); }

StopCause RequestedStop() {
  const StopCause observed = ObservedStop();
  if (observed != StopCause::kNone) return observed;
  return CauseOfSignal(g_signal.load());
}

std::string StopCauseText(StopCause cause) {
  switch (cause) {
    case StopCause::kNone:
      return "";
    case StopCause::kTimeLimit: {
      std::ostringstream text;
      text << "time limit " << g_time_limit << " s";
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
