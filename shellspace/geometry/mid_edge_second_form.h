// The per-face second fundamental form H_T from mid-edge normals (docs/math.md,
// "Bending energy: two models"), written once as a template over the scalar
// type (as geometry/element_geometry.h) so the same stencil gives the value,
// its analytic gradient and, through ceres::Jet, second derivatives.
//
// Face T = (X_0, X_1, X_2) counter-clockwise with unit normal N, edge basis
// E_1 = X_1 - X_0, E_2 = X_2 - X_0. Edge i is opposite X_i (it joins X_{i+1}
// and X_{i+2}, indices mod 3); across an interior edge i lies the face
// (X_{i+2}, X_{i+1}, P_i) with unit normal N_i, and n_i = (N + N_i)/|N + N_i|
// is the mid-edge normal. Then
//   c_i = (X_{i+1} + X_{i+2} - 2 X_i) . n_i   ( = 2 h_i sin(theta_i / 2) ),
//   H_T = [[c_0 + c_1, c_0], [c_0, c_0 + c_2]]   (in the basis E_1, E_2),
// with c_i = 0 on a boundary edge. The shape operator is B_T = G_T^-1 H_T,
// G_T the first fundamental form (FirstFundamentalForm).
#ifndef SHELLSPACE_GEOMETRY_MID_EDGE_SECOND_FORM_H_
#define SHELLSPACE_GEOMETRY_MID_EDGE_SECOND_FORM_H_

#include <cmath>

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// Gradient of w . N(x0, x1, x2) for a fixed vector w, N the unit normal of
// the triangle, m = (x1 - x0) x (x2 - x0), N = m / |m|, w_perp = (I - N N^T)
// w: d/dx1 = (e2 x w_perp)/|m|, d/dx2 = (w_perp x e1)/|m|, d/dx0 = -(sum).
template <typename T>
void UnitNormalDirectionalGradient(const Vec3<T>& x0, const Vec3<T>& x1,
                                   const Vec3<T>& x2, const Vec3<T>& w,
                                   Vec3<T>* g0, Vec3<T>* g1, Vec3<T>* g2) {
  const Vec3<T> e1 = x1 - x0, e2 = x2 - x0;
  const Vec3<T> m = e1.cross(e2);
  const T len = m.norm();
  const Vec3<T> normal = m / len;
  const Vec3<T> w_perp = w - w.dot(normal) * normal;
  *g1 = e2.cross(w_perp) / len;
  *g2 = w_perp.cross(e1) / len;
  *g0 = -(*g1 + *g2);
}

// c of one interior edge: the face (xc, xa, xb) (a cyclic rotation of T, xc
// the vertex opposite the edge xa -> xb), the face across it (xb, xa, xp).
//   c = (xa + xb - 2 xc) . n,  n = (N + N') / |N + N'|.
// Gradient (with u = xa + xb - 2 xc, w = (I - n n^T) u / |N + N'|):
//   dc = n . du + w . dN + w . dN'
// (UnitNormalDirectionalGradient for the last two). `valid` is false if a
// face is degenerate or the two normals are opposite (N + N' = 0).
template <typename T>
struct MidEdgeCoefficient {
  T c;
  Vec3<T> grad_a, grad_b, grad_c, grad_p;
  bool valid = false;

  MidEdgeCoefficient(const Vec3<T>& xa, const Vec3<T>& xb, const Vec3<T>& xc,
                     const Vec3<T>& xp, bool derivatives) {
    const Vec3<T> m0 = (xa - xc).cross(xb - xc);
    const Vec3<T> m1 = (xa - xb).cross(xp - xb);
    const T len0 = m0.norm(), len1 = m1.norm();
    if (!(ScalarValue(len0) > 0.0) || !(ScalarValue(len1) > 0.0)) return;
    const Vec3<T> sum = m0 / len0 + m1 / len1;
    const T sum_len = sum.norm();
    if (!(ScalarValue(sum_len) > 1e-12)) return;
    const Vec3<T> n = sum / sum_len;
    const Vec3<T> u = xa + xb - T(2) * xc;
    c = u.dot(n);
    valid = std::isfinite(ScalarValue(c));
    if (!derivatives || !valid) return;
    const Vec3<T> w = (u - c * n) / sum_len;
    Vec3<T> g0, g1, g2;
    UnitNormalDirectionalGradient(xc, xa, xb, w, &g0, &g1, &g2);
    grad_c = T(-2) * n + g0;
    grad_a = n + g1;
    grad_b = n + g2;
    UnitNormalDirectionalGradient(xb, xa, xp, w, &g0, &g1, &g2);
    grad_b += g0;
    grad_a += g1;
    grad_p = g2;
  }
};

// H_T of a face whose first kInterior edges (edges 0 .. kInterior - 1) are
// interior and the others boundary. Stencil x[0 .. 2] = X_0, X_1, X_2,
// x[3 + i] = P_i (i < kInterior): 3 + kInterior vertices. Entries
// (h11, h12, h22) = (c_0 + c_1, c_0, c_0 + c_2); grad[m][v] the gradient of
// entry m (0: h11, 1: h12, 2: h22) w.r.t. stencil vertex v (filled if
// `derivatives`). `valid` is false if any c_i is undefined.
template <typename T, int kInterior>
struct MidEdgeSecondForm {
  static constexpr int kVertices = 3 + kInterior;
  T c[3];
  T h11, h12, h22;
  Vec3<T> grad[3][kVertices];
  bool valid = true;

  MidEdgeSecondForm(const Vec3<T>* x, bool derivatives) {
    Vec3<T> dc[3][kVertices];
    for (int i = 0; i < 3; ++i) {
      c[i] = T(0);
      for (int v = 0; v < kVertices; ++v) dc[i][v].setZero();
    }
    for (int i = 0; i < kInterior; ++i) {
      const int a = (i + 1) % 3, b = (i + 2) % 3;
      const MidEdgeCoefficient<T> edge(x[a], x[b], x[i], x[3 + i], derivatives);
      if (!edge.valid) {
        valid = false;
        return;
      }
      c[i] = edge.c;
      if (derivatives) {
        dc[i][a] = edge.grad_a;
        dc[i][b] = edge.grad_b;
        dc[i][i] = edge.grad_c;
        dc[i][3 + i] = edge.grad_p;
      }
    }
    h11 = c[0] + c[1];
    h12 = c[0];
    h22 = c[0] + c[2];
    if (!derivatives) return;
    for (int v = 0; v < kVertices; ++v) {
      grad[0][v] = dc[0][v] + dc[1][v];
      grad[1][v] = dc[0][v];
      grad[2][v] = dc[0][v] + dc[2][v];
    }
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_MID_EDGE_SECOND_FORM_H_
