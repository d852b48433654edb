// Small meshes, options and image probes shared by the renderer's tests
// (tests/render/, tests/tools/film_strip_cli_data_test.cc).
#ifndef SHELLSPACE_TESTS_TESTING_RENDER_FIXTURES_H_
#define SHELLSPACE_TESTS_TESTING_RENDER_FIXTURES_H_

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/render/film_strip.h"

namespace shellspace::testing {

// The closed box [0, a] x [0, b] x [0, c], 8 vertices, 12 outward triangles.
Mesh Box(double a, double b, double c);

// The square [-1, 1]^2 x {0}, two triangles, outward normal +z.
Mesh UnitSquareMesh();

// Two frames of `mesh`: as it is, and moved by `shift` along the coordinate
// `axis` (0: x, 1: y, 2: z).
std::vector<Positions> MeshAndMovedCopy(const Mesh& mesh, int axis,
                                        double shift);

// True if the pixel p (3 bytes) is `color`.
bool IsColor(const std::uint8_t* p, const std::array<std::uint8_t, 3>& color);

// Pixels of [left, left + width) x [top, top + height) unlike `color`.
int CountUnlike(const RgbImage& image, const std::array<std::uint8_t, 3>& color,
                int left, int top, int width, int height);

// Width and height from a PNG file's IHDR chunk; (-1, -1) if not a PNG.
std::pair<int, int> PngSize(const std::string& path);

// The options of the camera tests: an image `width` pixels wide in total,
// frames `height` high, +y up and no labels (the pictures of the camera
// itself; labels, the up axis and the colour map are tested in
// tests/render/readable_strip_test.cc).
RenderOptions CameraOptions(int width, int height, int supersample = 1);

// Pixels of the cell [left, left + width) x [top, top + height) that differ
// from the background colour of `options` (width, height < 0: the image's
// width and height).
int CoveredPixels(const RgbImage& image, const RenderOptions& options,
                  int left = 0, int top = 0, int width = -1, int height = -1);

// Covered fraction of a sphere about the origin, seen from `view`, against
// the disc of the framing rule (camera.h: the vertices' projected extents fit
// into the frame inset by 5 %), computed here independently: in the front
// view the extents are those of x and y; in any view they are within the
// sphere's diameter 2 r. EXPECTs the ratio in (low, high).
void ExpectSphereCoverage(const Mesh& sphere, const std::string& view,
                          double low, double high);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_RENDER_FIXTURES_H_
