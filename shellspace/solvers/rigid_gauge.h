// Removing the 6 rigid-motion degrees of freedom of a free shell without
// dense rows (docs/math.md, "Derivatives and the rigid-motion gauge").
#ifndef SHELLSPACE_SOLVERS_RIGID_GAUGE_H_
#define SHELLSPACE_SOLVERS_RIGID_GAUGE_H_

#include <ceres/manifold.h>
#include <ceres/problem.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The affine subspace {x + B delta} of R^3 through the current point, with an
// orthonormal basis B (3 x m, m = 1: a line, m = 2: a plane). Plus(x, delta) =
// x + B delta, Minus(y, x) = B^T (y - x).
class AffineSubspaceManifold : public ceres::Manifold {
 public:
  explicit AffineSubspaceManifold(const Eigen::MatrixXd& basis);
  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return static_cast<int>(basis_.cols()); }
  bool Plus(const double* x, const double* delta,
            double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x,
             double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;

 private:
  Eigen::MatrixXd basis_;  // 3 x m, orthonormal columns
};

// Three vertices far apart: a = the vertex farthest from the centroid, b = the
// vertex farthest from a, c = the vertex farthest from the line ab.
std::array<int, 3> ChooseGaugeVertices(const Positions& shape);
// The same among the vertices of `group` (ascending; the whole shape: the
// same three as above).
std::array<int, 3> ChooseGaugeVertices(const Positions& shape,
                                       const std::vector<int>& group);
// A shell of several connected components (ConnectedComponents) moves
// rigidly in each: three gauge vertices per component, in the order of
// `components`.
std::vector<std::array<int, 3>> ChooseGaugeVertices(
    const Positions& shape, const std::vector<std::vector<int>>& components);

// The gauge of PinRigidMotions on a shape: vertex a held, b on the line
// through it along `line` (unit a -> b), c in the plane through it spanned by
// the orthonormal columns of `plane` (line, and the unit component of c - a
// orthogonal to it).
struct RigidGauge {
  std::array<int, 3> vertices{};  // a, b, c
  Eigen::Vector3d line;
  Eigen::Matrix<double, 3, 2> plane;
};
RigidGauge MakeRigidGauge(const Positions& shape);
// The same frame for given vertices a, b, c (which must not be collinear in
// `shape`: line and plane are then not finite).
RigidGauge MakeRigidGauge(const Positions& shape,
                          const std::array<int, 3>& vertices);

// Max |component| of a gradient `g` (3n, vertex-major, of a function of the
// shape's positions) over the coordinates `gauge` leaves free: every
// coordinate of the other vertices, line^T g_b and plane^T g_c -- the
// gradient_max_norm Ceres reports for a problem pinned by PinRigidMotions.
double GaugeFreeMaxNorm(const RigidGauge& gauge, const Eigen::VectorXd& g);

// Pins the rigid motions of `shape` (whose vertex blocks are in `problem`):
// vertex a is held constant, b moves only along the line ab, c only in the
// plane abc (at their current positions). Exactly 6 degrees of freedom are
// removed; the energy at the optimum does not depend on the choice. Returns
// the three vertices.
std::array<int, 3> PinRigidMotions(Positions* shape, ceres::Problem* problem);
// The same in each of `components` (6 degrees of freedom each).
void PinRigidMotions(Positions* shape, ceres::Problem* problem,
                     const std::vector<std::vector<int>>& components);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_RIGID_GAUGE_H_
