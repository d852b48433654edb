// The libFuzzer harness of the readers: the input bytes are written to a
// file and given to the real reader (io/mesh_io.h), which must either return
// a validated mesh or throw InputError. Anything else (another exception, a
// crash, a sanitizer report, a leak, a returned mesh that breaks the
// invariants ReadMesh promises, a read whose work is not proportional to
// the input's size) is a finding.
#ifndef SHELLSPACE_FUZZ_FUZZ_READER_H_
#define SHELLSPACE_FUZZ_FUZZ_READER_H_

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/input_file.h"
#include "shellspace/io/mesh_io.h"

namespace shellspace::fuzz {

// A per-process scratch file with extension `ext` (the reader dispatches on
// it), in $TMPDIR or /tmp. The process id is padded to a fixed width: the
// path's length (and so the coverage of the error messages built from it)
// is the same in every run, which keeps -seed=1 runs reproducible.
inline const std::string& ScratchPath(const char* ext) {
  static const std::string path = [ext] {
    const char* dir = std::getenv("TMPDIR");
    char name[64];
    std::snprintf(name, sizeof(name), "/shellspace_fuzz_%010d.%s",
                  static_cast<int>(getpid()), ext);
    return std::string(dir && *dir ? dir : "/tmp") + name;
  }();
  return path;
}

inline void WriteScratch(const std::string& path, const uint8_t* data,
                         size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data),
            static_cast<std::streamsize>(size));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

[[noreturn]] inline void Finding(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::abort();
}

// A stop token for one read of `size` bytes (io/input_file.h) that never
// says stop but counts the times it is asked: the readers ask once per
// chunk and once per 4096 lines or binary values, and a file of `size`
// bytes has at most size + 1 lines and size values, so more than 4 + 2
// (size / 4096 + 1) polls means a loop over rows the file does not hold (a
// header's counts trusted) -- a finding, reported at once instead of after
// minutes. Must outlive the read.
class ProportionalWork {
 public:
  explicit ProportionalWork(size_t size)
      : bound_(4 + 2 * (static_cast<long>(size) / 4096 + 1)),
        token_([this] {
          if (++polls_ > bound_) {
            Finding("read work not proportional to the file size (" +
                    std::to_string(polls_) +
                    " stop polls for a file of at most " +
                    std::to_string((bound_ - 4) / 2 * 4096) + " bytes)");
          }
          return false;
        }) {}
  ProportionalWork(const ProportionalWork&) = delete;
  ProportionalWork& operator=(const ProportionalWork&) = delete;
  const StopToken& token() const { return token_; }

 private:
  long bound_;
  mutable long polls_ = 0;  // counted by the token of a const instance too
  StopToken token_;
};

// The invariants of a mesh ReadMesh returned (ValidateMeshStructure).
inline void CheckReadMesh(const Mesh& mesh) {
  if (mesh.num_vertices() <= 0 || mesh.num_faces() <= 0) {
    Finding("empty mesh returned");
  }
  std::vector<int> uses(mesh.num_vertices(), 0);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.faces(f, c);
      if (v < 0 || v >= mesh.num_vertices()) Finding("index out of range");
      ++uses[v];
    }
  }
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (uses[v] == 0) Finding("isolated vertex returned");
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(mesh.positions(v, c))) Finding("non-finite returned");
    }
  }
}

// Reads `data` as a mesh file with extension `ext`, then validates it as a
// shell (ValidateShell: degenerate triangles).
inline int FuzzMesh(const uint8_t* data, size_t size, const char* ext) {
  const std::string& path = ScratchPath(ext);
  WriteScratch(path, data, size);
  const ProportionalWork work(size);
  try {
    const Mesh mesh = ReadMesh(path, work.token());
    CheckReadMesh(mesh);
    ValidateShell(mesh, path);
  } catch (const InputError& error) {
    const std::string message = error.what();
    if (message.find('\n') != std::string::npos) {
      Finding("multi-line error: " + message);
    }
    for (char c : message) {
      if (static_cast<unsigned char>(c) < 0x20 ||
          static_cast<unsigned char>(c) >= 0x7f) {
        Finding("raw byte in error: " + message);
      }
    }
  } catch (const std::exception& error) {
    Finding(std::string("exception other than InputError: ") + error.what());
  } catch (...) {
    Finding("non-standard exception");
  }
  return 0;
}

// FuzzMesh of a PLY file: `data` as it is if it starts with "ply", else
// the fixed header of a 4-vertex, 2-face mesh in `format` ("ascii",
// "binary_little_endian") with `coordinate` ("double", "float") vertex
// coordinates and uchar/int face lists, followed by `data`, so that random
// bytes exercise the data section.
inline int FuzzPlyData(const uint8_t* data, size_t size, const char* format,
                       const char* coordinate) {
  if (size >= 3 && std::memcmp(data, "ply", 3) == 0) {
    return FuzzMesh(data, size, "ply");
  }
  const std::string property = std::string("property ") + coordinate;
  std::string bytes = std::string("ply\nformat ") + format +
                      " 1.0\nelement vertex 4\n" + property + " x\n" +
                      property + " y\n" + property +
                      " z\nelement face 2\n"
                      "property list uchar int vertex_indices\nend_header\n";
  bytes.append(reinterpret_cast<const char*>(data), size);
  return FuzzMesh(reinterpret_cast<const uint8_t*>(bytes.data()),
                  bytes.size(), "ply");
}

}  // namespace shellspace::fuzz

#endif  // SHELLSPACE_FUZZ_FUZZ_READER_H_
