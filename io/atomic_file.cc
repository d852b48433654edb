#include "shellspace/io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>

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

StreamWriter ContentWriter(const std::string& content) {
  return [&content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  };
}

}  // namespace

std::string TemporarySibling(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-" +
         std::to_string(counter++);
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
