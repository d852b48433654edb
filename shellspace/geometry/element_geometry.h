// Differentiable per-element geometry of a triangle mesh, written once as
// templates over the scalar type so that the same stencil serves the energy,
// its analytic gradient and (by differentiating that gradient with ceres::Jet)
// its Hessian.
//
// Conventions (docs/math.md, "Membrane energy"): triangle (X_i, X_j, X_k),
// E_1 = X_j - X_i, E_2 = X_k - X_i. All gradients are returned per vertex in
// the order (i, j, k) or, for an edge flap, (i, j, k, l) as 3-vectors.
#ifndef SHELLSPACE_GEOMETRY_ELEMENT_GEOMETRY_H_
#define SHELLSPACE_GEOMETRY_ELEMENT_GEOMETRY_H_

#include <cmath>

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// [v]x with [v]x w = v x w.
template <typename T>
Eigen::Matrix<T, 3, 3> CrossMatrix(const Vec3<T>& v) {
  Eigen::Matrix<T, 3, 3> m;
  m << T(0), -v(2), v(1), v(2), T(0), -v(0), -v(1), v(0), T(0);
  return m;
}

// A Hessian over kEdges edge vectors E_a = X_{a+1} - X_0 (3 x 3 blocks) as
// the Hessian over the kEdges + 1 vertices X_0..X_kEdges: block (v, w) =
// sum_{a, b} C(a, v) C(b, w) H_edge(a, b), C(a, 0) = -1, C(a, a + 1) = 1.
template <int kEdges, typename T>
void EdgeToVertexHessian(
    const Eigen::Matrix<T, 3 * kEdges, 3 * kEdges>& edge,
    Eigen::Matrix<T, 3 * kEdges + 3, 3 * kEdges + 3>* vertex) {
  constexpr int n = 3 * kEdges;
  // Rows: vertex 0 = -(sum of the edge rows), vertex a + 1 = edge row a.
  Eigen::Matrix<T, n + 3, n> rows;
  rows.template bottomRows<n>() = edge;
  rows.template topRows<3>().setZero();
  for (int a = 0; a < kEdges; ++a)
    rows.template topRows<3>() -= edge.template middleRows<3>(3 * a);
  vertex->template rightCols<n>() = rows;
  vertex->template leftCols<3>().setZero();
  for (int a = 0; a < kEdges; ++a)
    vertex->template leftCols<3>() -= rows.template middleCols<3>(3 * a);
}

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
//
// Hessian (the Jacobian of that gradient), with N = E1 x E2 = 2 a n and
// [v]x the cross-product matrix ([v]x w = v x w): N is bilinear in (E1, E2),
// dN = -[E2]x dE1 + [E1]x dE2 =: J_N (dE1, dE2), so in edge coordinates
//   d2a/d(E1, E2)^2 = 1/2 ( J_N^T (I - n n^T) J_N / |N|
//                           + [[0, -[n]x], [[n]x, 0]] ),
// mapped to vertices by d/dX_i = -(d/dE1 + d/dE2), d/dX_j = d/dE1, d/dX_k =
// d/dE2.
template <typename T>
struct TriangleArea {
  T area;
  Vec3<T> normal;  // unit normal (E1 x E2)/|E1 x E2|
  Vec3<T> grad[3];
  Vec3<T> e1, e2;  // the edges, kept for Hessian()
  T len;           // |E1 x E2| = 2 a

  TriangleArea(const Vec3<T>& xi, const Vec3<T>& xj, const Vec3<T>& xk)
      : e1(xj - xi), e2(xk - xi) {
    const Vec3<T> n = e1.cross(e2);
    len = n.norm();
    area = T(0.5) * len;
    normal = n / len;
    grad[1] = T(0.5) * e2.cross(normal);
    grad[2] = T(0.5) * normal.cross(e1);
    grad[0] = -(grad[1] + grad[2]);
  }

