#include "shellspace/models/branching/lens_family.h"

#include <cmath>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

void CheckLensShape(const LensShape& shape) {
  if (!(shape.tau >= 0.0 && shape.tau <= kLensTauMax) ||
      !(std::fabs(shape.a1) <= kLensCurvatureMax) ||
      !(std::fabs(shape.a2) <= kLensCurvatureMax)) {
    throw InputError("lens shape out of bounds: need 0 <= tau <= " +
                     std::to_string(kLensTauMax) + ", |a1|, |a2| <= " +
                     std::to_string(kLensCurvatureMax));
  }
}

LensProfile EvaluateLensProfile(const LensShape& shape, double t) {
  LensProfile p;
  const double u = 1.0 - t;
  p.phi = t + shape.a1 * t * u + shape.a2 * t * t * u;
  p.phi_t = 1.0 + shape.a1 * (1.0 - 2.0 * t) + shape.a2 * (2.0 * t - 3.0 * t * t);
  p.dphi_da1 = t * u;
  p.dphi_da2 = t * t * u;
  p.dphit_da1 = 1.0 - 2.0 * t;
  p.dphit_da2 = 2.0 * t - 3.0 * t * t;
  return p;
}

CellPattern LensCellPattern(const LensShape& shape) {
  CheckLensShape(shape);
  CellPattern pattern;
  pattern.family = "lens";
  pattern.r = kLensRatio;
  pattern.next_offset = 0.5;
  const double tau = shape.tau;
  auto line = [](double at, int jump) {
    InterfaceCurve c;
    c.jump = jump;
    c.position = [at](double) { return at; };
    c.velocity = [](double) { return 0.0; };
    return c;
  };
  pattern.interfaces = {line(0.25, 2), line(0.75, -2)};
  // Needle flank: center + side * W(s) / 2.
  auto flank = [shape, tau](double center, double side, int jump) {
    InterfaceCurve c;
    c.jump = jump;
    c.s_begin = tau;
    c.s_end = 1.0;
    c.position = [=](double s) {
      const double t = (s - tau) / (1.0 - tau);
      return center + side * EvaluateLensProfile(shape, t).phi / 12.0;
    };
    c.velocity = [=](double s) {
      const double t = (s - tau) / (1.0 - tau);
      return side * EvaluateLensProfile(shape, t).phi_t / (12.0 * (1.0 - tau));
    };
    return c;
  };
  pattern.interfaces.push_back(flank(0.5, -1.0, -2));
  pattern.interfaces.push_back(flank(0.5, 1.0, 2));
  pattern.interfaces.push_back(flank(1.0, -1.0, 2));
  pattern.interfaces.push_back(flank(0.0, 1.0, -2));
  pattern.breakpoints = {tau};
  return pattern;
}

double LensReducedA(const LensShape& shape, double dA[3]) {
  static const int kPoints = 8;
  std::vector<double> nodes, weights;
  GaussLegendre01(kPoints, &nodes, &weights);
  double J = 0.0, dJ1 = 0.0, dJ2 = 0.0;
  for (int q = 0; q < kPoints; ++q) {
    const LensProfile p = EvaluateLensProfile(shape, nodes[q]);
    const double well = 1.0 - p.phi / 3.0;
    const double rate2 = p.phi_t * p.phi_t / 36.0;
    J += weights[q] * well * rate2;
    dJ1 += weights[q] * (-p.dphi_da1 / 3.0 * rate2 +
                         well * p.phi_t * p.dphit_da1 / 18.0);
    dJ2 += weights[q] * (-p.dphi_da2 / 3.0 * rate2 +
                         well * p.phi_t * p.dphit_da2 / 18.0);
  }
  const double inv = 1.0 / (1.0 - shape.tau);
  if (dA != nullptr) {
    dA[0] = J * inv * inv;
    dA[1] = dJ1 * inv;
    dA[2] = dJ2 * inv;
  }
  return J * inv;
}

double LensReducedB(const LensShape& shape, double* dB) {
  if (dB != nullptr) *dB = -8.0;
  return 12.0 - 8.0 * shape.tau;
}

}  // namespace shellspace::branching
