// The command line on inputs that are not regular files or lie in their
// headers: a FIFO (which used to block open() forever, deaf to SIGTERM),
// /dev/zero as a mesh, a mask or a --flagfile, a sparse 20 GB mesh, a PLY
// declaring 2^31 - 1 rows: each one line and exit 1, at once, beside the
// shared square as the other input. Every run is a child with a timeout
// (testing::RunCliWithTimeout), so a regression fails instead of hanging.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::CliRun;
using testing::RunCliWithTimeout;

std::string Write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(ReaderCliTest, SpecialFilesAndLyingHeadersAreOneLineAtOnce) {
  const std::string dir = testing::TempDir();
  const std::string square = testing::Square4();
  const std::string fifo = dir + "/fifo.ply";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string fifo_text = dir + "/fifo.txt";
  ASSERT_EQ(mkfifo(fifo_text.c_str(), 0600), 0);
  std::filesystem::create_symlink(fifo, dir + "/link.obj");
  std::filesystem::create_symlink("/dev/zero", dir + "/zero.ply");
  const std::string sparse = dir + "/sparse.off";
  const int fd = open(sparse.c_str(), O_CREAT | O_WRONLY, 0600);
  ASSERT_EQ(ftruncate(fd, 20000000000LL), 0);
  close(fd);
  const std::string lying = Write(
      dir + "/lying.ply",
      "ply\nformat binary_little_endian 1.0\nelement vertex 2147483647\n"
      "property double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
  const std::string flags =
      Write(dir + "/flags.txt", "# a flag file\n--reference=" + square +
                                    "\n--deformed=" + square + "\n");
  const std::string nested =
      Write(dir + "/nested.txt", "--flagfile=/dev/urandom\n");
  const std::string energy = "energy --deformed " + square + " --reference ";
  const std::string deform = "deform --reference " + square + " --targets " +
                             square + " --output " + dir + "/out.ply --mask ";
  struct Case {
    std::string args, line;  // line: the whole stderr
    int code;
  };
  const Case cases[] = {
      {energy + fifo,
       "shellspace energy: error: " + fifo +
           ": is a FIFO (named pipe), not a mesh file\n",
       1},
      {energy + dir + "/link.obj",
       "shellspace energy: error: " + dir +
           "/link.obj: is a FIFO (named pipe), not a mesh file\n",
       1},
      {energy + dir + "/zero.ply",
       "shellspace energy: error: " + dir +
           "/zero.ply: is a character device, not a mesh file\n",
       1},
      {energy + sparse,
       "shellspace energy: error: " + sparse +
           ": 20000000000 bytes, larger than the largest mesh file read "
           "(1 GiB)\n",
       1},
      {energy + lying,
       "shellspace energy: error: " + lying +
           ": PLY file ends early in element 'vertex': the header declares "
           "2147483647 rows of at least 24 bytes, more than the 0 bytes of "
           "data hold\n",
       1},
      {deform + "/dev/zero",
       "shellspace deform: error: /dev/zero: is a character device, not a "
       "mask file\n",
       1},
      {deform + fifo_text,
       "shellspace deform: error: " + fifo_text +
           ": is a FIFO (named pipe), not a mask file\n",
       1},
      {"energy --flagfile=/dev/zero",
       "shellspace energy: error: /dev/zero: is a character device, not a "
       "flag file\n",
       1},
      {"energy --flagfile " + fifo_text,
       "shellspace energy: error: " + fifo_text +
           ": is a FIFO (named pipe), not a flag file\n",
       1},
      {"energy -flagfile=" + flags + "," + nested,
       "shellspace energy: error: /dev/urandom: is a character device, not a "
       "flag file\n",
       1},
      {"energy --flagfile=" + dir + "/missing.txt",
       "shellspace energy: error: cannot open flag file " + dir +
           "/missing.txt (No such file or directory)\n",
       1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const CliRun run = RunCliWithTimeout(c.args);
    EXPECT_EQ(run.code, c.code);
    EXPECT_EQ(run.err, c.line);
  }
  // A regular flag file passes the check and reaches gflags (whatever the
  // verb then says of its flags).
  const CliRun ok = RunCliWithTimeout("energy --flagfile=" + flags);
  EXPECT_EQ(ok.err.find("flag file"), std::string::npos) << ok.err;
  EXPECT_NE(ok.code, -1) << ok.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.ply"));
}

}  // namespace
}  // namespace shellspace
