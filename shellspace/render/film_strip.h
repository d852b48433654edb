// Film strips: the frames of a shell sequence rendered side by side into one
// image by a fixed camera, each with a label (index and time) under it, and
// written as PNG.
#ifndef SHELLSPACE_RENDER_FILM_STRIP_H_
#define SHELLSPACE_RENDER_FILM_STRIP_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/render/shading.h"
#include "shellspace/render/up_axis.h"
#include "shellspace/render/view.h"

namespace shellspace {

// The surface colour of the frames. kPlain: the two-sided tint of Lighting
// (front_color outside, back_color inside). kDisplacement: each vertex i of
// frame k coloured by RampColor (color_ramp.h) of |x_k,i - x_0,i| / D, where
// D is the largest such distance over all vertices of all frames (D = 0: all
// vertices get the ramp's first colour), on both sides, times the shading;
// a colour bar under the strip shows the ramp from 0 to D (in the meshes'
// length unit).
enum class SurfaceColor { kPlain, kDisplacement };

// Parses "plain" or "displacement" (case-insensitive); throws InputError
// with a one-line message otherwise.
SurfaceColor ParseSurfaceColor(const std::string& text);

// "plain" or "displacement".
std::string SurfaceColorName(SurfaceColor color);

// Width of a column when RenderOptions::width is 0.
constexpr int kDefaultFrameWidth = 320;

// How a film strip is drawn. The defaults are those of `shellspace render`.
struct RenderOptions {
  // Width of the whole image in pixels; 0 (the default): kDefaultFrameWidth
  // per column. With C columns each frame is floor(width / C) pixels wide
  // (so width >= C), and the remainder width - C floor(width / C) < C stays
  // background, its left half (rounded down) left of the first column and
  // the rest right of the last: the image is exactly `width` wide. At most
  // 65536, and a frame at most 8192 pixels wide.
  int width = 0;
  // Height of each frame's picture in pixels, not counting its label strip;
  // 0 (the default): as high as the frame is wide (square frames). At most
  // 8192.
  int height = 0;
  ViewAngles view;  // front view by default (see view.h)
  // Which world axis points up on screen before the view angles apply
  // (up_axis.h; camera.h ViewFrame); kAuto: AutoUpAxis of the first frame
  // and the faces (an open surface stands on its boundary).
  UpAxis up = UpAxis::kAuto;
  Shading shading = Shading::kGouraud;
  SurfaceColor color = SurfaceColor::kPlain;
  // A label strip under each frame with "k  t=T": the frame index k from 0
  // and its time T = k / (n - 1) of n frames (0 for a single frame; up to
  // three decimals, trailing zeros dropped), centred; just "k" when that
  // does not fit the frame's width, nothing when "k" does not fit either.
  bool labels = true;
  // Each pixel averages supersample x supersample samples (anti-aliasing);
  // 1 samples each pixel once at its centre. In [1, 8].
  int supersample = 2;
  // Frames per row; longer sequences wrap into further rows. > 0.
  int max_per_row = 6;
  // Empty border of each frame, as a fraction of its width / height, in
  // [0, 0.5).
  double margin = 0.05;
  Lighting lighting;
};

// Throws InputError with a one-line message if an option is out of range.
void ValidateRenderOptions(const RenderOptions& options);

// Where the parts of a film strip of `count` frames lie, in pixels. With
// columns = min(count, max_per_row) and rows = ceil(count / columns), frame
// k's picture is frame_width x frame_height pixels at (FrameLeft(k),
// FrameTop(k)), its label strip the label_height rows right under it (0
// without labels), the colour bar strip (legend_height rows, 0 without a
// colour map) spans the bottom of the image, and
//   width  = RenderOptions::width, or columns * kDefaultFrameWidth for 0
//   height = rows * (frame_height + label_height) + legend_height.
// Labels and legend use the bitmap font (bitmap_font.h) at text_scale =
// clamp(round(frame_width / 160), 1, 4); label_height = 12 text_scale and
// legend_height = 14 text_scale.
struct FilmStripLayout {
  int columns = 0;
  int rows = 0;
  int frame_width = 0;
  int frame_height = 0;
  int label_height = 0;
  int legend_height = 0;
  int left = 0;  // background columns left of the first column
  int text_scale = 1;
  int width = 0;
  int height = 0;

  int FrameLeft(int k) const { return left + (k % columns) * frame_width; }
  int FrameTop(int k) const {
    return (k / columns) * (frame_height + label_height);
  }
};

// The layout of `count` >= 1 frames; throws InputError as
// ValidateRenderOptions does, or if width < columns.
FilmStripLayout LayoutFilmStrip(int count, const RenderOptions& options);

// What rendering and encoding a film strip of `count` frames holds in
// memory at its peak, in bytes: the image (3 B per pixel) and its PNG
// encoding (at most about as large again: 6 B per pixel together), and the
// supersampled buffer of one frame (a colour of 3 doubles and a depth per
// sample: 32 B x supersample^2 per frame pixel),
//   6 B x width x height + 32 B x supersample^2 x frame_width x frame_height
// of LayoutFilmStrip(count, options); the meshes are not counted. Computed
// in doubles (no overflow); throws as LayoutFilmStrip. Measured peak
// resident memory minus the process's own 29 MB (/usr/bin/time, `shellspace
// render` of 6 frames of the 323-vertex example plate): 0.59 GB at 12288 x
// 2048 (estimate 0.69 GB), 2.38 GB at 24576 x 4096 (estimate 2.76 GB).
double FilmStripBytes(int count, const RenderOptions& options);

// CheckMemory (geometry/memory_limits.h) of FilmStripBytes(frames, options),
// the model kFilmStripModel, before anything is rendered; `what` names the
// output (e.g. "--png"). Also throws as LayoutFilmStrip (a width below one
// pixel per column, a frame wider than 8192 pixels).
void CheckFilmStripMemory(int frames, const RenderOptions& options,
                          const std::string& what);

// The label of frame k of `count`: "k  t=T" as described at
// RenderOptions::labels.
std::string FrameLabel(int k, int count);

// Renders each frame (positions of one shell, all sharing `faces`) with the
// same camera, FrameVertices (camera.h) of the vertices of ALL frames with
// the up axis resolved from the first frame, and lays the frames out left
// to right, top to bottom as LayoutFilmStrip says; cells without a frame
// stay background. Deterministic: equal inputs give equal pixels. Throws
// InputError if there are no frames, frames differ in vertex count, a face
// index is out of range, a coordinate is not finite, or an option is out of
// range.
RgbImage RenderFilmStrip(const std::vector<Positions>& frames,
                         const Faces& faces, const RenderOptions& options);

// RenderFilmStrip, then WritePng to `path` (no partial file on failure).
void WriteFilmStrip(const std::vector<Positions>& frames, const Faces& faces,
                    const RenderOptions& options, const std::string& path);

// Same for meshes; throws InputError unless all meshes have the faces of the
// first one.
void WriteFilmStrip(const std::vector<Mesh>& meshes,
                    const RenderOptions& options, const std::string& path);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_FILM_STRIP_H_
