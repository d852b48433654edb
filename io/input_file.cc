#include "shellspace/io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

namespace shellspace {
namespace {

std::function<bool()>& StopPoll() {
  static std::function<bool()> poll;
  return poll;
}

// "1 GiB", "256 MiB", or the byte count.
std::string LimitText(std::int64_t bytes) {
  if (bytes % (std::int64_t{1} << 30) == 0) {
    return std::to_string(bytes >> 30) + " GiB";
  }
  if (bytes % (std::int64_t{1} << 20) == 0) {
    return std::to_string(bytes >> 20) + " MiB";
  }
  return std::to_string(bytes) + " bytes";
}

// What a file of mode `mode` is, for "is a ..., not a mesh file"; "" for a
// regular file.
std::string KindOf(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void FailKind(const std::string& path, const std::string& what,
                           const std::string& kind) {
  throw InputError(path + ": is " + kind + ", not a " + what);
}

void CheckSize(const std::string& path, const std::string& what,
               std::int64_t size, std::int64_t max_bytes) {
  if (size > max_bytes) {
    throw InputError(path + ": " + std::to_string(size) +
                     " bytes, larger than the largest " + what + " read (" +
                     LimitText(max_bytes) + ")");
  }
}

// A descriptor closed on scope exit.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_;
};

// Opens `path` for reading after checking (stat, then fstat of the open
// descriptor) that it is a regular file of at most `max_bytes`; `size` is
// set to its size.
int OpenInputFile(const std::string& path, const std::string& what,
                  std::int64_t max_bytes, std::int64_t* size) {
  // stat first: a device or FIFO is refused without being opened (opening
  // some devices has effects).
  struct stat before {};
  if (::stat(path.c_str(), &before) == 0) {
    const std::string kind = KindOf(before.st_mode);
    if (!kind.empty()) FailKind(path, what, kind);
    CheckSize(path, what, static_cast<std::int64_t>(before.st_size), max_bytes);
  }
  int fd = -1;
  do {
    fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  } while (fd < 0 && errno == EINTR);
  if (fd < 0) {
    const int error = errno;
    throw InputError("cannot open " + what + " " + path + " (" +
                     std::strerror(error) + ")");
  }
  Descriptor guard(fd);
  // fstat of what was opened: the path may have been replaced since stat.
  struct stat opened {};
  if (::fstat(fd, &opened) != 0) {
    throw InputError("cannot read " + what + " " + path);
  }
  const std::string kind = KindOf(opened.st_mode);
  if (!kind.empty()) FailKind(path, what, kind);
  *size = static_cast<std::int64_t>(opened.st_size);
  CheckSize(path, what, *size, max_bytes);
  return guard.release();
}

}  // namespace

std::function<bool()> SetReadStopPoll(std::function<bool()> poll) {
  std::function<bool()> previous = std::move(StopPoll());
  StopPoll() = std::move(poll);
  return previous;
}

void CheckReadStop(const std::string& path) {
  const std::function<bool()>& poll = StopPoll();
  if (poll && poll()) throw ReadStopped(path);
}

std::int64_t CheckInputFile(const std::string& path, const std::string& what,
                            std::int64_t max_bytes) {
  std::int64_t size = 0;
  Descriptor fd(OpenInputFile(path, what, max_bytes, &size));
  return size;
}

std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::int64_t max_bytes) {
  std::int64_t size = 0;
  Descriptor fd(OpenInputFile(path, what, max_bytes, &size));
  CheckReadStop(path);
  // Read to the end, not only the size fstat gave (files of /proc report
  // 0, a file may grow), but never more than max_bytes: one allocation of
  // the size and a spare byte that sees the end, more only if more comes.
  constexpr size_t kChunk = size_t{1} << 20;
  std::string bytes(static_cast<size_t>(size) + 1, '\0');
  size_t got = 0;
  while (true) {
    if (got == bytes.size()) {
      bytes.resize(static_cast<size_t>(std::min<std::int64_t>(
          static_cast<std::int64_t>(got + kChunk), max_bytes + 1)));
    }
    const size_t want = std::min(kChunk, bytes.size() - got);
    const ssize_t n = ::read(fd.get(), &bytes[got], want);
    if (n < 0) {
      const int error = errno;
      if (error == EINTR) {
        CheckReadStop(path);
        continue;
      }
      throw InputError("cannot read " + what + " " + path + " (" +
                       std::strerror(error) + ")");
    }
    if (n == 0) break;
    got += static_cast<size_t>(n);
    CheckSize(path, what, static_cast<std::int64_t>(got), max_bytes);
    CheckReadStop(path);
  }
  bytes.resize(got);
  return bytes;
}

}  // namespace shellspace
