#include "shellspace/cost_functions/shell/psd_projection.h"

#include <Eigen/Eigenvalues>

namespace shellspace {

bool ClampNegativeEigenvalues(Eigen::Ref<Eigen::MatrixXd> m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
  if (eigen.info() != Eigen::Success) return false;
  m = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
      eigen.eigenvectors().transpose();
  return true;
}

}  // namespace shellspace
