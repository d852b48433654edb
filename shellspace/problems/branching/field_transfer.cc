#include "shellspace/problems/branching/field_transfer.h"

#include <algorithm>
#include <cmath>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

RelaxedField TransferField(const RelaxedField& from, const RelaxedGrid& to) {
  const RelaxedGrid& g = from.grid;
  if (std::fabs(g.length - to.length) > 1e-12 * g.length ||
      std::fabs(g.height - to.height) > 1e-12 * g.height) {
    throw InputError("branching field transfer: the grids cover different domains");
  }
  RelaxedField out(to);
  const std::vector<double>& xs = g.xs();
  for (int i = 1; i <= to.nx; ++i) {
    const double x = std::min(to.x(i), g.length);
    // The source cell [x_k, x_{k+1}] holding x (k in [0, nx - 1]).
    int k = static_cast<int>(std::upper_bound(xs.begin(), xs.end(), x) -
                             xs.begin()) - 1;
    k = std::clamp(k, 0, g.nx - 1);
    const double a = (x - xs[k]) / (xs[k + 1] - xs[k]);
    for (int j = 0; j < to.ny; ++j) {
      const double t = to.y(j) / g.dy();
      int m = static_cast<int>(std::floor(t));
      const double b = t - m;
      m = ((m % g.ny) + g.ny) % g.ny;
      const int m1 = (m + 1) % g.ny;
      out.at(i, j) = (1.0 - a) * ((1.0 - b) * from.at(k, m) + b * from.at(k, m1)) +
                     a * ((1.0 - b) * from.at(k + 1, m) + b * from.at(k + 1, m1));
    }
  }
  return out;
}

}  // namespace shellspace::branching
