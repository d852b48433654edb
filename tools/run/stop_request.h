// Stopping a run early: --time_limit SECONDS and SIGINT / SIGTERM / SIGHUP
// (a closed terminal: handled as SIGTERM is). A signal the starting
// process ignored (`nohup`: SIGHUP; a script's background job: SIGINT)
// stays ignored.
//
// The signal handler only records the signal in a std::atomic; the solvers
// poll StopPollForRun() between iterations (SolverSettings::stop), end at
// their best iterate, and the verb writes what it has: complete frames, and
// "partial": true with the reason in --json and summary.json. A second
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

#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

enum class StopCause { kNone, kTimeLimit, kInterrupt, kTerminate, kHangup };

// Installs the SIGINT / SIGTERM / SIGHUP handlers and starts the clock of
// `time_limit_seconds` (<= 0: no limit). Called once by main.
void InstallStopHandlers(double time_limit_seconds);

// The poll for SolverSettings::stop: true once a signal arrived or the time
// limit passed; the first time it returns true, that cause is recorded as
// observed.
StopPoll StopPollForRun();

// The cause a poll returned true for (a solve was cut short), or kNone.
StopCause ObservedStop();
// A signal received, observed by a solve or not (kNone if none; the time
// limit only counts once observed).
StopCause RequestedStop();

// "time limit 10 s", "SIGINT", "SIGTERM", "SIGHUP", or "" for kNone.
std::string StopCauseText(StopCause cause);
// 124, 130, 143, 129, or 0 for kNone.
int StopExitCode(StopCause cause);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_STOP_REQUEST_H_
