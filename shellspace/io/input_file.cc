#include "shellspace/io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <utility>

namespace shellspace {
namespace {

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

void CheckReadStop(const StopToken& stop, const std::string& path) {
  if (stop.stop_requested()) throw ReadStopped(path);
}

std::int64_t CheckInputFile(const std::string& path, const std::string& what,
                            std::int64_t max_bytes) {
  return InputFile(path, what, max_bytes).size();
}

InputFile::InputFile(const std::string& path, const std::string& what,
                     std::int64_t max_bytes, StopToken stop)
    : path_(path), what_(what), max_bytes_(max_bytes), stop_(std::move(stop)) {
  fd_ = OpenInputFile(path, what, max_bytes, &size_);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

const std::string& InputFile::Read(size_t limit) {
  CheckReadStop(stop_, path_);
  constexpr size_t kChunk = size_t{1} << 20;
  // One allocation of the size and a spare byte that sees the end; more
  // only if more comes (files of /proc report size 0, a file may grow), but
  // never more than max_bytes.
  if (bytes_.empty() && !at_end_) {
    bytes_.reserve(static_cast<size_t>(size_) + 1);
  }
  while (!at_end_ && bytes_.size() < limit) {
    const size_t got = bytes_.size();
    const size_t room =
        bytes_.capacity() > got ? bytes_.capacity() : got + kChunk;
    const size_t most = static_cast<size_t>(max_bytes_) + 1;  // to refuse
    const size_t want = std::min(
        {kChunk, room - got, limit - got, most > got ? most - got : size_t{1}});
    bytes_.resize(got + want);
    const ssize_t n = ::read(fd_, &bytes_[got], want);
    if (n < 0) {
      const int error = errno;
      bytes_.resize(got);
      if (error == EINTR) {
        CheckReadStop(stop_, path_);
        continue;
      }
      throw InputError("cannot read " + what_ + " " + path_ + " (" +
                       std::strerror(error) + ")");
    }
    bytes_.resize(got + static_cast<size_t>(n));
    if (n == 0) {
      at_end_ = true;
      break;
    }
    CheckSize(path_, what_, static_cast<std::int64_t>(bytes_.size()),
              max_bytes_);
    CheckReadStop(stop_, path_);
  }
  return bytes_;
}

std::string InputFile::ReadAll() {
  Read(std::numeric_limits<size_t>::max());
  return std::move(bytes_);
}

std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::int64_t max_bytes, const StopToken& stop) {
  return InputFile(path, what, max_bytes, stop).ReadAll();
}

}  // namespace shellspace
