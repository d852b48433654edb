// Z-buffer triangle rasteriser of the renderer.
#ifndef SHELLSPACE_RENDER_RASTERIZER_H_
#define SHELLSPACE_RENDER_RASTERIZER_H_

#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/render/camera.h"
#include "shellspace/render/shading.h"

namespace shellspace {

// Colour and depth of a width x height image; colours are RGB in [0, 1], row
// 0 is the top row. Depth starts at +infinity (nothing drawn).
struct FrameBuffer {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3d> color;  // index y * width + x
  std::vector<double> depth;           // index y * width + x

  FrameBuffer(int w, int h, const Eigen::Vector3d& background);
  // True where some triangle has been drawn.
  bool covered(int x, int y) const;
};

// Draws the triangles of the mesh (positions, faces) seen through `camera`
// into `target` (which must have the camera's width and height). A pixel is
// drawn when its centre lies inside or on the edge of the projected triangle
// and the depth interpolated there is smaller than the stored depth (ties keep
// the earlier triangle, so the result depends only on the input). Triangles
// that project to zero area (seen edge-on) are skipped. Colours follow
// `lighting` and `shading` (shading.h). With `vertex_colors` (one RGB colour
// per vertex), a pixel's base colour is the barycentric interpolation of its
// triangle's vertex colours on both sides, replacing front_color and
// back_color; the shading multiplies it as before. Throws InputError if a
// face refers to a vertex outside [0, positions.rows()) or vertex_colors has
// another size than positions.rows().
void RasterizeMesh(const Positions& positions, const Faces& faces,
                   const Camera& camera, Shading shading,
                   const Lighting& lighting, FrameBuffer* target,
                   const std::vector<Eigen::Vector3d>* vertex_colors = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_RASTERIZER_H_
