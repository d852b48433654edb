// libFuzzer target: ASCII PLY through ReadMesh (fuzz/fuzz_reader.h). An
// input that does not start with "ply" gets a fixed ASCII header of a
// 4-vertex, 2-face mesh, so that random bytes exercise the data section.
#include "fuzz/fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return shellspace::fuzz::FuzzPlyData(data, size, "ascii", "double");
}
