// The path energy E_K = K sum_k W[s_{k-1}, s_k] of a shell path and its
// gradient with respect to the inner shapes (docs/math.md, "Path energy and
// discrete geodesics").
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_PATH_ENERGY_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_PATH_ENERGY_H_

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/shell_path.h"

namespace shellspace {

// Path energy E_K = K sum_{k=1..K} W[s_{k-1}, s_k] of a path with K + 1
// shapes; fills the per-step energies W[s_{k-1}, s_k] if given.
// Throws InputError naming the element if one W has a degenerate element.
double PathEnergy(const ShellSpace& space, const ShellPath& path,
                  std::vector<double>* step_energies = nullptr);

// The same without exceptions: nullopt if some W[s_{k-1}, s_k] has a
// degenerate element (*failure, if given, names the first, prefixed by the
// step) -- the status for line searches. *step_energies is unspecified then.
std::optional<double> TryPathEnergy(
    const ShellSpace& space, const ShellPath& path,
    std::vector<double>* step_energies = nullptr,
    ElementFailure* failure = nullptr);

// The gradient of E_K with respect to the inner shape k (1 <= k < K; all 3n
// coordinates, vertex-major): G_k = K (D_2 W[s_{k-1}, s_k] +
// D_1 W[s_k, s_{k+1}]). False if either W has a degenerate element.
bool TryInnerShapeGradient(const ShellSpace& space, const ShellPath& path,
                           int k, Eigen::VectorXd* gradient);

// TryInnerShapeGradient for every inner shape k = 1 .. K - 1, with each
// term W[s_k, s_{k+1}] evaluated once for both its shells (TryEnergyGradients),
// the terms and then the calls in parallel (ParallelFor over `threads`):
// calls use(k - 1, G_k) for every inner shape once all gradients exist.
// False (and no call) if an element of any W is degenerate.
bool ForEachInnerShapeGradient(
    const ShellSpace& space, const ShellPath& path, int threads,
    const std::function<void(int, const Eigen::VectorXd&)>& use);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_PATH_ENERGY_H_
