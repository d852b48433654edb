// The fixed orthographic camera of the film strips.
#ifndef SHELLSPACE_RENDER_CAMERA_H_
#define SHELLSPACE_RENDER_CAMERA_H_

#include <vector>

#include <Eigen/Core>

#include "shellspace/geometry/mesh.h"
#include "shellspace/render/up_axis.h"
#include "shellspace/render/view.h"

namespace shellspace {

// An orthographic camera onto a width x height pixel image. With the
// orthonormal frame (right, up, forward), forward = -c of ViewAngles, a world
// point p maps to
//   x     = width / 2  + scale * right   . (p - center)
//   y     = height / 2 - scale * up      . (p - center)
//   depth =              forward . (p - center)
// in pixel units: x grows rightwards, y downwards (row 0 is the top row), and a
// smaller depth is nearer to the viewer. Pixel (i, j) is the square
// [i, i + 1) x [j, j + 1) and is sampled at its centre (i + 0.5, j + 0.5).
struct Camera {
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  Eigen::Vector3d forward = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double scale = 1;  // pixels per world unit
  int width = 0;
  int height = 0;

  // (x, y, depth) of the world point p, by the formula above.
  Eigen::Vector3d Project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - center;
    return {0.5 * width + scale * right.dot(d),
            0.5 * height - scale * up.dot(d), forward.dot(d)};
  }
};

// The camera frame of a view: forward = -c(azimuth, elevation),
// right = (cos(azimuth), 0, -sin(azimuth)) (horizontal, so the world +y axis
// never appears tilted), up = right x forward.
void ViewFrame(const ViewAngles& view, Eigen::Vector3d* right,
               Eigen::Vector3d* up, Eigen::Vector3d* forward);

// The same frame for another up axis (up_axis.h): the view's frame in the
// world rotated by R = UpRotation(up_axis), brought back to world
// coordinates (each vector R^T v), so that UpDirection(up_axis) plays the
// part of +y: it never appears tilted, the azimuth turns about it and
// elevation 90 looks down along it. kPlusY gives ViewFrame(view) exactly.
// Throws std::invalid_argument for kAuto.
void ViewFrame(const ViewAngles& view, UpAxis up_axis, Eigen::Vector3d* right,
               Eigen::Vector3d* up, Eigen::Vector3d* forward);

// Axis-aligned bounding box of all vertices of all frames. Throws InputError
// if there are no vertices or a coordinate is not finite.
void BoundingBox(const std::vector<Positions>& frames, Eigen::Vector3d* lower,
                 Eigen::Vector3d* upper);

// The camera that frames the box [lower, upper] for the view: center is the
// box centre and scale is the largest value for which the projection of the
// box's eight corners fits into the image inset by margin * width on the
// left and right and margin * height on the top and bottom, i.e.
//   scale = min((1 - 2 margin) width / extent_x, (1 - 2 margin) height / extent_y)
// with extent_x, extent_y the widths of the projected box along right and up
// (an extent of zero imposes no limit; a box that projects to a point gets
// scale 1). Using one box for all frames of a sequence keeps the camera
// fixed, so motion between frames stays visible.
Camera FrameBox(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                const ViewAngles& view, int width, int height, double margin);

// The tighter camera that frames the vertices of all frames themselves: with
// [lo_x, hi_x] the range of right . p and [lo_y, hi_y] that of up . p over all
// vertices p of all frames, center projects to the middle of both ranges and
//   scale = min((1 - 2 margin) width / (hi_x - lo_x),
//               (1 - 2 margin) height / (hi_y - lo_y))
// (zero ranges as in FrameBox), so the projected vertices touch the margins
// on at least one side. One camera for all frames: motion stays visible.
// The camera frame is ViewFrame(view, up_axis) with up_axis resolved by
// ResolveUpAxis(up_axis, frames[0], faces) (kAuto: from the first frame and,
// if given, the faces' boundary). Throws InputError as BoundingBox does.
Camera FrameVertices(const std::vector<Positions>& frames,
                     const ViewAngles& view, int width, int height,
                     double margin, UpAxis up_axis = UpAxis::kPlusY,
                     const Faces* faces = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_CAMERA_H_
