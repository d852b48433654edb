// Small meshes and image probes shared by the renderer's tests
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

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_RENDER_FIXTURES_H_
