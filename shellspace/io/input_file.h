// Reading the files a run takes as input: regular files only, opened without
// blocking, read whole up to a size limit, and the caller's stop token asked
// while they are read and parsed.
#ifndef SHELLSPACE_IO_INPUT_FILE_H_
#define SHELLSPACE_IO_INPUT_FILE_H_

#include <cstdint>
#include <string>

#include "shellspace/geometry/mesh.h"
#include "shellspace/runtime/stop_token.h"

namespace shellspace {

// The largest mesh file read: 1 GiB (a binary PLY of 20 million vertices
// and 40 million double-precision triangles, far beyond what the solvers
// handle). Larger files, a sparse 20 GB file among them, are refused from
// their size before a byte is read.
constexpr std::int64_t kMaxMeshFileBytes = std::int64_t{1} << 30;
// The largest vertex mask read: 256 MiB.
constexpr std::int64_t kMaxMaskFileBytes = std::int64_t{1} << 28;
// The largest flag file read (gflags' --flagfile): 1 MiB.
constexpr std::int64_t kMaxFlagFileBytes = std::int64_t{1} << 20;

// A stop seen while reading: the reader ends with this (an InputError
// naming the file), and the caller reports the stop.
class ReadStopped : public InputError {
 public:
  explicit ReadStopped(const std::string& path)
      : InputError(path + ": reading stopped (stop requested)"), path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Every reader takes the caller's stop token (the default: none) and asks
// it between chunks of a file and every few thousand lines or rows of its
// content, so that a SIGTERM ends the read of the largest file within
// milliseconds; when it says stop the reader throws ReadStopped. (The CLI
// passes a token of SIGINT, SIGTERM and SIGHUP; tools/run/stop_request.h.)

// Throws ReadStopped(path) if `stop` says stop.
void CheckReadStop(const StopToken& stop, const std::string& path);

// Calls CheckReadStop every `period` calls of Tick (cheap in a loop).
// `path` and `stop` must outlive the ticker.
class ReadStopTicker {
 public:
  ReadStopTicker(const std::string& path, const StopToken& stop,
                 std::uint32_t period = 4096)
      : path_(path), stop_(stop), period_(period) {}
  void Tick() {
    if (++count_ >= period_) {
      count_ = 0;
      CheckReadStop(stop_, path_);
    }
  }

 private:
  const std::string& path_;
  const StopToken& stop_;
  const std::uint32_t period_;
  std::uint32_t count_ = 0;
};

// Checks that `path` names a regular file (a symbolic link to one counts) of
// at most `max_bytes` bytes without reading it: opened with O_NONBLOCK (so a
// FIFO without writer does not block) and fstat. Throws one InputError line
// naming the file and, for `what` ("mesh file"), the problem: missing,
// unreadable, a directory, a FIFO, a character or block device (/dev/zero,
// /dev/urandom), a socket, larger than `max_bytes`. Returns its size.
std::int64_t CheckInputFile(const std::string& path, const std::string& what,
                            std::int64_t max_bytes);

// A regular file being read: opened and checked as by CheckInputFile
// (the descriptor checked is the one read: a file replaced after the check
// is not read), then read in chunks of 1 MiB, asking `stop`
// (CheckReadStop) between them. Reads to the end of the file, not to the
// size fstat gave, but refuses it once more than `max_bytes` arrived (a
// file that grows, or reports size 0 as those of /proc do).
class InputFile {
 public:
  InputFile(const std::string& path, const std::string& what,
            std::int64_t max_bytes, StopToken stop = StopToken());
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The size fstat gave.
  std::int64_t size() const { return size_; }
  // Reads until `limit` bytes were read or the file ended; returns all
  // bytes read so far (a prefix to check a header on before the rest is
  // read).
  const std::string& Read(size_t limit);
  // Reads the rest and returns the whole content (moved out).
  std::string ReadAll();

 private:
  std::string path_, what_;
  std::int64_t max_bytes_;
  StopToken stop_;
  std::int64_t size_ = 0;
  int fd_ = -1;
  std::string bytes_;
  bool at_end_ = false;
};

// The whole content of the regular file `path` (InputFile::ReadAll).
std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::int64_t max_bytes,
                          const StopToken& stop = StopToken());

}  // namespace shellspace

#endif  // SHELLSPACE_IO_INPUT_FILE_H_
