// libFuzzer target: OFF through ReadMesh (fuzz/fuzz_reader.h).
#include "fuzz/fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return shellspace::fuzz::FuzzMesh(data, size, "off");
}
