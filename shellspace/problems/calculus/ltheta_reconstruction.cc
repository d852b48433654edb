#include "shellspace/problems/calculus/ltheta_reconstruction.h"

#include <ceres/problem.h>

#include <Eigen/Geometry>
#include <cmath>
#include <utility>

#include "shellspace/cost_functions/ltheta_cost_functions.h"
#include "shellspace/geometry/element_geometry.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {
namespace {

Eigen::Vector3d Vertex(const Positions& shape, int v) {
  return shape.row(v).transpose();
}

}  // namespace

RigidBlendFrame::RigidBlendFrame(const Positions& a, const Positions& b) {
  const Eigen::Matrix3Xd a_t = a.transpose(), b_t = b.transpose();
  const Eigen::Matrix4d to_a = Eigen::umeyama(b_t, a_t, false);
  rotation_ = to_a.topLeftCorner<3, 3>();
  const Eigen::Vector3d c = to_a.topRightCorner<3, 1>();
  centroid_a_ = a_t.rowwise().mean();
  centroid_b_ = b_t.rowwise().mean();
  aligned_.resize(b.rows(), 3);
  for (int v = 0; v < b.rows(); ++v) {
    aligned_.row(v) = (rotation_ * Vertex(b, v) + c).transpose();
  }
}

Positions RigidBlendFrame::Move(const Positions& x, double t) const {
  const Eigen::Quaterniond partial = Eigen::Quaterniond::Identity().slerp(
      t, Eigen::Quaterniond(Eigen::Matrix3d(rotation_.transpose())));
  const Eigen::Matrix3d q = partial.toRotationMatrix();
  const Eigen::Vector3d shift = t * (centroid_b_ - centroid_a_);
  Positions moved(x.rows(), 3);
  for (int v = 0; v < x.rows(); ++v) {
    moved.row(v) =
        (q * (Vertex(x, v) - centroid_a_) + centroid_a_ + shift).transpose();
  }
  return moved;
}

Positions BlendRigidly(const Positions& a, const Positions& b, double t) {
  if (t <= 0) return a;
  if (t >= 1) return b;
  const Eigen::Matrix3Xd a_t = a.transpose(), b_t = b.transpose();
  const Eigen::Matrix4d to_a = Eigen::umeyama(b_t, a_t, false);
  const Eigen::Matrix3d r = to_a.topLeftCorner<3, 3>();
  const Eigen::Vector3d c = to_a.topRightCorner<3, 1>();
  const Eigen::Vector3d centroid_a = a_t.rowwise().mean();
  const Eigen::Vector3d centroid_b = b_t.rowwise().mean();
  const Eigen::Quaterniond partial = Eigen::Quaterniond::Identity().slerp(
      t, Eigen::Quaterniond(Eigen::Matrix3d(r.transpose())));
  const Eigen::Matrix3d q = partial.toRotationMatrix();
  const Eigen::Vector3d shift = t * (centroid_b - centroid_a);
  Positions guess(a.rows(), 3);
  for (int v = 0; v < a.rows(); ++v) {
    const Eigen::Vector3d b_aligned = r * Vertex(b, v) + c;
    const Eigen::Vector3d blend = (1 - t) * Vertex(a, v) + t * b_aligned;
    guess.row(v) = (q * (blend - centroid_a) + centroid_a + shift).transpose();
  }
  return guess;
}

