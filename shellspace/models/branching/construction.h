// A self-similar branching construction on (0, L) x [0, H): a cell pattern
// (problems/branching/km_family.h, lens_family.h) repeated over generations
// k = 0, 1, ... with period h_k = h0 r^-k on x in [x_{k+1}, x_k], x_0 = L,
// x_{k+1} = x_k - l_k, l_k = L (1 - theta) theta^k (generation 0 farthest
// from the austenite at x = 0). Generation k's period starts at y = offset_k, offset_0 = 0,
// offset_{k+1} = offset_k + next_offset h_{k+1}.
#ifndef SHELLSPACE_MODELS_BRANCHING_CONSTRUCTION_H_
#define SHELLSPACE_MODELS_BRANCHING_CONSTRUCTION_H_

#include <string>
#include <vector>

#include "shellspace/models/branching/cell_pattern.h"

namespace shellspace::branching {

struct Construction {
  CellPattern pattern;
  double length = 1.0;  // L
  double h0 = 0.25;     // first (coarsest) period
  double theta = 0.3;   // length ratio l_{k+1} / l_k
  int max_generations = 60;
  // Free generation lengths l_0, l_1, ... (OptimalFreeLengths,
  // problems/branching/self_similar_series.h); when non-empty they replace
  // theta.
  std::vector<double> lengths;

  // u_y (+-1) at (x, y), and optionally the y-distance to the nearest
  // interface of that column (for smoothing to a diffuse profile).
  int VariantAt(double x, double y, double* distance = nullptr) const;
  // Generation index and cell coordinate s of x in (0, L].
  int GenerationAt(double x, double* s) const;
  double PeriodOf(int k) const;
  double OffsetOf(int k) const;
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_MODELS_BRANCHING_CONSTRUCTION_H_
