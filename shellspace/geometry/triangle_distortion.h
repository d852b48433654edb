// Distortion of a triangle relative to a reference triangle, in an orthonormal
// frame of the reference triangle, with analytic derivatives w.r.t. both the
// reference and the deformed vertices.
#ifndef SHELLSPACE_GEOMETRY_TRIANGLE_DISTORTION_H_
#define SHELLSPACE_GEOMETRY_TRIANGLE_DISTORTION_H_

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// For reference edges Eb1, Eb2 and deformed edges E1, E2 (docs/math.md,
// "Membrane energy") let gbar = L L^T be the Cholesky factorisation of the
// reference first fundamental form, L = [[l11, 0], [l21, l22]], i.e.
//   l11 = |Eb1|,  rho = l21/l11 = Eb1.Eb2/|Eb1|^2,  l22 = |Eb2 - rho Eb1|,
// and the reference area abar = l11 l22 / 2. The deformation gradient in the
// reference frame has columns F1 = E1/l11, F2 = (E2 - rho E1)/l22, and
//   [[a, b], [b, c]] = F^T F = L^-1 g L^-T,
// so tr G = a + c and det G = a c - b^2 for G = gbar^-1 g.
//
// Stored derivatives: d_deformed[m][v] and d_reference[m][v] are the
// gradients of m = (a, b, c) w.r.t. vertex v = (i, j, k) of the deformed and
// reference triangle; d_area[v] the gradient of abar.
template <typename T>
struct TriangleDistortion {
  T a, b, c;
  T reference_area;
  Vec3<T> d_deformed[3][3];
  Vec3<T> d_reference[3][3];
  Vec3<T> d_area[3];

  // `with_derivatives` = false computes only the values.
  TriangleDistortion(const Vec3<T>* ref, const Vec3<T>* def,
                     bool with_derivatives) {
    const Vec3<T> eb1 = ref[1] - ref[0], eb2 = ref[2] - ref[0];
    const T l11_sq = eb1.squaredNorm();
    const T l11 = sqrt(l11_sq);
    const T rho = eb1.dot(eb2) / l11_sq;
    const Vec3<T> p = eb2 - rho * eb1;
    const T l22 = p.norm();
    reference_area = T(0.5) * l11 * l22;

    const Vec3<T> e1 = def[1] - def[0], e2 = def[2] - def[0];
    const Vec3<T> f1 = e1 / l11;
    const Vec3<T> f2 = (e2 - rho * e1) / l22;
    a = f1.dot(f1);
    b = f1.dot(f2);
    c = f2.dot(f2);
    if (!with_derivatives) return;

    // Deformed side: gradients w.r.t. E1 and E2.
    const Vec3<T> zero = Vec3<T>::Zero();
    const Vec3<T> d_e1[3] = {T(2) * f1 / l11, f2 / l11 - rho * f1 / l22,
                             T(-2) * rho * f2 / l22};
    const Vec3<T> d_e2[3] = {zero, f1 / l22, T(2) * f2 / l22};
    for (int m = 0; m < 3; ++m) {
      d_deformed[m][1] = d_e1[m];
      d_deformed[m][2] = d_e2[m];
      d_deformed[m][0] = -(d_e1[m] + d_e2[m]);
    }

    // Reference side: chain through the frame parameters (l11, rho, l22).
    const T r = l11 / l22;
    const T d_param[4][3] = {{T(-2) * a / l11, T(0), T(0)},           // a
                             {-b / l11, -r * a, -b / l22},            // b
                             {T(0), T(-2) * r * b, T(-2) * c / l22},  // c
                             {T(0.5) * l22, T(0), T(0.5) * l11}};     // abar
    const Vec3<T> dl11[2] = {eb1 / l11, zero};
    const Vec3<T> drho[2] = {(eb2 - T(2) * rho * eb1) / l11_sq, eb1 / l11_sq};
    const Vec3<T> dl22[2] = {-rho * p / l22, p / l22};
    for (int m = 0; m < 4; ++m) {
      Vec3<T> g[2];
      for (int s = 0; s < 2; ++s) {
        g[s] = d_param[m][0] * dl11[s] + d_param[m][1] * drho[s] +
               d_param[m][2] * dl22[s];
      }
      Vec3<T>* out = m < 3 ? d_reference[m] : d_area;
      out[1] = g[0];
      out[2] = g[1];
      out[0] = -(g[0] + g[1]);
    }
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_TRIANGLE_DISTORTION_H_
