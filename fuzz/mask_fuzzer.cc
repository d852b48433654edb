// libFuzzer target: the vertex-mask reader (ReadMask, io/mesh_io.h) for a
// mesh of 100 vertices: returns sorted unique indices in [0, 100) or throws
// a one-line, printable InputError.
#include "fuzz/fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace shellspace;
  const std::string& path = fuzz::ScratchPath("txt");
  fuzz::WriteScratch(path, data, size);
  const fuzz::ProportionalWork work(size);
  try {
    const std::vector<int> mask = ReadMask(path, 100, work.token());
    for (size_t i = 0; i < mask.size(); ++i) {
      if (mask[i] < 0 || mask[i] >= 100) fuzz::Finding("mask index out of range");
      if (i > 0 && mask[i] <= mask[i - 1]) fuzz::Finding("mask not sorted unique");
    }
  } catch (const InputError& error) {
    for (char c : std::string(error.what())) {
      if (static_cast<unsigned char>(c) < 0x20 ||
          static_cast<unsigned char>(c) >= 0x7f) {
        fuzz::Finding(std::string("raw byte in error: ") + error.what());
      }
    }
  } catch (const std::exception& error) {
    fuzz::Finding(std::string("exception other than InputError: ") +
                  error.what());
  } catch (...) {
    fuzz::Finding("non-standard exception");
  }
  return 0;
}
