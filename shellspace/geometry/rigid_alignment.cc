#include "shellspace/geometry/rigid_alignment.h"

#include <Eigen/SVD>

namespace shellspace {

Positions AlignRigidly(const Positions& source, const Positions& target) {
  const Eigen::RowVector3d cs = source.colwise().mean();
  const Eigen::RowVector3d ct = target.colwise().mean();
  const Eigen::Matrix3d cov =
      (source.rowwise() - cs).transpose() * (target.rowwise() - ct);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0)
    d(2, 2) = -1;
  const Eigen::Matrix3d r = svd.matrixV() * d * svd.matrixU().transpose();
  Positions out = (source.rowwise() - cs) * r.transpose();
  out.rowwise() += ct;
  return out;
}

double RelativeDistanceUpToRigidMotion(const Positions& p, const Positions& q) {
  const Positions aligned = AlignRigidly(p, q);
  const double diameter =
      (q.colwise().maxCoeff() - q.colwise().minCoeff()).norm();
  return (aligned - q).rowwise().norm().maxCoeff() / diameter;
}

}  // namespace shellspace