LThetaQuantities ComputeLThetaQuantities(const ShellSpace& space,
                                         const Positions& shape) {
  const Topology& topo = space.topology;
  LThetaQuantities q;
  q.lengths.resize(topo.edges.size());
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    q.lengths[e] =
        (Vertex(shape, topo.edges[e][1]) - Vertex(shape, topo.edges[e][0]))
            .norm();
  }
  q.areas.resize(space.faces.rows());
  for (int f = 0; f < space.faces.rows(); ++f) {
    q.areas[f] = TriangleArea<double>(Vertex(shape, space.faces(f, 0)),
                                      Vertex(shape, space.faces(f, 1)),
                                      Vertex(shape, space.faces(f, 2)))
                     .area;
  }
  q.dihedrals.resize(topo.interior_edges.size());
  for (size_t e = 0; e < topo.interior_edges.size(); ++e) {
    const EdgeFlap& flap = topo.interior_edges[e];
    q.dihedrals[e] =
        DihedralAngle<double>(Vertex(shape, flap.i), Vertex(shape, flap.j),
                              Vertex(shape, flap.k), Vertex(shape, flap.l))
            .theta;
  }
  return q;
}

LThetaWeights LThetaResidualWeights(const ShellSpace& space,
                                    const Positions& reference) {
  const LThetaQuantities ref = ComputeLThetaQuantities(space, reference);
  if (!(ref.lengths.size() == 0 || ref.lengths.minCoeff() > 0) ||
      !(ref.areas.size() == 0 || ref.areas.minCoeff() > 0) ||
      !ref.lengths.allFinite() || !ref.areas.allFinite()) {
    throw InputError(
        "LΘA: the reference shape (first keyframe) has a degenerate edge "
        "or triangle");
  }
  LThetaWeights w;
  w.edge = ref.lengths.cwiseInverse();
  w.area = ref.areas.cwiseSqrt().cwiseInverse();
  const double eta = space.material.eta;
  w.dihedral.resize(space.topology.interior_edges.size());
  for (size_t e = 0; e < space.topology.interior_edges.size(); ++e) {
    const EdgeFlap& flap = space.topology.interior_edges[e];
    const double length2 =
        (Vertex(reference, flap.j) - Vertex(reference, flap.i)).squaredNorm();
    w.dihedral[e] = std::sqrt(
        3 * eta * length2 / (ref.areas[flap.face_0] + ref.areas[flap.face_1]));
  }
  return w;
}

Positions ReconstructFromLTheta(const ShellSpace& space,
                                const LThetaQuantities& target,
                                const LThetaWeights& weights,
                                const Positions& initial,
                                const SolverSettings& settings,
                                ceres::Solver::Summary* summary,
                                const std::vector<int>& fixed_vertices) {
  const Topology& topo = space.topology;
  Positions x = initial;
  double* data = x.data();
  ceres::Problem problem;
  for (int v = 0; v < space.num_vertices; ++v) {
    problem.AddParameterBlock(data + 3 * v, 3);
  }
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    problem.AddResidualBlock(
        EdgeLengthCostFunction::Create(target.lengths[e], weights.edge[e]),
        nullptr, data + 3 * topo.edges[e][0], data + 3 * topo.edges[e][1]);
  }
  for (int f = 0; f < space.faces.rows(); ++f) {
    problem.AddResidualBlock(
        TriangleAreaCostFunction::Create(target.areas[f], weights.area[f]),
        nullptr, data + 3 * space.faces(f, 0), data + 3 * space.faces(f, 1),
        data + 3 * space.faces(f, 2));
  }
  if (space.material.eta > 0) {
    for (size_t e = 0; e < topo.interior_edges.size(); ++e) {
      const EdgeFlap& flap = topo.interior_edges[e];
      problem.AddResidualBlock(DihedralAngleCostFunction::Create(
                                   target.dihedrals[e], weights.dihedral[e]),
                               nullptr, data + 3 * flap.i, data + 3 * flap.j,
                               data + 3 * flap.k, data + 3 * flap.l);
    }
  }
  if (fixed_vertices.empty()) {
    PinRigidMotions(&x, &problem);
  } else {
    for (int v : fixed_vertices) problem.SetParameterBlockConstant(data + 3 * v);
  }
  ceres::Solver::Summary result = SolveWithSettings(&problem, settings);
  if (summary != nullptr) *summary = std::move(result);
  return x;
}

}  // namespace shellspace
