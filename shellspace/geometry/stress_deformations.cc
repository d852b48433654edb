#include "shellspace/geometry/stress_deformations.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

namespace shellspace {
namespace {

constexpr double kDegree = M_PI / 180.0;

// Knuth's MMIX linear congruential generator; uniform in [0, 1) from the
// top 53 bits.
class Lcg {
 public:
  explicit Lcg(std::uint64_t seed) : state_(seed ^ 0x9E3779B97F4A7C15ull) {}
  double Uniform() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state_ >> 11) * 0x1.0p-53;
  }
  // A unit vector, uniform on the sphere.
  Eigen::Vector3d Direction() {
    const double z = 2 * Uniform() - 1;
    const double phi = 2 * M_PI * Uniform();
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  std::uint64_t state_;
};

double Diagonal(const Positions& shape) {
  return (shape.colwise().maxCoeff() - shape.colwise().minCoeff()).norm();
}

}  // namespace

PrincipalFrame ComputePrincipalFrame(const Positions& shape) {
  PrincipalFrame frame;
  frame.centroid = shape.colwise().mean().transpose();
  const Eigen::MatrixX3d centred =
      shape.rowwise() - frame.centroid.transpose();
  const Eigen::Matrix3d covariance = centred.transpose() * centred;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  // Eigenvalues ascending: the longest axis is the last.
  frame.axes.col(0) = eigen.eigenvectors().col(2);
  frame.axes.col(1) = eigen.eigenvectors().col(1);
  frame.axes.col(2) = frame.axes.col(0).cross(frame.axes.col(1));
  const Eigen::VectorXd s = centred * frame.axes.col(0);
  frame.s_min = s.size() ? s.minCoeff() : 0.0;
  frame.s_max = s.size() ? s.maxCoeff() : 0.0;
  return frame;
}

Positions BendAlongLongestAxis(const Positions& shape, double degrees) {
  const PrincipalFrame f = ComputePrincipalFrame(shape);
  const double theta = degrees * kDegree;
  const double length = f.s_max - f.s_min;
  if (!(std::abs(theta) > 0) || !(length > 0)) return shape;
  const double radius = length / theta;
  const double middle = 0.5 * (f.s_min + f.s_max);
  Positions bent(shape.rows(), 3);
  for (int v = 0; v < shape.rows(); ++v) {
    const Eigen::Vector3d local =
        f.axes.transpose() * (shape.row(v).transpose() - f.centroid);
    const double s = local[0] - middle, u = local[1], w = local[2];
    const double phi = theta * s / length;
    const Eigen::Vector3d moved = (radius - u) * std::sin(phi) * f.axes.col(0) +
                                  (radius - (radius - u) * std::cos(phi)) *
                                      f.axes.col(1) +
                                  w * f.axes.col(2);
    bent.row(v) = (f.centroid + middle * f.axes.col(0) + moved).transpose();
  }
  return bent;
}

Positions TwistAboutLongestAxis(const Positions& shape, double degrees) {
  const PrincipalFrame f = ComputePrincipalFrame(shape);
  const double length = f.s_max - f.s_min;
  if (!(length > 0)) return shape;
  Positions twisted(shape.rows(), 3);
  for (int v = 0; v < shape.rows(); ++v) {
    const Eigen::Vector3d x = shape.row(v).transpose() - f.centroid;
    const double s = x.dot(f.axes.col(0));
    const double angle = degrees * kDegree * (s - f.s_min) / length;
    twisted.row(v) =
        (f.centroid + Eigen::AngleAxisd(angle, f.axes.col(0)) * x).transpose();
  }
  return twisted;
}

Positions LocalPull(const Positions& shape, double strength) {
  const PrincipalFrame f = ComputePrincipalFrame(shape);
  const double diagonal = Diagonal(shape);
  int top = 0;
  for (int v = 1; v < shape.rows(); ++v) {
    if (shape.row(v).dot(f.axes.col(1).transpose()) >
        shape.row(top).dot(f.axes.col(1).transpose())) {
      top = v;
    }
  }
  const Eigen::RowVector3d p = shape.row(top);
  const double sigma = diagonal / 8;
  Positions pulled = shape;
  for (int v = 0; v < shape.rows(); ++v) {
    const double r2 = (shape.row(v) - p).squaredNorm();
    pulled.row(v) += strength * diagonal *
                     std::exp(-r2 / (2 * sigma * sigma)) *
                     f.axes.col(1).transpose();
  }
  return pulled;
}

Positions RandomRigidMotion(const Positions& shape, double degrees,
                            std::uint64_t seed) {
  Lcg random(seed);
  const Eigen::Vector3d axis = random.Direction();
  const Eigen::Vector3d translation = 0.25 * Diagonal(shape) *
                                      random.Direction();
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(degrees * kDegree, axis).toRotationMatrix();
  const Eigen::RowVector3d c = shape.colwise().mean();
  Positions moved(shape.rows(), 3);
  for (int v = 0; v < shape.rows(); ++v) {
    moved.row(v) = (rotation * (shape.row(v) - c).transpose()).transpose() +
                   c + translation.transpose();
  }
  return moved;
}

Positions DeformForCorpus(const Positions& shape, const std::string& kind,
                          double strength, bool with_rigid_motion,
                          std::uint64_t seed) {
  Positions deformed;
  if (kind == "none") return shape;
  if (kind == "bend") {
    deformed = BendAlongLongestAxis(shape, strength);
  } else if (kind == "twist") {
    deformed = TwistAboutLongestAxis(shape, strength);
  } else if (kind == "pull") {
    deformed = LocalPull(shape, strength);
  } else if (kind == "rigid") {
    return RandomRigidMotion(shape, strength, seed);
  } else {
    throw InputError("deformation must be none, bend, twist, pull or rigid, got '" +
                     kind + "'");
  }
  return with_rigid_motion ? RandomRigidMotion(deformed, 30, seed) : deformed;
}

}  // namespace shellspace
