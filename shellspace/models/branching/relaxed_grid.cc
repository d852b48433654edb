#include "shellspace/models/branching/relaxed_grid.h"

#include <cmath>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

RelaxedGrid::RelaxedGrid(double length_, double height_, int nx_, int ny_,
                         double grading_)
    : length(length_), height(height_), nx(nx_), ny(ny_), grading(grading_) {
  if (!(length > 0) || !(height > 0)) {
    throw InputError("branching grid: length and height must be positive");
  }
  if (nx < 2 || ny < 8) {
    throw InputError("branching grid: need nx >= 2 and ny >= 8");
  }
  if (!(grading >= 1.0) || grading > 4.0) {
    throw InputError("branching grid: grading must lie in [1, 4]");
  }
  x_.resize(nx + 1);
  for (int i = 0; i <= nx; ++i) {
    x_[i] = length * std::pow(static_cast<double>(i) / nx, grading);
  }
  x_[nx] = length;
}

double RelaxedGrid::wx(int i) const {
  const double left = i == 1 ? 0.0 : 0.5 * (x_[i - 1] + x_[i]);
  const double right = i == nx ? length : 0.5 * (x_[i] + x_[i + 1]);
  return right - left;
}

}  // namespace shellspace::branching
