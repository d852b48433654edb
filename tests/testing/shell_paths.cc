#include "tests/testing/shell_paths.h"

#include <algorithm>
#include <random>

namespace shellspace::testing {

ShellPath PerturbedLinearPath(const Positions& a, const Positions& b, int K,
                              double amplitude, unsigned seed) {
  ShellPath path = LinearPath(a, b, K);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (int k = 1; k < K; ++k) {
    for (int i = 0; i < path[k].size(); ++i) path[k].data()[i] += u(rng);
  }
  return path;
}

double RelativePathDistance(const ShellPath& a, const ShellPath& b) {
  double distance = 0, size = 0;
  for (size_t k = 0; k < b.size(); ++k) {
    distance = std::max(distance, (a[k] - b[k]).norm());
    size = std::max(size, b[k].norm());
  }
  return distance / size;
}

}  // namespace shellspace::testing
