#include "shellspace/models/branching/cell_pattern.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

ColumnState StateAt(const CellPattern& pattern, double s) {
  struct Entry {
    double position, velocity;
    int jump;
  };
  std::vector<Entry> entries;
  for (const InterfaceCurve& curve : pattern.interfaces) {
    if (s < curve.s_begin || s > curve.s_end) continue;
    double g = curve.position(s);
    g -= std::floor(g);
    entries.push_back({g, curve.velocity(s), curve.jump});
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const Entry& a, const Entry& b) {
                     return a.position < b.position;
                   });
  ColumnState state;
  for (const Entry& e : entries) {
    state.position.push_back(e.position);
    state.velocity.push_back(e.velocity);
    state.jump.push_back(e.jump);
  }
  return state;
}

int VariantAt(const ColumnState& column, double eta, double* distance) {
  const int m = static_cast<int>(column.position.size());
  if (m == 0) throw InputError("branching cell: column without interfaces");
  eta -= std::floor(eta);
  // The last interface below eta (cyclically) decides the variant.
  int below = m - 1;
  for (int i = 0; i < m; ++i) {
    if (column.position[i] <= eta) below = i;
  }
  if (distance != nullptr) {
    double best = 1.0;
    for (double p : column.position) {
      double d = std::fabs(p - eta);
      best = std::min(best, std::min(d, 1.0 - d));
    }
    *distance = best;
  }
  return column.jump[below] > 0 ? 1 : -1;
}

double ColumnVariance(const ColumnState& column) {
  const int m = static_cast<int>(column.position.size());
  // Piece k = [p_k, p_{k+1}) carries F_k = -sum_{i <= k} jump_i v_i; the
  // piece [0, p_0) and the wrapped piece [p_{m-1}, 1) carry F = 0 (the sum
  // over all interfaces vanishes when the volume fraction is conserved).
  double f = 0.0, mean = 0.0, second = 0.0;
  for (int k = 0; k < m; ++k) {
    f -= column.jump[k] * column.velocity[k];
    const double next = k + 1 < m ? column.position[k + 1] : 1.0;
    const double width = next - column.position[k];
    mean += width * f;
    second += width * f * f;
  }
  // Piece [p_{m-1}, 1) used f = F_{m-1} = -sum all; [0, p_0) has F = 0.
  return second - mean * mean;
}

void GaussLegendre01(int points, std::vector<double>* nodes,
                     std::vector<double>* weights) {
  nodes->assign(points, 0.0);
  weights->assign(points, 0.0);
  for (int i = 0; i < points; ++i) {
    // Newton on P_n from the Chebyshev guess.
    double z = std::cos(M_PI * (i + 0.75) / (points + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= points; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = points * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    (*nodes)[i] = 0.5 * (1.0 - z);
    (*weights)[i] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

double ColumnMeanSquare(const ColumnState& column, double anchor) {
  const int m = static_cast<int>(column.position.size());
  anchor -= std::floor(anchor);
  // F on the pieces as in ColumnVariance; F0 = F(anchor).
  double f = 0.0, f0 = 0.0;
  for (int k = 0; k < m; ++k) {
    if (column.position[k] < anchor) f0 -= column.jump[k] * column.velocity[k];
  }
  double second = column.position.empty() ? 0.0 : column.position[0] * f0 * f0;
  for (int k = 0; k < m; ++k) {
    f -= column.jump[k] * column.velocity[k];
    const double next = k + 1 < m ? column.position[k + 1] : 1.0;
    const double width = next - column.position[k];
    second += width * (f - f0) * (f - f0);
  }
  return second;
}

namespace {
template <typename Density>
CellCoefficients Integrate(const CellPattern& pattern, int points,
                           const Density& density) {
  std::vector<double> cuts = {0.0, 1.0};
  for (double b : pattern.breakpoints) {
    if (b > 0.0 && b < 1.0) cuts.push_back(b);
  }
  for (const InterfaceCurve& c : pattern.interfaces) {
    if (c.s_begin > 0.0 && c.s_begin < 1.0) cuts.push_back(c.s_begin);
    if (c.s_end > 0.0 && c.s_end < 1.0) cuts.push_back(c.s_end);
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<double> nodes, weights;
  GaussLegendre01(points, &nodes, &weights);
  CellCoefficients result;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double a = cuts[k], b = cuts[k + 1];
    for (int q = 0; q < points; ++q) {
      const double s = a + (b - a) * nodes[q];
      result.A += (b - a) * weights[q] * density(StateAt(pattern, s));
    }
  }
  for (const InterfaceCurve& c : pattern.interfaces) {
    result.B += 2.0 * (c.s_end - c.s_begin);
  }
  return result;
}
}  // namespace

CellCoefficients EvaluateCell(const CellPattern& pattern, int points) {
  return Integrate(pattern, points,
                   [](const ColumnState& c) { return ColumnVariance(c); });
}

CellCoefficients EvaluateCellZeroAt(const CellPattern& pattern, double anchor,
                                    int points) {
  return Integrate(pattern, points, [anchor](const ColumnState& c) {
    return ColumnMeanSquare(c, anchor);
  });
}

}  // namespace shellspace::branching
