#include "shellspace/render/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace shellspace {

void ViewFrame(const ViewAngles& view, Eigen::Vector3d* right,
               Eigen::Vector3d* up, Eigen::Vector3d* forward) {
  const double a = view.azimuth * M_PI / 180;
  const double e = view.elevation * M_PI / 180;
  *forward = -Eigen::Vector3d(std::cos(e) * std::sin(a), std::sin(e),
                              std::cos(e) * std::cos(a));
  *right = Eigen::Vector3d(std::cos(a), 0, -std::sin(a));
  *up = right->cross(*forward);
}

void ViewFrame(const ViewAngles& view, UpAxis up_axis, Eigen::Vector3d* right,
               Eigen::Vector3d* up, Eigen::Vector3d* forward) {
  ViewFrame(view, right, up, forward);
  if (up_axis == UpAxis::kPlusY) return;
  // R is a signed permutation: R^T v only moves and negates coordinates, so
  // the frame stays exactly orthonormal.
  const Eigen::Matrix3d inverse = UpRotation(up_axis).transpose();
  *right = inverse * *right;
  *up = inverse * *up;
  *forward = inverse * *forward;
}

void BoundingBox(const std::vector<Positions>& frames, Eigen::Vector3d* lower,
                 Eigen::Vector3d* upper) {
  const double inf = std::numeric_limits<double>::infinity();
  *lower = Eigen::Vector3d::Constant(inf);
  *upper = Eigen::Vector3d::Constant(-inf);
  bool any = false;
  for (size_t k = 0; k < frames.size(); ++k) {
    const Positions& p = frames[k];
    if (p.rows() == 0) continue;
    if (!p.allFinite()) {
      throw InputError("frame " + std::to_string(k) +
                       " has a non-finite vertex coordinate");
    }
    *lower = lower->cwiseMin(p.colwise().minCoeff().transpose());
    *upper = upper->cwiseMax(p.colwise().maxCoeff().transpose());
    any = true;
  }
  if (!any) throw InputError("nothing to render: the frames have no vertices");
}

namespace {

// Sets camera.scale for projected extents extent_x, extent_y (world units).
void FitScale(double extent_x, double extent_y, double size, double margin,
              Camera* camera) {
  const double usable = 1 - 2 * margin;
  const double tiny = 1e-12 * std::max(1.0, size);
  double scale = std::numeric_limits<double>::infinity();
  if (extent_x > tiny) scale = std::min(scale, usable * camera->width / extent_x);
  if (extent_y > tiny) scale = std::min(scale, usable * camera->height / extent_y);
  camera->scale = std::isfinite(scale) ? scale : 1;
}

}  // namespace

Camera FrameBox(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                const ViewAngles& view, int width, int height, double margin) {
  Camera camera;
  ViewFrame(view, &camera.right, &camera.up, &camera.forward);
  camera.center = 0.5 * (lower + upper);
  camera.width = width;
  camera.height = height;
  // The box is symmetric about its centre, so its projection is too.
  const Eigen::Vector3d half = 0.5 * (upper - lower);
  const double extent_x = 2 * camera.right.cwiseAbs().dot(half);
  const double extent_y = 2 * camera.up.cwiseAbs().dot(half);
  FitScale(extent_x, extent_y, half.norm(), margin, &camera);
  return camera;
}

Camera FrameVertices(const std::vector<Positions>& frames,
                     const ViewAngles& view, int width, int height,
                     double margin, UpAxis up_axis, const Faces* faces) {
  Eigen::Vector3d lower, upper;
  BoundingBox(frames, &lower, &upper);  // validates
  Camera camera;
  ViewFrame(view, ResolveUpAxis(up_axis, frames[0], faces), &camera.right,
            &camera.up, &camera.forward);
  camera.width = width;
  camera.height = height;
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(inf);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-inf);
  Eigen::Matrix3d basis;  // rows: right, up, forward
  basis << camera.right.transpose(), camera.up.transpose(),
      camera.forward.transpose();
  for (const Positions& p : frames) {
    for (int i = 0; i < p.rows(); ++i) {
      const Eigen::Vector3d q = basis * p.row(i).transpose();
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  camera.center = basis.transpose() * (0.5 * (lo + hi));
  FitScale(hi.x() - lo.x(), hi.y() - lo.y(), (upper - lower).norm(), margin,
           &camera);
  return camera;
}

}  // namespace shellspace
