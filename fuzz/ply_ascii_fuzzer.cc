// libFuzzer target: ASCII PLY through ReadMesh (fuzz/fuzz_reader.h). An
// input that does not start with "ply" gets a fixed ASCII header of a
// 4-vertex, 2-face mesh, so that random bytes exercise the data section.
#include <cstring>
#include <string>

#include "shellspace/fuzz/fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size >= 3 && std::memcmp(data, "ply", 3) == 0) {
    return shellspace::fuzz::FuzzMesh(data, size, "ply");
  }
  std::string bytes =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\n"
      "property double y\nproperty double z\nelement face 2\n"
      "property list uchar int vertex_indices\nend_header\n";
  bytes.append(reinterpret_cast<const char*>(data), size);
  return shellspace::fuzz::FuzzMesh(
      reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "ply");
}
