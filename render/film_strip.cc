#include "shellspace/render/film_strip.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "shellspace/render/camera.h"
#include "shellspace/render/rasterizer.h"

namespace shellspace {
namespace {

// Largest frame side accepted, to turn absurd sizes into a clear error rather
// than an allocation failure.
constexpr int kMaxFrameSide = 8192;

std::uint8_t ToByte(double value) {
  return static_cast<std::uint8_t>(
      std::lround(255 * std::clamp(value, 0.0, 1.0)));
}

// Box-filters the supersampled buffer into the cell at (left, top) of image.
void CopyDownsampled(const FrameBuffer& buffer, int factor, int left, int top,
                     RgbImage* image) {
  const int width = buffer.width / factor;
  const int height = buffer.height / factor;
  const double weight = 1.0 / (factor * factor);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int j = 0; j < factor; ++j) {
        for (int i = 0; i < factor; ++i) {
          sum += buffer.color[static_cast<size_t>(y * factor + j) *
                                  buffer.width + x * factor + i];
        }
      }
      std::uint8_t* pixel = image->at(left + x, top + y);
      for (int c = 0; c < 3; ++c) pixel[c] = ToByte(weight * sum[c]);
    }
  }
}

}  // namespace

void ValidateRenderOptions(const RenderOptions& options) {
  if (options.width <= 0 || options.height <= 0) {
    throw InputError("frame size must be positive, got " +
                     std::to_string(options.width) + "x" +
                     std::to_string(options.height));
  }
  if (options.width > kMaxFrameSide || options.height > kMaxFrameSide) {
    throw InputError("frame size at most " + std::to_string(kMaxFrameSide) +
                     " pixels per side, got " + std::to_string(options.width) +
                     "x" + std::to_string(options.height));
  }
  if (options.supersample < 1 || options.supersample > 8) {
    throw InputError("supersample must be in [1, 8]");
  }
  if (options.max_per_row < 1) {
    throw InputError("frames per row must be positive");
  }
  if (!(options.margin >= 0 && options.margin < 0.5)) {
    throw InputError("frame margin must be in [0, 0.5)");
  }
  if (!std::isfinite(options.view.azimuth) ||
      !(options.view.elevation >= -90 && options.view.elevation <= 90)) {
    throw InputError("view needs a finite azimuth and elevation in [-90, 90]");
  }
}

RgbImage RenderFilmStrip(const std::vector<Positions>& frames,
                         const Faces& faces, const RenderOptions& options) {
  ValidateRenderOptions(options);
  if (frames.empty()) throw InputError("no frames to render");
  for (size_t k = 1; k < frames.size(); ++k) {
    if (frames[k].rows() != frames[0].rows()) {
      throw InputError("frame " + std::to_string(k) + " has " +
                       std::to_string(frames[k].rows()) +
                       " vertices, frame 0 has " +
                       std::to_string(frames[0].rows()));
    }
  }
  const int factor = options.supersample;
  const Camera camera =
      FrameVertices(frames, options.view, options.width * factor,
                    options.height * factor, options.margin);

  const int count = static_cast<int>(frames.size());
  const int columns = std::min(count, options.max_per_row);
  const int rows = (count + columns - 1) / columns;
  RgbImage image(columns * options.width, rows * options.height);
  const Eigen::Vector3d& background = options.lighting.background;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = ToByte(background[i % 3]);
  }
  for (int k = 0; k < count; ++k) {
    FrameBuffer buffer(camera.width, camera.height, background);
    RasterizeMesh(frames[k], faces, camera, options.shading, options.lighting,
                  &buffer);
    CopyDownsampled(buffer, factor, (k % columns) * options.width,
                    (k / columns) * options.height, &image);
  }
  return image;
}

void WriteFilmStrip(const std::vector<Positions>& frames, const Faces& faces,
                    const RenderOptions& options, const std::string& path) {
  WritePng(RenderFilmStrip(frames, faces, options), path);
}

void WriteFilmStrip(const std::vector<Mesh>& meshes,
                    const RenderOptions& options, const std::string& path) {
  if (meshes.empty()) throw InputError("no frames to render");
  std::vector<Positions> frames;
  frames.reserve(meshes.size());
  for (size_t k = 0; k < meshes.size(); ++k) {
    if (k > 0 && (meshes[k].faces.rows() != meshes[0].faces.rows() ||
                  meshes[k].faces != meshes[0].faces)) {
      throw InputError("mesh " + std::to_string(k) +
                       " has other faces than mesh 0");
    }
    frames.push_back(meshes[k].positions);
  }
  WriteFilmStrip(frames, meshes[0].faces, options, path);
}

}  // namespace shellspace
