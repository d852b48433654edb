// The readers' inputs: anything but a regular file (a FIFO, /dev/zero,
// /dev/urandom, a directory, a socket, a symbolic link to one of them) and a
// file above the size limit (a sparse 20 GB file) are one line naming the
// file and what it is, without blocking or reading; headers whose counts
// the file size cannot hold are refused before a row is read (a counting
// stop token shows that no loop ran over the declared rows); blank lines
// cost no memory per line; a token that says stop ends every reader with
// ReadStopped.
#include "shellspace/io/input_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "tests/testing/test_support.h"

#if defined(__SANITIZE_ADDRESS__)
#define SHELLSPACE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHELLSPACE_TEST_ASAN 1
#endif
#endif

namespace shellspace {
namespace {

std::string Write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The message of the InputError `read` throws, "accepted" if none.
std::string ErrorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

// Runs `f` in a child process and returns its result, or "timed out" after
// `seconds` (the child is killed): a reader that blocks on a FIFO or reads
// /dev/zero without end fails the test instead of hanging the suite. The
// child's address space is capped at 4 GB (not under ASan, whose shadow
// memory needs more).
std::string InChild(const std::function<std::string()>& f,
                    double seconds = 20) {
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
#ifndef SHELLSPACE_TEST_ASAN
    const rlimit limit{rlim_t{4} << 30, rlim_t{4} << 30};
    setrlimit(RLIMIT_AS, &limit);
#endif
    alarm(static_cast<unsigned>(seconds) + 1);
    std::string result;
    try {
      result = f();
    } catch (const std::exception& e) {
      result = std::string("exception: ") + e.what();
    }
    const ssize_t written = write(fds[1], result.data(), result.size());
    _exit(written == static_cast<ssize_t>(result.size()) ? 0 : 1);
  }
  close(fds[1]);
  const auto start = std::chrono::steady_clock::now();
  std::string result;
  bool timed_out = false;
  char chunk[4096];
  while (true) {
    if (std::chrono::steady_clock::now() - start >
        std::chrono::duration<double>(seconds)) {
      kill(pid, SIGKILL);
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    const ssize_t n = read(fds[0], chunk, sizeof(chunk));
    if (n <= 0) break;
    result.append(chunk, static_cast<size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (timed_out) return "timed out";
  if (!WIFEXITED(status)) return "child died: " + result;
  return result;
}

// A path (a symbolic link named .ply/.off/.txt) to `target`.
std::string LinkTo(const std::string& dir, const std::string& name,
                   const std::string& target) {
  const std::string path = dir + "/" + name;
  std::filesystem::create_symlink(target, path);
  return path;
}

// A stop token for a reader that counts the times it is asked (polls) and
// says stop at poll `stop_at` (0: never). Must outlive the read.
class CountingStopToken {
 public:
  explicit CountingStopToken(long stop_at = 0)
      : token_([this, stop_at] {
          ++polls_;
          return stop_at > 0 && polls_ >= stop_at;
        }) {}
  const StopToken& token() const { return token_; }
  long polls() const { return polls_; }

 private:
  long polls_ = 0;
  StopToken token_;
};

// The largest resident set of this process so far (VmHWM), in bytes.
long PeakResidentBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6)) * 1024;
  }
  return -1;
}

