// libFuzzer target: binary PLY through ReadMesh (fuzz/fuzz_reader.h). An
// input that does not start with "ply" gets a fixed binary little-endian
// header of a 4-vertex, 2-face mesh (float coordinates, uchar/int lists), so
// that random bytes exercise the binary data section.
#include "fuzz/fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return shellspace::fuzz::FuzzPlyData(data, size, "binary_little_endian",
                                       "float");
}
