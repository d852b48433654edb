#include "shellspace/render/film_strip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/geometry/named_values.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/render/bitmap_font.h"
#include "shellspace/render/camera.h"
#include "shellspace/render/color_ramp.h"
#include "shellspace/render/rasterizer.h"

namespace shellspace {
namespace {

// Largest frame side and image width accepted, to turn absurd sizes into a
// clear error rather than an allocation failure.
constexpr int kMaxFrameSide = 8192;
constexpr int kMaxImageWidth = 65536;

// Ink of the labels and the legend.
constexpr std::array<std::uint8_t, 3> kTextColor = {60, 60, 60};

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

// The largest vertex distance from the first frame over all frames.
double MaxDisplacement(const std::vector<Positions>& frames) {
  double largest = 0;
  for (const Positions& p : frames) {
    largest = std::max(
        largest, (p - frames[0]).rowwise().norm().maxCoeff());
  }
  return largest;
}

std::vector<Eigen::Vector3d> DisplacementColors(const Positions& frame,
                                                const Positions& first,
                                                double largest) {
  std::vector<Eigen::Vector3d> colors(frame.rows());
  for (int i = 0; i < frame.rows(); ++i) {
    const double d = (frame.row(i) - first.row(i)).norm();
    colors[i] = RampColor(largest > 0 ? d / largest : 0.0);
  }
  return colors;
}

// "%.3g" of a positive length for the legend.
std::string Short(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

// The colour bar: "|x_k - x_0|  0 [ramp] D", centred in the legend strip at
// row `top`; the title is left out when the line does not fit.
void DrawLegend(double largest, const FilmStripLayout& layout, int top,
                RgbImage* image) {
  const int s = layout.text_scale;
  const int gap = 3 * s;
  const std::string title = "|x_k - x_0|";
  const std::string low = "0";
  const std::string high = Short(largest);
  const int numbers = TextWidth(low, s) + TextWidth(high, s) + 2 * gap;
  const int title_width = TextWidth(title, s) + 2 * gap;
  const int available = layout.width - 2 * gap;
  const bool with_title = available - numbers - title_width >= 16 * s;
  const int bar = std::min(
      160 * s, available - numbers - (with_title ? title_width : 0));
  if (bar < 1) return;
  const int total = numbers + bar + (with_title ? title_width : 0);
  int x = std::max(0, (layout.width - total) / 2);
  const int text_top = top + 3 * s;
  if (with_title) {
    DrawText(title, x, text_top, s, kTextColor, image);
    x += TextWidth(title, s) + 2 * gap;
  }
  DrawText(low, x, text_top, s, kTextColor, image);
  x += TextWidth(low, s) + gap;
  const int bar_height = (kGlyphHeight - 1) * s;  // the height of a digit
  for (int i = 0; i < bar && x + i < image->width; ++i) {
    const Eigen::Vector3d c = RampColor(bar > 1 ? i / (bar - 1.0) : 1.0);
    for (int j = 0; j < bar_height; ++j) {
      std::uint8_t* pixel = image->at(x + i, text_top + j);
      for (int k = 0; k < 3; ++k) pixel[k] = ToByte(c[k]);
    }
  }
  x += bar + gap;
  DrawText(high, x, text_top, s, kTextColor, image);
}

constexpr NamedValue<SurfaceColor> kSurfaceColorNames[] = {
    {SurfaceColor::kPlain, "plain"},
    {SurfaceColor::kDisplacement, "displacement"}};

}  // namespace

SurfaceColor ParseSurfaceColor(const std::string& text) {
  return ParseNamedValue(kSurfaceColorNames, AsciiLowercase(text),
                         "the colour");
}

std::string SurfaceColorName(SurfaceColor color) {
  return NameOf(kSurfaceColorNames, color);
}

void ValidateRenderOptions(const RenderOptions& options) {
  if (options.width < 0 || options.height < 0) {
    throw InputError("image width and frame height must be positive (or 0 "
                     "for the default), got " +
                     std::to_string(options.width) + " and " +
                     std::to_string(options.height));
  }
  if (options.width > kMaxImageWidth) {
    throw InputError("image width at most " + std::to_string(kMaxImageWidth) +
                     " pixels, got " + std::to_string(options.width));
  }
  if (options.height > kMaxFrameSide) {
    throw InputError("frame height at most " + std::to_string(kMaxFrameSide) +
                     " pixels, got " + std::to_string(options.height));
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

FilmStripLayout LayoutFilmStrip(int count, const RenderOptions& options) {
  ValidateRenderOptions(options);
  if (count < 1) throw InputError("no frames to render");
  FilmStripLayout layout;
  layout.columns = std::min(count, options.max_per_row);
  layout.rows = (count + layout.columns - 1) / layout.columns;
  if (options.width == 0) {
    layout.frame_width = kDefaultFrameWidth;
    layout.width = layout.columns * kDefaultFrameWidth;
  } else {
    if (options.width < layout.columns) {
      throw InputError("image width " + std::to_string(options.width) +
                       " is less than one pixel per column (" +
                       std::to_string(layout.columns) + " columns)");
    }
    layout.frame_width = options.width / layout.columns;
    layout.width = options.width;
  }
  if (layout.frame_width > kMaxFrameSide) {
    throw InputError("frame width at most " + std::to_string(kMaxFrameSide) +
                     " pixels, got " + std::to_string(layout.frame_width) +
                     " (image width / columns)");
  }
  layout.left = (layout.width - layout.columns * layout.frame_width) / 2;
  layout.frame_height =
      options.height > 0 ? options.height : layout.frame_width;
  layout.text_scale = std::clamp((layout.frame_width + 80) / 160, 1, 4);
  layout.label_height = options.labels ? 12 * layout.text_scale : 0;
  layout.legend_height =
      options.color == SurfaceColor::kDisplacement ? 14 * layout.text_scale
                                                   : 0;
  const long long height =
      static_cast<long long>(layout.rows) *
          (layout.frame_height + layout.label_height) +
      layout.legend_height;
  if (height > std::numeric_limits<int>::max()) {
    throw InputError("a film strip of " + std::to_string(count) +
                     " frames would be " + std::to_string(height) +
                     " pixels high, more than an image holds");
  }
  layout.height = static_cast<int>(height);
  return layout;
}

double FilmStripBytes(int count, const RenderOptions& options) {
  const FilmStripLayout layout = LayoutFilmStrip(count, options);
  const double samples = static_cast<double>(options.supersample) *
                         options.supersample;
  return 6.0 * layout.width * static_cast<double>(layout.height) +
         32.0 * samples * layout.frame_width *
             static_cast<double>(layout.frame_height);
}

void CheckFilmStripMemory(int frames, const RenderOptions& options,
                          const std::string& what) {
  const FilmStripLayout layout = LayoutFilmStrip(frames, options);
  CheckMemory(FilmStripBytes(frames, options),
              what + ": a film strip of " + std::to_string(frames) +
                  " frame(s), " + std::to_string(layout.width) + " x " +
                  std::to_string(layout.height) + " pixels (frames " +
                  std::to_string(layout.frame_width) + " x " +
                  std::to_string(layout.frame_height) + ")",
              kFilmStripModel);
}

std::string FrameLabel(int k, int count) {
  const double t = count > 1 ? static_cast<double>(k) / (count - 1) : 0.0;
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", t);
  std::string time = text;
  while (time.back() == '0') time.pop_back();
  if (time.back() == '.') time.pop_back();
  return std::to_string(k) + "  t=" + time;
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
  const int count = static_cast<int>(frames.size());
  const FilmStripLayout layout = LayoutFilmStrip(count, options);
  const int factor = options.supersample;
  const Camera camera = FrameVertices(
      frames, options.view, layout.frame_width * factor,
      layout.frame_height * factor, options.margin, options.up, &faces);

  RgbImage image(layout.width, layout.height);
  const Eigen::Vector3d& background = options.lighting.background;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = ToByte(background[i % 3]);
  }
  const bool by_displacement = options.color == SurfaceColor::kDisplacement;
  const double largest = by_displacement ? MaxDisplacement(frames) : 0.0;
  const int s = layout.text_scale;
  for (int k = 0; k < count; ++k) {
    FrameBuffer buffer(camera.width, camera.height, background);
    std::vector<Eigen::Vector3d> colors;
    if (by_displacement) {
      colors = DisplacementColors(frames[k], frames[0], largest);
    }
    RasterizeMesh(frames[k], faces, camera, options.shading, options.lighting,
                  &buffer, by_displacement ? &colors : nullptr);
    const int left = layout.FrameLeft(k);
    const int top = layout.FrameTop(k);
    CopyDownsampled(buffer, factor, left, top, &image);
    if (options.labels) {
      std::string label = FrameLabel(k, count);
      if (TextWidth(label, s) > layout.frame_width) label = std::to_string(k);
      if (TextWidth(label, s) <= layout.frame_width) {
        DrawText(label, left + (layout.frame_width - TextWidth(label, s)) / 2,
                 top + layout.frame_height + 2 * s, s, kTextColor, &image);
      }
    }
  }
  if (by_displacement) {
    DrawLegend(largest, layout, layout.height - layout.legend_height, &image);
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
