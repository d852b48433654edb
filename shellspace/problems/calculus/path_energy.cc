#include "shellspace/problems/calculus/path_energy.h"

#include <algorithm>
#include <string>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/runtime/parallel_for.h"

namespace shellspace {

std::optional<double> TryPathEnergy(const ShellSpace& space,
                                    const ShellPath& path,
                                    std::vector<double>* step_energies,
                                    ElementFailure* failure) {
  const int steps = static_cast<int>(path.size()) - 1;
  double sum = 0;
  if (step_energies) step_energies->clear();
  for (int k = 1; k <= steps; ++k) {
    DeformationEnergy w;
    if (!TryEvaluateDeformationEnergy(space, path[k - 1], path[k], &w,
                                      failure)) {
      if (failure) {
        failure->description = "W[s_" + std::to_string(k - 1) + ", s_" +
                               std::to_string(k) + "]: " +
                               failure->description;
      }
      return std::nullopt;
    }
    if (step_energies) step_energies->push_back(w.total);
    sum += w.total;
  }
  return steps * sum;
}

double PathEnergy(const ShellSpace& space, const ShellPath& path,
                  std::vector<double>* step_energies) {
  ElementFailure failure;
  const std::optional<double> energy =
      TryPathEnergy(space, path, step_energies, &failure);
  if (!energy) {
    throw InputError("path energy: " + failure.description + " is degenerate");
  }
  return *energy;
}

bool TryInnerShapeGradient(const ShellSpace& space, const ShellPath& path,
                           int k, Eigen::VectorXd* gradient) {
  const int K = static_cast<int>(path.size()) - 1;
  Eigen::VectorXd incoming, outgoing;
  if (!TryEnergyGradient(space, path[k - 1], path[k], ShellSide::kDeformed,
                         &incoming) ||
      !TryEnergyGradient(space, path[k], path[k + 1], ShellSide::kReference,
                         &outgoing)) {
    return false;
  }
  *gradient = double(K) * (incoming + outgoing);
  return true;
}

bool ForEachInnerShapeGradient(
    const ShellSpace& space, const ShellPath& path, int threads,
    const std::function<void(int, const Eigen::VectorXd&)>& use) {
  const int K = static_cast<int>(path.size()) - 1;
  if (K < 2) return true;
  // Term by term, W[s_k, s_{k+1}] once for both of its inner shapes (the
  // ends need no gradient): K element passes instead of 2 (K - 1), the
  // same digits as TryInnerShapeGradient.
  std::vector<Eigen::VectorXd> of_reference(K), of_deformed(K);
  std::vector<char> ok(K, 1);
  ParallelFor(K, threads, [&](int k) {
    ok[k] = TryEnergyGradients(space, path[k], path[k + 1],
                               k > 0 ? &of_reference[k] : nullptr,
                               k + 1 < K ? &of_deformed[k] : nullptr);
  });
  if (!std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; })) {
    return false;
  }
  ParallelFor(K - 1, threads, [&](int i) {
    use(i, double(K) * (of_deformed[i] + of_reference[i + 1]));
  });
  return true;
}

}  // namespace shellspace