  // The 9 x 9 Hessian d2a / dX dX, blocks (i, j, k) x (i, j, k).
  void Hessian(Eigen::Matrix<T, 9, 9>* hessian) const {
    Eigen::Matrix<T, 3, 6> jn;
    jn.template leftCols<3>() = -CrossMatrix(e2);
    jn.template rightCols<3>() = CrossMatrix(e1);
    const Eigen::Matrix<T, 3, 3> projector =
        Eigen::Matrix<T, 3, 3>::Identity() - normal * normal.transpose();
    Eigen::Matrix<T, 6, 6> h = jn.transpose() * projector * jn / len;
    const Eigen::Matrix<T, 3, 3> nx = CrossMatrix(normal);
    h.template block<3, 3>(0, 3) -= nx;
    h.template block<3, 3>(3, 0) += nx;
    h *= T(0.5);
    EdgeToVertexHessian<2>(h, hessian);
  }
};

// theta - theta_bar as the representative in [-pi, pi): the change of a
// dihedral angle that crosses the branch cut of atan2 (a flap folded to
// nearly +-pi, turning a little further) is the small turn it is, not
// 2 pi minus it. A constant shift of the difference, so its derivatives are
// those of theta - theta_bar; the jump moves to a flap turned by pi
// against its reference.
template <typename T>
T DihedralAngleChange(const T& theta, const T& theta_bar) {
  T delta = theta - theta_bar;
  const double value = ScalarValue(delta);
  if (value >= M_PI) {
    delta -= T(2 * M_PI);
  } else if (value < -M_PI) {
    delta += T(2 * M_PI);
  }
  return delta;
}

// Signed dihedral angle of an edge flap (i, j, k, l) (geometry/topology.h):
// with e = X_j - X_i, n0 = e x (X_k - X_i), n1 = (X_l - X_i) x e,
//   theta = atan2(((n0 x n1) . e) / |e|, n0 . n1),
// zero for a flat flap. Gradient (Discrete Shells):
//   dtheta/dX_k = -|e| n0/|n0|^2,   dtheta/dX_l = -|e| n1/|n1|^2,
//   dtheta/dX_i = -(1 - s0) dtheta/dX_k - (1 - s1) dtheta/dX_l,
//   dtheta/dX_j = -s0 dtheta/dX_k - s1 dtheta/dX_l,
// with s0 = (X_k - X_i).e/|e|^2, s1 = (X_l - X_i).e/|e|^2 the positions of
// the feet of the opposite vertices along the edge.
//
// Hessian (the Jacobian of that gradient), in the edge coordinates (e, e_k =
// X_k - X_i, e_l = X_l - X_i), with u_0 = n0/|n0|^2, B_0 = (I - 2 n0 n0^T /
// |n0|^2) / |n0|^2 (so d u_0 = B_0 d n0), ehat = e/|e|, [v]x the
// cross-product matrix, and likewise u_1, B_1 for n1:
//   dn0 = -[e_k]x de + [e]x de_k,            dn1 = [e_l]x de - [e]x de_l,
//   d g_k/de = -u_0 ehat^T + |e| B_0 [e_k]x,  d g_k/de_k = -|e| B_0 [e]x,
//   d g_l/de = -u_1 ehat^T - |e| B_1 [e_l]x,  d g_l/de_l =  |e| B_1 [e]x,
//   d s0/de = (e_k - 2 s0 e)^T/|e|^2, d s0/de_k = e^T/|e|^2 (s1 with e_l),
//   d g_i = g_k ds0 - (1 - s0) d g_k + g_l ds1 - (1 - s1) d g_l,
//   d g_j = -g_k ds0 - s0 d g_k - g_l ds1 - s1 d g_l,
// mapped to vertices by d/dX_i = -(d/de + d/de_k + d/de_l).
template <typename T>
struct DihedralAngle {
  T theta;
  Vec3<T> grad[4];  // (i, j, k, l)
  // Stencil quantities, kept for Hessian().
  Vec3<T> e, ek, el, n0, n1;
  T e_len, s0, s1;

