#include "shellspace/geometry/rigid_alignment.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace shellspace {

Positions RigidMotion::Apply(const Positions& x) const {
  Positions out = x * rotation.transpose();
  out.rowwise() += translation;
  return out;
}

RigidMotion RigidMotion::Fraction(double tau,
                                  const Eigen::RowVector3d& centre) const {
  const Eigen::AngleAxisd whole(rotation);
  RigidMotion part;
  part.rotation = Eigen::AngleAxisd(tau * whole.angle(), whole.axis())
                      .toRotationMatrix();
  const Eigen::RowVector3d moved_centre =
      centre * rotation.transpose() + translation;
  // x -> R_tau x + (c - R_tau c) + tau (moved_centre - c)
  part.translation = centre - centre * part.rotation.transpose() +
                     tau * (moved_centre - centre);
  return part;
}

RigidMotion RigidMotion::Inverse() const {
  RigidMotion inverse;
  inverse.rotation = rotation.transpose();
  inverse.translation = -translation * rotation;
  return inverse;
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

Positions ComponentwiseRigidMotion::Apply(const Positions& x) const {
  Positions out = x;
  for (size_t g = 0; g < groups.size(); ++g) {
    for (const int v : groups[g]) {
      out.row(v) = x.row(v) * motions[g].rotation.transpose() +
                   motions[g].translation;
    }
  }
  return out;
}

ComponentwiseRigidMotion FitRigidMotions(
    const Positions& source, const Positions& target,
    const std::vector<std::vector<int>>& groups) {
  ComponentwiseRigidMotion fitted{groups, {}};
  for (const std::vector<int>& group : groups) {
    Positions p(group.size(), 3), q(group.size(), 3);
    for (size_t i = 0; i < group.size(); ++i) {
      p.row(i) = source.row(group[i]);
      q.row(i) = target.row(group[i]);
    }
    fitted.motions.push_back(FitRigidMotion(p, q));
  }
  return fitted;
}

double RelativeDistanceUpToRigidMotion(const Positions& p, const Positions& q) {
  const Positions aligned = AlignRigidly(p, q);
  const double diameter =
      (q.colwise().maxCoeff() - q.colwise().minCoeff()).norm();
  return (aligned - q).rowwise().norm().maxCoeff() / diameter;
}

}  // namespace shellspace