TEST(InputFileTest, SpecialFilesAreOneLineWithoutBlockingOrReading) {
  const std::string dir = testing::TempDir();
  const std::string fifo = dir + "/fifo.ply";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string fifo_mask = dir + "/fifo_mask.txt";
  ASSERT_EQ(mkfifo(fifo_mask.c_str(), 0600), 0);
  const std::string socket_path = dir + "/socket.off";
  const int sock = socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, socket_path.c_str(),
               sizeof(address.sun_path) - 1);
  ASSERT_EQ(bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)),
            0);
  std::filesystem::create_directory(dir + "/directory.obj");
  // Sparse files: 20 GB and one byte above each limit (no disk used).
  const auto sparse = [&dir](const std::string& name, std::int64_t size) {
    const std::string path = dir + "/" + name;
    const int fd = open(path.c_str(), O_CREAT | O_WRONLY, 0600);
    EXPECT_EQ(ftruncate(fd, size), 0);
    close(fd);
    return path;
  };
  const std::int64_t kGB = 1000 * 1000 * 1000;
  struct Case {
    std::string path;
    bool mask;
    std::string expected;
  };
  const std::string zero = LinkTo(dir, "zero.ply", "/dev/zero");
  const std::string urandom = LinkTo(dir, "urandom.off", "/dev/urandom");
  const std::string fifo_link = LinkTo(dir, "link_to_fifo.obj", fifo);
  const std::string huge = sparse("sparse.ply", 20 * kGB);
  const std::string above = sparse("above.off", kMaxMeshFileBytes + 1);
  const std::string huge_mask = sparse("sparse_mask.txt", 20 * kGB);
  const std::string above_mask = sparse("above.txt", kMaxMaskFileBytes + 1);
  const Case cases[] = {
      {fifo, false, fifo + ": is a FIFO (named pipe), not a mesh file"},
      {fifo_link, false,
       fifo_link + ": is a FIFO (named pipe), not a mesh file"},
      {zero, false, zero + ": is a character device, not a mesh file"},
      {urandom, false, urandom + ": is a character device, not a mesh file"},
      {dir + "/directory.obj", false,
       dir + "/directory.obj: is a directory, not a mesh file"},
      {socket_path, false, socket_path + ": is a socket, not a mesh file"},
      {huge, false,
       huge + ": 20000000000 bytes, larger than the largest mesh file read "
              "(1 GiB)"},
      {above, false,
       above + ": 1073741825 bytes, larger than the largest mesh file read "
               "(1 GiB)"},
      {dir + "/missing.ply", false,
       "cannot open mesh file " + dir +
           "/missing.ply (No such file or directory)"},
      {"/dev/zero", true, "/dev/zero: is a character device, not a mask file"},
      {"/dev/urandom", true,
       "/dev/urandom: is a character device, not a mask file"},
      {fifo_mask, true,
       fifo_mask + ": is a FIFO (named pipe), not a mask file"},
      {LinkTo(dir, "link_mask.txt", fifo_mask), true,
       dir + "/link_mask.txt: is a FIFO (named pipe), not a mask file"},
      {dir, true, dir + ": is a directory, not a mask file"},
      {huge_mask, true,
       huge_mask + ": 20000000000 bytes, larger than the largest mask file "
                   "read (256 MiB)"},
      {above_mask, true,
       above_mask + ": 268435457 bytes, larger than the largest mask file "
                    "read (256 MiB)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.path);
    const std::string message = InChild([&c] {
      CountingStopToken polls;
      const std::string error = ErrorOf([&c, &polls] {
        if (c.mask) {
          ReadMask(c.path, 10, polls.token());
        } else {
          ReadMesh(c.path, polls.token());
        }
      });
      // Refused before the first chunk was read.
      return polls.polls() == 0 ? error : error + " after a read";
    });
    EXPECT_EQ(message, c.expected);
  }
  close(sock);
  // 16 cases: 9 mesh paths, 7 mask paths.
  EXPECT_EQ(std::size(cases), 16u);
}

TEST(InputFileTest, ProcFilesOfSizeZeroAreReadToTheirEnd) {
  // /proc reports size 0 for files with content: read to the end, bounded by
  // the limit, not by the reported size.
  const std::string text =
      ReadInputFile("/proc/self/status", "status", 1 << 20);
  EXPECT_NE(text.find("VmHWM:"), std::string::npos);
  EXPECT_EQ(ErrorOf([] { ReadInputFile("/proc/self/status", "status", 16); }),
            "/proc/self/status: 17 bytes, larger than the largest status read "
            "(16 bytes)");
}

