#include "shellspace/problems/statistics/procrustes_pca.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/statistics/shell_pca.h"

namespace shellspace {

ProcrustesPcaModel ComputeProcrustesPca(const std::vector<Positions>& shapes,
                                        int max_iterations) {
  if (shapes.empty()) throw InputError("Procrustes PCA: no shapes");
  for (const Positions& shape : shapes) {
    if (shape.rows() != shapes[0].rows() || !shape.allFinite()) {
      throw InputError("Procrustes PCA: shapes of different sizes or with "
                       "non-finite coordinates");
    }
  }
  const int n = static_cast<int>(shapes.size());
  ProcrustesPcaModel model;
  std::vector<Positions> aligned(n);
  for (int i = 0; i < n; ++i) aligned[i] = AlignRigidly(shapes[i], shapes[0]);
  auto average = [&] {
    Positions sum = Positions::Zero(shapes[0].rows(), 3);
    for (const Positions& a : aligned) sum += a;
    return Positions(sum / n);
  };
  model.mean = average();
  const double size = std::max(model.mean.norm(), 1e-300);
  for (int sweep = 0; sweep < max_iterations; ++sweep) {
    for (int i = 0; i < n; ++i) aligned[i] = AlignRigidly(shapes[i], model.mean);
    const Positions next = AlignRigidly(average(), shapes[0]);
    const double change = (next - model.mean).norm();
    model.mean = next;
    model.iterations = sweep + 1;
    if (change < 1e-12 * size) break;
  }
  for (int i = 0; i < n; ++i) {
    aligned[i] = AlignRigidly(shapes[i], model.mean);
    model.displacements.push_back(aligned[i] - model.mean);
  }
  Eigen::MatrixXd gram(n, n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k <= i; ++k) {
      gram(i, k) = gram(k, i) =
          model.displacements[i].cwiseProduct(model.displacements[k]).sum() / n;
    }
  }
  GramModes modes = ModesFromGram(gram, model.displacements);
  model.eigenvalues = std::move(modes.eigenvalues);
  model.modes = std::move(modes.modes);
  return model;
}

Positions ProcrustesModeShape(const ProcrustesPcaModel& model, int j,
                              double t) {
  if (j < 0 || j >= static_cast<int>(model.modes.size())) {
    throw InputError("Procrustes PCA: mode " + std::to_string(j + 1) +
                     " does not exist (the model has " +
                     std::to_string(model.modes.size()) + ")");
  }
  return model.mean + t * std::sqrt(model.eigenvalues(j)) * model.modes[j];
}

Positions ProcrustesReconstruct(const ProcrustesPcaModel& model,
                                const Positions& shape, int m) {
  if (m < 0 || m > static_cast<int>(model.modes.size())) {
    throw InputError("Procrustes PCA: " + std::to_string(m) +
                     " modes requested, the model has " +
                     std::to_string(model.modes.size()));
  }
  if (shape.rows() != model.mean.rows()) {
    throw InputError("Procrustes PCA: shape of the wrong size");
  }
  const Positions d = AlignRigidly(shape, model.mean) - model.mean;
  Positions result = model.mean;
  for (int j = 0; j < m; ++j) {
    result += d.cwiseProduct(model.modes[j]).sum() * model.modes[j];
  }
  return result;
}

}  // namespace shellspace
