// Atomic file writing: every file the library and the CLI write goes through
// here. The content is written to a temporary sibling of the target, unique
// to the process and the call ("<path>.tmp-<pid>-<start>-<n>", <start> the
// process's start time, ProcessTag below: it never ends in a
// mesh or image extension, so a directory listing of frames does not pick
// it up), then renamed into place (no fsync). A failure removes the
// temporary and leaves any earlier file at the target untouched.
#ifndef SHELLSPACE_IO_ATOMIC_FILE_H_
#define SHELLSPACE_IO_ATOMIC_FILE_H_

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace shellspace {

// Writes the bytes a callback puts into the stream. Throws InputError
// (geometry/mesh.h) if the temporary cannot be opened or written or the
// rename fails; an exception from `write` propagates after the temporary is
// removed.
using StreamWriter = std::function<void(std::ostream&)>;
void WriteFileAtomically(const std::string& path, const StreamWriter& write);

// Writes `content` (text or binary bytes).
void WriteFileAtomically(const std::string& path, const std::string& content);

// Several files that appear together or not at all: Add() writes each one's
// temporary; Commit() renames them all into place. Destroying the set
// without Commit() (an exception on the way) removes the temporaries.
class AtomicFileSet {
 public:
  AtomicFileSet() = default;
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;
  ~AtomicFileSet();

  void Add(const std::string& path, const StreamWriter& write);
  void Add(const std::string& path, const std::string& content);
  void Commit();

 private:
  struct Entry {
    std::string path, temporary;
  };
  std::vector<Entry> entries_;
};

// The temporary sibling name for `path` (unique per process and call).
std::string TemporarySibling(const std::string& path);

// "<pid>-<start>": this process in the names of its temporaries, <start>
// its start time in clock ticks after boot (/proc/self/stat; 0 if
// unknown), so that a later run can tell the temporaries of a process that
// has ended from those of one that runs (a pid alone may be reused).
std::string ProcessTag();

// True if the process `pid` that started at `start` (0: unknown) has
// ended: no process has that pid, or the one that has it started at
// another time. False while it may run (also when it cannot be told).
bool ProcessEnded(long pid, unsigned long long start);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_ATOMIC_FILE_H_