// A header declaring more than its file holds: refused from the counts and
// the file size, with the stop poll never reached (no loop over the rows).
TEST(InputFileTest, LyingHeadersAreRefusedFromTheirCountsAndTheFileSize) {
  const std::string dir = testing::TempDir();
  const std::string xyz =
      "property float x\nproperty float y\nproperty float z\n";
  const std::string list = "property list uchar int vertex_indices\n";
  const auto ply = [&](const std::string& format, const std::string& elements) {
    return "ply\nformat " + format + " 1.0\n" + elements + "end_header\n";
  };
  const std::string square_ascii =
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  std::string square_binary;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) {
    square_binary.append(reinterpret_cast<const char*>(&v), 4);
  }
  for (const auto& face : {std::array<int32_t, 3>{0, 1, 2}, {0, 2, 3}}) {
    square_binary += '\3';
    square_binary.append(reinterpret_cast<const char*>(face.data()), 12);
  }
  const std::string big = "2147483647";
  struct Case {
    std::string name, content, expected;
  };
  const std::string ascii = "ascii", binary = "binary_little_endian";
  // A valid binary square and an element of 2^31 - 1 rows without
  // properties (321 bytes; it used to loop for minutes, then be accepted).
  std::string issue_file =
      ply(binary,
          "comment a mesh with an extra element of no properties\n"
          "element vertex 4\n" +
              xyz + "element face 2\n" + list + "element junk " + big + "\n") +
      square_binary;
  const Case cases[] = {
      {"ascii_vertices.ply",
       ply(ascii,
           "element vertex " + big + "\n" + xyz + "element face 2\n" + list) +
           square_ascii,
       "PLY file ends early in element 'vertex': the header declares "
       "2147483647 rows of at least 6 bytes, more than the 40 bytes of data "
       "hold"},
      {"ascii_faces.ply",
       ply(ascii,
           "element vertex 4\n" + xyz + "element face " + big + "\n" + list) +
           square_ascii,
       "PLY file ends early in element 'face': the header declares "
       "2147483647 rows of at least 8 bytes, more than the 40 bytes of data "
       "hold"},
      {"ascii_extra.ply",
       ply(ascii, "element vertex 4\n" + xyz + "element face 2\n" + list +
                      "element junk " + big + "\nproperty uchar a\n") +
           square_ascii,
       "PLY file ends early in element 'junk': the header declares "
       "2147483647 rows of at least 2 bytes, more than the 40 bytes of data "
       "hold"},
      {"ascii_extra_no_properties.ply",
       ply(ascii, "element vertex 4\n" + xyz + "element face 2\n" + list +
                      "element junk " + big + "\n") +
           square_ascii,
       "PLY element 'junk' declares 2147483647 rows but has no properties"},
      {"binary_vertices.ply",
       ply(binary,
           "element vertex " + big + "\n" + xyz + "element face 2\n" + list) +
           square_binary,
       "PLY file ends early in element 'vertex': the header declares "
       "2147483647 rows of at least 12 bytes, more than the 74 bytes of data "
       "hold"},
      {"binary_faces.ply",
       ply(binary,
           "element vertex 4\n" + xyz + "element face " + big + "\n" + list) +
           square_binary,
       "PLY file ends early in element 'face': the header declares "
       "2147483647 rows of at least 13 bytes, more than the 74 bytes of data "
       "hold"},
      {"binary_extra.ply",
       ply(binary, "element vertex 4\n" + xyz + "element face 2\n" + list +
                       "element junk " + big + "\nproperty double a\n") +
           square_binary,
       "PLY file ends early in element 'junk': the header declares "
       "2147483647 rows of at least 8 bytes, more than the 74 bytes of data "
       "hold"},
      {"binary_extra_no_properties.ply", issue_file,
       "PLY element 'junk' declares 2147483647 rows but has no properties"},
      {"binary_list_count.ply",
       ply(binary, "element vertex 4\n" + xyz + "element face 2\n" + list +
                       "element junk 1\nproperty list uint uchar a\n") +
           square_binary + std::string("\xff\xff\xff\xff", 4),
       "PLY file ends early in element 'junk' (0 of 1 read)"},
      {"binary_count_above_int.ply",
       ply(binary, "element vertex 2147483648\n" + xyz) + square_binary,
       "malformed PLY element line 'element vertex 214748364...' (line 3)"},
      {"vertices.off", "OFF\n" + big + " 2 0\n0 0 0\n",
       "OFF file ends early: the header declares 2147483647 vertices of at "
       "least 6 bytes, more than the 6 bytes of data hold"},
      {"faces.off", "OFF\n4 " + big + " 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n",
       "OFF file ends early: the header declares 2147483647 faces of at least "
       "8 bytes, more than the 24 bytes of data hold"},
      {"coff_vertices.off", "COFF 1000 1 0\n0 0 0 1 1 1\n",
       "OFF file ends early: the header declares 1000 vertices of at least 6 "
       "bytes, more than the 12 bytes of data hold"},
      {"counts_above_int.off", "OFF\n99999999999 2 0\n",
       "malformed OFF counts line (expected 'vertices faces edges') (line 2)"},
  };
  for (const Case& c : cases) {
    const std::string path = Write(dir + "/" + c.name, c.content);
    SCOPED_TRACE(path);
    CountingStopToken polls;
    EXPECT_EQ(ErrorOf([&path, &polls] { ReadMesh(path, polls.token()); }),
              path + ": " + c.expected);
    // The polls of reading the file (at the start and after its only
    // chunk; once more when the rest is read after a header that passed):
    // no line or row loop reached its first poll (every 4096 lines or
    // values).
    EXPECT_LE(polls.polls(), 3);
  }
  // A lying header on a 1 GiB (sparse) file: refused from the first MiB,
  // the rest never read (polls at the start, after the first MiB and after
  // one more byte; 1024 more for the whole file).
  const std::string header = ply(
      binary, "element vertex " + big + "\n" + xyz + "element face 2\n" + list);
  const std::string sparse = Write(dir + "/sparse_lying.ply", header);
  ASSERT_EQ(truncate(sparse.c_str(), kMaxMeshFileBytes), 0);
  CountingStopToken polls;
  EXPECT_EQ(
      ErrorOf([&sparse, &polls] { ReadMesh(sparse, polls.token()); }),
      sparse +
          ": PLY file ends early in element 'vertex': the header "
          "declares 2147483647 rows of at least 12 bytes, more than the " +
          std::to_string(kMaxMeshFileBytes - header.size()) +
          " bytes of data hold");
  EXPECT_EQ(polls.polls(), 3);
  EXPECT_EQ(issue_file.size(), 321u);
  EXPECT_EQ(std::size(cases), 14u);
}

