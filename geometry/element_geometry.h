// Differentiable per-element geometry of a triangle mesh, written once as
// templates over the scalar type so that the same stencil serves the energy,
// its analytic gradient and (by differentiating that gradient with ceres::Jet)
// its Hessian.
//
// Conventions (shells.md): triangle (X_i, X_j, X_k), E_1 = X_j - X_i,
// E_2 = X_k - X_i. All gradients are returned per vertex in the order
// (i, j, k) or, for an edge flap, (i, j, k, l) as 3-vectors.
#ifndef SHELLSPACE_GEOMETRY_ELEMENT_GEOMETRY_H_
#define SHELLSPACE_GEOMETRY_ELEMENT_GEOMETRY_H_

#include <cmath>

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// First fundamental form in the edge basis, g = [[E1.E1, E1.E2],[E1.E2,
// E2.E2]], stored as (g11, g12, g22). Gradient: dg11/dE1 = 2 E1, dg12/dE1 = E2,
// dg12/dE2 = E1, dg22/dE2 = 2 E2 (and d/dX_i = -(d/dE1 + d/dE2)).
template <typename T>
struct FirstFundamentalForm {
  T g11, g12, g22;
  // grad[m][v]: gradient of entry m (0: g11, 1: g12, 2: g22) w.r.t. vertex v.
  Vec3<T> grad[3][3];

  FirstFundamentalForm(const Vec3<T>& xi, const Vec3<T>& xj,
                       const Vec3<T>& xk) {
    const Vec3<T> e1 = xj - xi, e2 = xk - xi;
    g11 = e1.dot(e1);
    g12 = e1.dot(e2);
    g22 = e2.dot(e2);
    const Vec3<T> zero = Vec3<T>::Zero();
    const Vec3<T> d_e1[3] = {T(2) * e1, e2, zero};
    const Vec3<T> d_e2[3] = {zero, e1, T(2) * e2};
    for (int m = 0; m < 3; ++m) {
      grad[m][1] = d_e1[m];
      grad[m][2] = d_e2[m];
      grad[m][0] = -(d_e1[m] + d_e2[m]);
    }
  }
};

// Triangle area a = |E1 x E2| / 2 = sqrt(det g) / 2 and its gradient
// da/dX_j = (E2 x n) / 2, da/dX_k = (n x E1) / 2, da/dX_i = -(sum), n the unit
// normal.
template <typename T>
struct TriangleArea {
  T area;
  Vec3<T> normal;  // unit normal (E1 x E2)/|E1 x E2|
  Vec3<T> grad[3];

  TriangleArea(const Vec3<T>& xi, const Vec3<T>& xj, const Vec3<T>& xk) {
    const Vec3<T> e1 = xj - xi, e2 = xk - xi;
    const Vec3<T> n = e1.cross(e2);
    const T len = n.norm();
    area = T(0.5) * len;
    normal = n / len;
    grad[1] = T(0.5) * e2.cross(normal);
    grad[2] = T(0.5) * normal.cross(e1);
    grad[0] = -(grad[1] + grad[2]);
  }
};

// Signed dihedral angle of an edge flap (i, j, k, l) (geometry/topology.h):
// with e = X_j - X_i, n0 = e x (X_k - X_i), n1 = (X_l - X_i) x e,
//   theta = atan2(((n0 x n1) . e) / |e|, n0 . n1),
// zero for a flat flap. Gradient (Discrete Shells):
//   dtheta/dX_k = -|e| n0/|n0|^2,   dtheta/dX_l = -|e| n1/|n1|^2,
//   dtheta/dX_i = -(1 - s0) dtheta/dX_k - (1 - s1) dtheta/dX_l,
//   dtheta/dX_j = -s0 dtheta/dX_k - s1 dtheta/dX_l,
// with s0 = (X_k - X_i).e/|e|^2, s1 = (X_l - X_i).e/|e|^2 the positions of
// the feet of the opposite vertices along the edge.
template <typename T>
struct DihedralAngle {
  T theta;
  Vec3<T> grad[4];  // (i, j, k, l)

  DihedralAngle(const Vec3<T>& xi, const Vec3<T>& xj, const Vec3<T>& xk,
                const Vec3<T>& xl) {
    const Vec3<T> e = xj - xi;
    const Vec3<T> ek = xk - xi, el = xl - xi;
    const Vec3<T> n0 = e.cross(ek);
    const Vec3<T> n1 = el.cross(e);
    const T e_len2 = e.squaredNorm();
    const T e_len = sqrt(e_len2);
    theta = atan2(n0.cross(n1).dot(e) / e_len, n0.dot(n1));
    grad[2] = -(e_len / n0.squaredNorm()) * n0;
    grad[3] = -(e_len / n1.squaredNorm()) * n1;
    const T s0 = ek.dot(e) / e_len2;
    const T s1 = el.dot(e) / e_len2;
    grad[0] = -(T(1) - s0) * grad[2] - (T(1) - s1) * grad[3];
    grad[1] = -s0 * grad[2] - s1 * grad[3];
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_ELEMENT_GEOMETRY_H_
