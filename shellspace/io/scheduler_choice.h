// The --scheduler value of the collection front ends (the `collection`
// verbs, shellspace.collections): where their tasks run.
#ifndef SHELLSPACE_IO_SCHEDULER_CHOICE_H_
#define SHELLSPACE_IO_SCHEDULER_CHOICE_H_

#include <string>

namespace shellspace {

// The most local workers this machine holds: one per core (at least 2; each
// runs one solver thread), and each with kLocalWorkerBytes of memory.
inline constexpr double kLocalWorkerBytes = 512.0 * (1 << 20);
int MostLocalWorkers();

// none (in this process), local (a local cluster of `local_workers`
// processes, 0: the front end's default), local:N (1 <= N <=
// MostLocalWorkers()) or the address of a running scheduler
// ([tcp://|tls://]HOST:PORT, PORT in 1..65535).
struct SchedulerChoice {
  enum class Kind { kNone, kLocal, kAddress };
  Kind kind = Kind::kNone;
  int local_workers = 0;
  std::string address;
};

// The choice of `value`; InputError (one line) for anything else. A keyword
// in another case ("LOCAL:2", "None") or none with a count is refused, not
// taken for a host named local.
SchedulerChoice ParseScheduler(const std::string& value);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_SCHEDULER_CHOICE_H_
