// Film strips: the frames of a shell sequence rendered side by side into one
// image by a fixed camera, and written as PNG.
#ifndef SHELLSPACE_RENDER_FILM_STRIP_H_
#define SHELLSPACE_RENDER_FILM_STRIP_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/render/shading.h"
#include "shellspace/render/view.h"

namespace shellspace {

// How a film strip is drawn. The defaults are those of `shellspace render`.
struct RenderOptions {
  int width = 320;    // pixels per frame, > 0
  int height = 320;   // pixels per frame, > 0
  ViewAngles view;    // front view by default (see view.h)
  Shading shading = Shading::kGouraud;
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

// Renders each frame (positions of one shell, all sharing `faces`) with the
// same camera, FrameVertices (camera.h) of the vertices of ALL frames, and
// lays the frames out left to right, top to bottom: with n frames,
// columns = min(n, max_per_row) and rows = ceil(n / columns), so the image is
// columns * width by rows * height pixels; frame k occupies the cell at
// column k % columns, row k / columns; cells without a frame stay background.
// Deterministic: equal inputs give equal pixels. Throws InputError if there
// are no frames, frames differ in vertex count, a face index is out of range,
// a coordinate is not finite, or an option is out of range.
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