  DihedralAngle(const Vec3<T>& xi, const Vec3<T>& xj, const Vec3<T>& xk,
                const Vec3<T>& xl)
      : e(xj - xi), ek(xk - xi), el(xl - xi) {
    n0 = e.cross(ek);
    n1 = el.cross(e);
    const T e_len2 = e.squaredNorm();
    e_len = sqrt(e_len2);
    theta = atan2(n0.cross(n1).dot(e) / e_len, n0.dot(n1));
    grad[2] = -(e_len / n0.squaredNorm()) * n0;
    grad[3] = -(e_len / n1.squaredNorm()) * n1;
    s0 = ek.dot(e) / e_len2;
    s1 = el.dot(e) / e_len2;
    grad[0] = -(T(1) - s0) * grad[2] - (T(1) - s1) * grad[3];
    grad[1] = -s0 * grad[2] - s1 * grad[3];
  }

  // The 12 x 12 Hessian d2theta / dX dX, blocks (i, j, k, l) x (i, j, k, l).
  void Hessian(Eigen::Matrix<T, 12, 12>* hessian) const {
    using M3 = Eigen::Matrix<T, 3, 3>;
    const M3 identity = M3::Identity();
    const T n0_sq = n0.squaredNorm(), n1_sq = n1.squaredNorm();
    const T e_len2 = e_len * e_len;
    const Vec3<T> ehat = e / e_len;
    const Vec3<T> u0 = n0 / n0_sq, u1 = n1 / n1_sq;
    const M3 b0 = (identity - (T(2) / n0_sq) * n0 * n0.transpose()) / n0_sq;
    const M3 b1 = (identity - (T(2) / n1_sq) * n1 * n1.transpose()) / n1_sq;
    const M3 ex = CrossMatrix(e);
    // Jacobians w.r.t. (e, e_k, e_l): 3 x 9 for the vector gradients, 1 x 9
    // for s0, s1.
    Eigen::Matrix<T, 3, 9> dgk = Eigen::Matrix<T, 3, 9>::Zero();
    Eigen::Matrix<T, 3, 9> dgl = Eigen::Matrix<T, 3, 9>::Zero();
    dgk.template leftCols<3>() =
        -u0 * ehat.transpose() + e_len * b0 * CrossMatrix(ek);
    dgk.template middleCols<3>(3) = -e_len * b0 * ex;
    dgl.template leftCols<3>() =
        -u1 * ehat.transpose() - e_len * b1 * CrossMatrix(el);
    dgl.template rightCols<3>() = e_len * b1 * ex;
    Eigen::Matrix<T, 1, 9> ds0 = Eigen::Matrix<T, 1, 9>::Zero();
    Eigen::Matrix<T, 1, 9> ds1 = Eigen::Matrix<T, 1, 9>::Zero();
    ds0.template leftCols<3>() = (ek - T(2) * s0 * e).transpose() / e_len2;
    ds0.template middleCols<3>(3) = e.transpose() / e_len2;
    ds1.template leftCols<3>() = (el - T(2) * s1 * e).transpose() / e_len2;
    ds1.template rightCols<3>() = e.transpose() / e_len2;
    const Eigen::Matrix<T, 3, 9> gk_ds0 = grad[2] * ds0;
    const Eigen::Matrix<T, 3, 9> gl_ds1 = grad[3] * ds1;
    // Rows (i, j, k, l), columns (e, e_k, e_l).
    Eigen::Matrix<T, 12, 9> rows;
    rows.template middleRows<3>(0) =
        gk_ds0 - (T(1) - s0) * dgk + gl_ds1 - (T(1) - s1) * dgl;
    rows.template middleRows<3>(3) = -gk_ds0 - s0 * dgk - gl_ds1 - s1 * dgl;
    rows.template middleRows<3>(6) = dgk;
    rows.template middleRows<3>(9) = dgl;
    hessian->template rightCols<9>() = rows;
    hessian->template leftCols<3>() = -(rows.template middleCols<3>(0) +
                                        rows.template middleCols<3>(3) +
                                        rows.template middleCols<3>(6));
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_ELEMENT_GEOMETRY_H_
