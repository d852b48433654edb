#include "shellspace/models/branching/construction.h"

#include <algorithm>
#include <cmath>

namespace shellspace::branching {

double Construction::PeriodOf(int k) const {
  return h0 * std::pow(static_cast<double>(pattern.r), -k);
}

double Construction::OffsetOf(int k) const {
  double offset = 0.0;
  for (int j = 1; j <= k; ++j) offset += pattern.next_offset * PeriodOf(j);
  return offset;
}

int Construction::GenerationAt(double x, double* s) const {
  if (!lengths.empty()) {
    double right = length;
    const int n = static_cast<int>(lengths.size());
    for (int k = 0; k < n; ++k) {
      const double left = right - lengths[k];
      if (x >= left || k + 1 == n) {
        *s = std::clamp((right - x) / lengths[k], 0.0, 1.0);
        return k;
      }
      right = left;
    }
  }
  double right = length;
  double l = length * (1.0 - theta);
  for (int k = 0; k < max_generations; ++k) {
    const double left = right - l;
    if (x >= left || k + 1 == max_generations) {
      *s = std::clamp((right - x) / l, 0.0, 1.0);
      return k;
    }
    right = left;
    l *= theta;
  }
  *s = 1.0;
  return max_generations - 1;
}

int Construction::VariantAt(double x, double y, double* distance) const {
  double s = 0.0;
  const int k = GenerationAt(x, &s);
  const double h = PeriodOf(k);
  const double eta = (y - OffsetOf(k)) / h;
  const ColumnState column = StateAt(pattern, s);
  double d = 0.0;
  const int variant = branching::VariantAt(column, eta, &d);
  if (distance != nullptr) *distance = d * h;
  return pattern.swap_variants && k % 2 == 1 ? -variant : variant;
}

}  // namespace shellspace::branching
