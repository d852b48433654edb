#include "shellspace/geometry/rigid_alignment.h"

#include <Eigen/SVD>

namespace shellspace {

Positions RigidMotion::Apply(const Positions& x) const {
  Positions out = x * rotation.transpose();
  out.rowwise() += translation;
  return out;
}

RigidMotion FitRigidMotion(const Positions& source, const Positions& target) {
  const Eigen::RowVector3d cs = source.colwise().mean();
  const Eigen::RowVector3d ct = target.colwise().mean();
  const Eigen::Matrix3d cov =
      (source.rowwise() - cs).transpose() * (target.rowwise() - ct);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0)
    d(2, 2) = -1;
  RigidMotion motion;
  motion.rotation = svd.matrixV() * d * svd.matrixU().transpose();
  motion.translation = ct - cs * motion.rotation.transpose();
  return motion;
}

Positions AlignRigidly(const Positions& source, const Positions& target) {
  const RigidMotion motion = FitRigidMotion(source, target);
  const Eigen::RowVector3d cs = source.colwise().mean();
  const Eigen::RowVector3d ct = target.colwise().mean();
  // Rotated about the centroid, then moved onto the target's: the same
  // digits as before the motion was a type of its own.
  Positions out = (source.rowwise() - cs) * motion.rotation.transpose();
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
