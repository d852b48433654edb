#include "shellspace/problems/calculus/shell_path.h"

namespace shellspace {

ShellPath LinearPath(const Positions& a, const Positions& b, int steps) {
  ShellPath path;
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    path.push_back((1 - t) * a + t * b);
  }
  return path;
}

}  // namespace shellspace
