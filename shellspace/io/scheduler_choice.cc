#include "shellspace/io/scheduler_choice.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/ascii_lowercase.h"

namespace shellspace {
namespace {

// local:N: N in 1..MostLocalWorkers().
int LocalWorkerCount(const std::string& value) {
  const std::string count = value.substr(6);
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(count.c_str(), &end, 10);
  const int most = MostLocalWorkers();
  if (count.empty() || *end != '\0' || errno != 0 || n < 1 ||
      count.find_first_not_of("0123456789") != std::string::npos) {
    throw InputError("local:N needs a worker count N in 1.." +
                     std::to_string(most) + ", got '" + value + "'");
  }
  if (n > most) {
    throw InputError("local:" + count + ": this machine holds at most " +
                     std::to_string(most) +
                     " local workers (one per core, 512 MiB each)");
  }
  return static_cast<int>(n);
}

// [tcp://|tls://]HOST:PORT, PORT in 1..65535, HOST without blanks, commas
// or slashes.
void CheckAddress(const std::string& value) {
  std::string address = value;
  for (const char* scheme : {"tcp://", "tls://"}) {
    if (address.rfind(scheme, 0) == 0) address = address.substr(6);
  }
  const size_t colon = address.rfind(':');
  const std::string host =
      colon == std::string::npos ? "" : address.substr(0, colon);
  const std::string port =
      colon == std::string::npos ? "" : address.substr(colon + 1);
  const bool port_ok =
      !port.empty() && port.size() <= 5 &&
      port.find_first_not_of("0123456789") == std::string::npos &&
      std::stol(port) >= 1 && std::stol(port) <= 65535;
  if (host.empty() || !port_ok ||
      host.find_first_of(" \t\n,/") != std::string::npos ||
      address.find("://") != std::string::npos) {
    throw InputError("expected none, local, local:N or a scheduler address "
                     "HOST:PORT (tcp://HOST:8786, PORT 1..65535), got '" +
                     value + "'");
  }
}

}  // namespace

int MostLocalWorkers() {
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  const double memory = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                        static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  long most = std::max(2L, cores > 0 ? cores : 1L);
  if (memory > 0) {
    most = std::min(most, std::max(1L, static_cast<long>(
                                           memory / kLocalWorkerBytes)));
  }
  return static_cast<int>(most);
}

SchedulerChoice ParseScheduler(const std::string& value) {
  SchedulerChoice choice;
  if (value == "none") return choice;
  choice.kind = SchedulerChoice::Kind::kLocal;
  if (value == "local") return choice;
  const std::string lower = AsciiLowercase(value);
  if (lower != value && (lower == "none" || lower == "local" ||
                         lower.rfind("local:", 0) == 0 ||
                         lower.rfind("none:", 0) == 0)) {
    throw InputError("'" + value + "': the keywords none, local and local:N "
                     "are lower-case (did you mean '" + lower +
                     "'?); an address is HOST:PORT");
  }
  if (value.rfind("none:", 0) == 0) {
    throw InputError("'" + value + "': none takes no count (none, local, "
                     "local:N or a scheduler address HOST:PORT)");
  }
  if (value.rfind("local:", 0) == 0) {
    choice.local_workers = LocalWorkerCount(value);
    return choice;
  }
  CheckAddress(value);
  choice.kind = SchedulerChoice::Kind::kAddress;
  choice.address = value;
  return choice;
}

}  // namespace shellspace