// 20 MB of blank lines (and of '#' comments): read line by line, never
// materialised (the readers used to hold every line as a string: 1.1 GB);
// in a PLY or OFF header, refused after its first MiB.
TEST(InputFileTest, BlankLinesCostNoMemoryPerLine) {
  const std::string dir = testing::TempDir();
  const std::string blank(20 << 20, '\n');
  const std::string square_obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  struct Case {
    std::string name, content, expected;  // expected: "" = read
  };
  const Case cases[] = {
      {"blank.obj", blank, "mesh has no vertices"},
      {"blank_square.obj", blank + square_obj + blank, ""},
      {"comments.obj", std::string(10 << 20, '#') + "\n" + blank + square_obj,
       ""},
      {"blank_header.ply", "ply\n" + blank,
       "PLY header longer than 1048576 bytes (no end_header before line "
       "1048574)"},
      {"blank_data.ply",
       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty "
       "float y\nproperty float z\nelement face 2\nproperty list uchar int "
       "vertex_indices\nend_header\n" +
           blank + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n" + blank,
       ""},
      {"blank.off", "OFF\n" + blank,
       "OFF header longer than 1048576 bytes (no vertex and face counts "
       "before line 1048574)"},
      {"blank_counts.off",
       "OFF\n\n\n4 2 0\n" + blank +
           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 "
           "3\n",
       ""},
      {"blank_mask.txt", blank + "3\n" + blank, ""},
  };
  for (const Case& c : cases) {
    const std::string path = Write(dir + "/" + c.name, c.content);
    SCOPED_TRACE(path);
    const std::string result = InChild([&path] {
      const long before = PeakResidentBytes();
      const std::string error = ErrorOf([&path] {
        if (path.find("mask") != std::string::npos) {
          if (ReadMask(path, 4) != std::vector<int>{3}) throw InputError("?");
        } else {
          ReadMesh(path);
        }
      });
      const long grown = PeakResidentBytes() - before;
      // The file's bytes (about 40 MB) and little more.
      return grown < (100 << 20) ? error
                                 : error + " (peak memory grew by " +
                                       std::to_string(grown >> 20) + " MB)";
    });
    EXPECT_EQ(result,
              c.expected.empty() ? "accepted" : path + ": " + c.expected);
  }
}

