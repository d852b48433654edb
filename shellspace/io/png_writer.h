// Writing 8-bit RGB images as PNG (libpng).
#ifndef SHELLSPACE_IO_PNG_WRITER_H_
#define SHELLSPACE_IO_PNG_WRITER_H_

#include <cstdint>
#include <string>
#include <vector>

namespace shellspace {

// An 8-bit RGB image, row-major, top row first: pixel (x, y) is at
// 3 * (y * width + x).
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;

  RgbImage() = default;
  RgbImage(int w, int h, std::uint8_t fill = 255)
      : width(w), height(h), pixels(3 * static_cast<size_t>(w) * h, fill) {}
  std::uint8_t* at(int x, int y) {
    return pixels.data() + 3 * (static_cast<size_t>(y) * width + x);
  }
  const std::uint8_t* at(int x, int y) const {
    return pixels.data() + 3 * (static_cast<size_t>(y) * width + x);
  }
};

// The PNG file bytes of `image` (8-bit RGB). Throws InputError
// (geometry/mesh.h) for an empty image.
std::string EncodePng(const RgbImage& image);

// Writes `image` to `path` as PNG, atomically (io/atomic_file.h), so a
// failure leaves no partial file. Throws InputError if the file cannot be
// written.
void WritePng(const RgbImage& image, const std::string& path);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_PNG_WRITER_H_
