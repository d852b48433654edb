// Stopping a run early: --time_limit SECONDS and SIGINT / SIGTERM / SIGHUP
// (a closed terminal: handled as SIGTERM is). A signal the starting
// process ignored (`nohup`: SIGHUP; a script's background job: SIGINT)
// stays ignored.
//
// The signal handler only records the signal in a std::atomic (the one
// process-wide stop state, here in the CLI: the library keeps none). The
// run hands stop tokens made from it down: the solvers ask
// SolveStopToken() between iterations (SolverSettings::stop), end at their
// best iterate, and the verb writes what it has: complete frames, and
// "partial": true with the reason in --json and summary.json; the readers
// of its inputs ask ReadStopToken(). A second
// signal terminates at once (the default action; the
// temporaries a killed run may leave are hidden or end in .tmp-PID-N, and
// readers skip them).
//
// Exit codes of a stopped run: 124 after --time_limit (as timeout(1)),
// 129 after SIGHUP, 130 after SIGINT, 143 after SIGTERM (128 + the signal,
// as a shell reports a killed command).
//
// The time limit is a stopping rule of the user: a run it does not stop
// computes the same numbers as without it. A limit beyond the steady
// clock's range (more than about 146 years, e.g. 1e10 s) is no limit.
#ifndef SHELLSPACE_TOOLS_RUN_STOP_REQUEST_H_
#define SHELLSPACE_TOOLS_RUN_STOP_REQUEST_H_

#include <string>

#include "shellspace/runtime/stop_token.h"

namespace shellspace {

enum class StopCause { kNone, kTimeLimit, kInterrupt, kTerminate, kHangup };

// Installs the SIGINT / SIGTERM / SIGHUP handlers and starts the clock of
// `time_limit_seconds` (<= 0: no limit). Called once by main.
void InstallStopHandlers(double time_limit_seconds);

// The token of the run's solves (SolverSettings::stop): says stop once a
// signal arrived or the time limit passed; the first time it says stop,
// that cause is recorded (ObservedStopCause).
StopToken SolveStopToken();

// The token of the run's readers (io/input_file.h): says stop once
// RequestedStopCause() is not kNone (the time limit stops solves only).
StopToken ReadStopToken();

// The cause the solves' token said stop for (a solve was cut short), or
// kNone.
StopCause ObservedStopCause();
// That cause, else a signal received, observed by a solve or not (kNone if
// none; the time limit only counts once observed).
StopCause RequestedStopCause();

// "time limit 10 s", "SIGINT", "SIGTERM", "SIGHUP", or "" for kNone.
std::string StopCauseText(StopCause cause);
// 124, 130, 143, 129, or 0 for kNone.
int StopExitCode(StopCause cause);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_STOP_REQUEST_H_