// A mesh file of `rows` vertices in each format, for the stop tests.
std::string LongFile(const std::string& dir, const std::string& format,
                     int rows) {
  std::string body;
  const auto vertex_lines = [&](const std::string& prefix) {
    for (int i = 0; i < rows; ++i)
      body += prefix + "0 0 " + std::to_string(i) + "\n";
  };
  if (format == "ply_ascii" || format == "ply_binary") {
    const bool binary = format == "ply_binary";
    body = "ply\nformat " +
           std::string(binary ? "binary_little_endian" : "ascii") +
           " 1.0\nelement vertex " + std::to_string(rows) +
           "\nproperty double x\nproperty double y\nproperty double z\n"
           "element face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n";
    if (binary) {
      for (int i = 0; i < rows; ++i) {
        const double v[3] = {0, 0, static_cast<double>(i)};
        body.append(reinterpret_cast<const char*>(v), sizeof(v));
      }
      const char face[13] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0};
      body.append(face, 13);
    } else {
      vertex_lines("");
      body += "3 0 1 2\n";
    }
    return Write(dir + "/" + format + ".ply", body);
  }
  if (format == "obj") {
    vertex_lines("v ");
    return Write(dir + "/long.obj", body + "f 1 2 3\n");
  }
  if (format == "off") {
    body = "OFF\n" + std::to_string(rows) + " 1 0\n";
    vertex_lines("");
    return Write(dir + "/long.off", body + "3 0 1 2\n");
  }
  for (int i = 0; i < rows; ++i) body += std::to_string(i % 10) + "\n";
  return Write(dir + "/long_mask.txt", body);
}

// A token that says stop ends every reader at the poll it is seen: in the
// chunks of the file (poll 2) or in its lines or rows (poll 20), with
// ReadStopped naming the file; the same files read whole without a stop.
TEST(InputFileTest, AStopTokenEndsEveryReaderAtItsPoll) {
  const std::string dir = testing::TempDir();
  const int kRows = 200000;  // 2 MB and more: several chunks
  int stopped = 0;
  for (const std::string format :
       {"ply_ascii", "ply_binary", "obj", "off", "mask"}) {
    const std::string path = LongFile(dir, format, kRows);
    SCOPED_TRACE(path);
    const auto read = [&path, &format](const StopToken& stop) {
      if (format == "mask") {
        ReadMask(path, 10, stop);
      } else {
        ReadMesh(path, stop);
      }
    };
    {
      // Without a stop: the reader gets through the rows (the files are not
      // valid meshes: isolated vertices) and polls about every 4096 rows.
      CountingStopToken polls;
      const std::string error =
          ErrorOf([&read, &polls] { read(polls.token()); });
      EXPECT_EQ(error.find("reading stopped"), std::string::npos) << error;
      EXPECT_GT(polls.polls(), kRows / 4096) << error;
    }
    for (long stop_at : {2L, 20L}) {
      CountingStopToken polls(stop_at);
      try {
        read(polls.token());
        ADD_FAILURE() << "not stopped";
      } catch (const ReadStopped& e) {
        EXPECT_EQ(e.path(), path);
        EXPECT_EQ(std::string(e.what()),
                  path + ": reading stopped (stop requested)");
        ++stopped;
      }
      EXPECT_EQ(polls.polls(), stop_at);
    }
  }
  EXPECT_EQ(stopped, 10);
}

// A token that says stop from the start ends a read before its first
// chunk: ReadInputFile, ReadMask, ReadMesh and ReadFrameSequence throw
// ReadStopped naming the file; without the token they read it.
TEST(InputFileTest, AStoppedTokenEndsEveryReadBeforeItsFirstChunk) {
  const std::string dir = testing::TempDir();
  const std::string mask = Write(dir + "/stopped_mask.txt", "0\n");
  const std::string mesh = Write(
      dir + "/stopped.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const StopToken stopped([] { return true; });
  const auto path_of = [](const std::function<void()>& read) {
    try {
      read();
    } catch (const ReadStopped& e) {
      return e.path();
    }
    return std::string("not stopped");
  };
  EXPECT_EQ(path_of([&] { ReadInputFile(mask, "mask", 1 << 20, stopped); }),
            mask);
  EXPECT_EQ(path_of([&] { ReadMask(mask, 1, stopped); }), mask);
  EXPECT_EQ(path_of([&] { ReadMesh(mesh, stopped); }), mesh);
  EXPECT_EQ(path_of([&] { ReadFrameSequence(mesh + "," + mesh, stopped); }),
            mesh);
  EXPECT_EQ(ReadMask(mask, 1), std::vector<int>{0});
  EXPECT_EQ(ReadFrameSequence(mesh + "," + mesh).frames.size(), 2u);
}

}  // namespace
}  // namespace shellspace
