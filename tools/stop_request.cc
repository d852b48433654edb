#include "shellspace/tools/stop_request.h"

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
  return StopCause::kNone;
}

void Observe(StopCause cause) {
  int none = 0;
  g_observed.compare_exchange_strong(none, static_cast<int>(cause));
}

bool Poll() {
  const int signal_number = g_signal.load();
  if (signal_number != 0) {
    Observe(CauseOfSignal(signal_number));
    return true;
  }
  if (g_observed.load() != 0) return true;  // the time limit, latched
  if (g_time_limit > 0 && std::chrono::steady_clock::now() >= g_deadline) {
    Observe(StopCause::kTimeLimit);
    return true;
  }
  return false;
}

}  // namespace

void InstallStopHandlers(double time_limit_seconds) {
  g_time_limit = time_limit_seconds;
  if (time_limit_seconds > 0) {
    g_deadline = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(time_limit_seconds));
  }
  struct sigaction action {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // writes in progress are not interrupted
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
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
  }
  return 0;
}

}  // namespace shellspace
