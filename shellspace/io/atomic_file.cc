#include "shellspace/io/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "shellspace/geometry/mesh.h"

namespace shellspace {
namespace {

// Writes `write`'s bytes to `temporary`; on any failure removes it and
// throws (an InputError naming `path`, or `write`'s own exception).
void WriteTemporary(const std::string& path, const std::string& temporary,
                    const StreamWriter& write) {
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError("cannot open " + path + " for writing");
  try {
    write(out);
  } catch (...) {
    out.close();
    std::remove(temporary.c_str());
    throw;
  }
  out.close();
  if (!out) {
    std::remove(temporary.c_str());
    throw InputError("failed writing " + path);
  }
}

void Rename(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw InputError("cannot write " + path);
  }
}

// The start time (field 22 of /proc/PID/stat, after the parenthesised
// command name, which may hold spaces), or 0 if it cannot be read.
unsigned long long StartTimeOf(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(in, line)) return 0;
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(line.substr(close + 1));
  std::string field;
  for (int i = 3; i <= 22; ++i) {  // fields 3 (state) to 22 (starttime)
    if (!(fields >> field)) return 0;
  }
  try {
    return std::stoull(field);
  } catch (const std::exception&) {
    return 0;
  }
}

StreamWriter ContentWriter(const std::string& content) {
  return [&content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  };
}

}  // namespace

std::string TemporarySibling(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp-" + ProcessTag() + "-" + std::to_string(counter++);
}

std::string ProcessTag() {
  // Cached per thread and re-read after a fork (a new pid).
  thread_local long cached_pid = -1;
  thread_local std::string tag;
  const long pid = static_cast<long>(::getpid());
  if (pid != cached_pid) {
    tag = std::to_string(pid) + "-" + std::to_string(StartTimeOf(pid));
    cached_pid = pid;
  }
  return tag;
}

bool ProcessEnded(long pid, unsigned long long start) {
  if (pid <= 0) return false;
  if (::kill(static_cast<pid_t>(pid), 0) != 0) return errno == ESRCH;
  if (start == 0) return false;  // a process has the pid: maybe the owner
  const unsigned long long now = StartTimeOf(pid);
  return now != 0 && now != start;
}

void WriteFileAtomically(const std::string& path, const StreamWriter& write) {
  const std::string temporary = TemporarySibling(path);
  WriteTemporary(path, temporary, write);
  Rename(temporary, path);
}

void WriteFileAtomically(const std::string& path, const std::string& content) {
  WriteFileAtomically(path, ContentWriter(content));
}

AtomicFileSet::~AtomicFileSet() {
  for (const Entry& entry : entries_) std::remove(entry.temporary.c_str());
}

void AtomicFileSet::Add(const std::string& path, const StreamWriter& write) {
  Entry entry{path, TemporarySibling(path)};
  WriteTemporary(path, entry.temporary, write);
  entries_.push_back(std::move(entry));
}

void AtomicFileSet::Add(const std::string& path, const std::string& content) {
  Add(path, ContentWriter(content));
}

void AtomicFileSet::Commit() {
  while (!entries_.empty()) {
    const Entry entry = entries_.front();
    entries_.erase(entries_.begin());
    Rename(entry.temporary, entry.path);
  }
}

}  // namespace shellspace
