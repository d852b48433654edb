#include "shellspace/render/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace shellspace {
namespace {

// Twice the signed area of the screen triangle (a, b, p): positive when p is
// to the left of a -> b in a y-up frame.
double EdgeFunction(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    double px, double py) {
  return (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
}

// Area-weighted vertex normals (sum of the unnormalized face normals),
// normalized; zero for vertices without non-degenerate faces.
std::vector<Eigen::Vector3d> VertexNormals(const Positions& p,
                                           const Faces& faces) {
  std::vector<Eigen::Vector3d> normals(p.rows(), Eigen::Vector3d::Zero());
  for (int f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = p.row(faces(f, 0)).transpose();
    const Eigen::Vector3d b = p.row(faces(f, 1)).transpose();
    const Eigen::Vector3d c = p.row(faces(f, 2)).transpose();
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals[faces(f, k)] += n;
  }
  for (auto& n : normals) {
    const double length = n.norm();
    if (length > 0) n /= length;
  }
  return normals;
}

void CheckFaces(const Faces& faces, int num_vertices) {
  if (faces.size() == 0) return;
  if (faces.minCoeff() < 0 || faces.maxCoeff() >= num_vertices) {
    throw InputError("a face refers to a vertex outside [0, " +
                     std::to_string(num_vertices) + ")");
  }
}

// A face on screen: its corners projected (x, y in pixels, z the depth),
// twice its signed area, the light's intensity at its corners and the
// colour of its side facing the viewer.
struct ScreenTriangle {
  Eigen::Vector3d screen[3];
  double area = 0;
  double shade[3] = {0, 0, 0};
  Eigen::Vector3d base;
};

// Draws face f of `faces` as `triangle` into *target: each pixel whose
// centre lies in it and whose depth is nearer than the buffer's gets the
// interpolated shade times its base colour (or the interpolated vertex
// colours).
void FillTriangle(const ScreenTriangle& triangle, const Faces& faces, int f,
                  const std::vector<Eigen::Vector3d>* vertex_colors,
                  FrameBuffer* target) {
  const Eigen::Vector3d* const screen = triangle.screen;
  const double area = triangle.area;
  const double* const shade = triangle.shade;
  const Eigen::Vector3d& base = triangle.base;
  const double min_x = std::min({screen[0].x(), screen[1].x(), screen[2].x()});
  const double max_x = std::max({screen[0].x(), screen[1].x(), screen[2].x()});
  const double min_y = std::min({screen[0].y(), screen[1].y(), screen[2].y()});
  const double max_y = std::max({screen[0].y(), screen[1].y(), screen[2].y()});
  // Pixels whose centres can lie in the triangle, clipped to the image.
  const int x0 = std::max(0, static_cast<int>(std::ceil(min_x - 0.5)));
  const int x1 = std::min(target->width - 1,
                          static_cast<int>(std::floor(max_x - 0.5)));
  const int y0 = std::max(0, static_cast<int>(std::ceil(min_y - 0.5)));
  const int y1 = std::min(target->height - 1,
                          static_cast<int>(std::floor(max_y - 0.5)));
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      const double w0 = EdgeFunction(screen[1], screen[2], px, py) / area;
      const double w1 = EdgeFunction(screen[2], screen[0], px, py) / area;
      const double w2 = EdgeFunction(screen[0], screen[1], px, py) / area;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const double z =
          w0 * screen[0].z() + w1 * screen[1].z() + w2 * screen[2].z();
      const size_t index = static_cast<size_t>(y) * target->width + x;
      if (!(z < target->depth[index])) continue;
      target->depth[index] = z;
      const double s = w0 * shade[0] + w1 * shade[1] + w2 * shade[2];
      if (vertex_colors) {
        target->color[index] = s * (w0 * (*vertex_colors)[faces(f, 0)] +
                                    w1 * (*vertex_colors)[faces(f, 1)] +
                                    w2 * (*vertex_colors)[faces(f, 2)]);
      } else {
        target->color[index] = s * base;
      }
    }
  }
}

}  // namespace

FrameBuffer::FrameBuffer(int w, int h, const Eigen::Vector3d& background)
    : width(w),
      height(h),
      color(static_cast<size_t>(w) * h, background),
      depth(static_cast<size_t>(w) * h,
            std::numeric_limits<double>::infinity()) {}

bool FrameBuffer::covered(int x, int y) const {
  return std::isfinite(depth[static_cast<size_t>(y) * width + x]);
}

void RasterizeMesh(const Positions& positions, const Faces& faces,
                   const Camera& camera, Shading shading,
                   const Lighting& lighting, FrameBuffer* target,
                   const std::vector<Eigen::Vector3d>* vertex_colors) {
  CheckFaces(faces, static_cast<int>(positions.rows()));
  if (vertex_colors &&
      vertex_colors->size() != static_cast<size_t>(positions.rows())) {
    throw InputError("vertex colours: " +
                     std::to_string(vertex_colors->size()) + " for " +
                     std::to_string(positions.rows()) + " vertices");
  }
  const Eigen::Vector3d light =
      (lighting.light_in_camera.x() * camera.right +
       lighting.light_in_camera.y() * camera.up -
       lighting.light_in_camera.z() * camera.forward)
          .normalized();
  const std::vector<Eigen::Vector3d> vertex_normals =
      shading == Shading::kGouraud ? VertexNormals(positions, faces)
                                   : std::vector<Eigen::Vector3d>();
  auto intensity = [&](const Eigen::Vector3d& n) {
    return lighting.ambient + lighting.diffuse * std::max(0.0, n.dot(light));
  };

  for (int f = 0; f < faces.rows(); ++f) {
    ScreenTriangle triangle;
    Eigen::Vector3d world[3];
    Eigen::Vector3d* const screen = triangle.screen;
    for (int k = 0; k < 3; ++k) {
      world[k] = positions.row(faces(f, k)).transpose();
      screen[k] = camera.Project(world[k]);
    }
    const double area = EdgeFunction(screen[0], screen[1], screen[2].x(),
                                     screen[2].y());
    if (!(std::abs(area) > 1e-12)) continue;
    triangle.area = area;

    // Side facing the viewer: the front when the normal points at the camera.
    Eigen::Vector3d normal = (world[1] - world[0]).cross(world[2] - world[0]);
    const double length = normal.norm();
    if (length > 0) normal /= length;
    const bool front = normal.dot(camera.forward) < 0;
    const double side = front ? 1.0 : -1.0;
    triangle.base = front ? lighting.front_color : lighting.back_color;

    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& n =
          shading == Shading::kGouraud && vertex_normals[faces(f, k)].squaredNorm() > 0
              ? vertex_normals[faces(f, k)]
              : normal;
      triangle.shade[k] = intensity(side * n);
    }
    FillTriangle(triangle, faces, f, vertex_colors, target);
  }
}

}  // namespace shellspace
