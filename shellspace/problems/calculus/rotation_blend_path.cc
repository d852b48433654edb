#include "shellspace/problems/calculus/rotation_blend_path.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

#include "shellspace/problems/calculus/ltheta_reconstruction.h"

namespace shellspace {
namespace {

Eigen::Vector3d Row(const Positions& x, int v) { return x.row(v).transpose(); }

// [x_b - x_a, x_c - x_a, n] of face (a, b, c), n the unit normal.
Eigen::Matrix3d TriangleFrame(const Positions& x, int a, int b, int c) {
  Eigen::Matrix3d frame;
  frame.col(0) = Row(x, b) - Row(x, a);
  frame.col(1) = Row(x, c) - Row(x, a);
  const Eigen::Vector3d normal = frame.col(0).cross(frame.col(1));
  const double length = normal.norm();
  frame.col(2) =
      length > 0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
  return frame;
}

// The polar factors of one face's deformation gradient: F = exp([w]x) U.
struct FaceMotion {
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();     // w
  Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();  // U
};

FaceMotion PolarFactors(const Eigen::Matrix3d& from,
                        const Eigen::Matrix3d& to) {
  FaceMotion m;
  const double scale = from.col(0).norm() * from.col(1).norm();
  if (!(std::abs(from.determinant()) > 1e-14 * scale)) return m;
  const Eigen::Matrix3d gradient = to * from.inverse();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      gradient, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  Eigen::Vector3d sigma = svd.singularValues();
  const Eigen::Matrix3d v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0) {  // a reflection: flip the least
    u.col(2) = -u.col(2);
    sigma(2) = -sigma(2);
  }
  const Eigen::AngleAxisd rotation(Eigen::Matrix3d(u * v.transpose()));
  m.rotation = rotation.angle() * rotation.axis();
  m.stretch = v * sigma.asDiagonal() * v.transpose();
  return m;
}

// The representative of the rotation w (w + 2 pi j w / |w|, j = -1, 0, 1)
// nearest to `reference`.
Eigen::Vector3d NearestBranch(const Eigen::Vector3d& w,
                              const Eigen::Vector3d& reference) {
  const double angle = w.norm();
  if (angle == 0) return w;
  Eigen::Vector3d best = w;
  for (int j : {-1, 1}) {
    const Eigen::Vector3d other = w * ((angle + 2 * M_PI * j) / angle);
    if ((other - reference).squaredNorm() < (best - reference).squaredNorm()) {
      best = other;
    }
  }
  return best;
}

// Moves every face's rotation vector onto the branch of its neighbour's,
// breadth first from the least rotated face of each component.
void UnwrapRotations(const Faces& faces, const Topology& topology,
                     std::vector<FaceMotion>* motions) {
  const int num_faces = static_cast<int>(faces.rows());
  std::vector<std::vector<int>> neighbours(num_faces);
  for (const auto& pair : topology.edge_faces) {
    if (pair[1] < 0) continue;
    neighbours[pair[0]].push_back(pair[1]);
    neighbours[pair[1]].push_back(pair[0]);
  }
  std::vector<int> order(num_faces);
  for (int f = 0; f < num_faces; ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return (*motions)[a].rotation.norm() < (*motions)[b].rotation.norm();
  });
  std::vector<char> done(num_faces, 0);
  std::deque<int> queue;
  for (int seed : order) {
    if (done[seed]) continue;
    done[seed] = 1;
    queue.push_back(seed);
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      for (int g : neighbours[f]) {
        if (done[g]) continue;
        done[g] = 1;
        (*motions)[g].rotation =
            NearestBranch((*motions)[g].rotation, (*motions)[f].rotation);
        queue.push_back(g);
      }
    }
  }
}

// The fit of step 3: the shape x minimising
//   sum_f sum_{edges ab of f} |x_b - x_a - F_f (X_b - X_a)|^2 / |X_b - X_a|^2
//   + eps sum_v |x_v - l_v|^2
// for face gradients F_f and anchor positions l (masked vertices held at
// l_v). The matrix depends on X and the mask only: factored once.
class FaceGradientFit {
 public:
  FaceGradientFit(const Faces& faces, const Positions& start,
                  const std::vector<int>& fixed_vertices)
      : start_(start), unknown_(start.rows(), 0) {
    const int n = static_cast<int>(start.rows());
    for (int v : fixed_vertices) unknown_[v] = -1;
    for (int v = 0; v < n; ++v) {
      if (unknown_[v] >= 0) unknown_[v] = m_++;
    }
    // Edge weights 1 / |X_b - X_a|^2, one term per face edge.
    edges_.reserve(3 * faces.rows());
    double weight_sum = 0;
    for (int f = 0; f < faces.rows(); ++f) {
      for (int i = 0; i < 3; ++i) {
        const int a = faces(f, i), b = faces(f, (i + 1) % 3);
        const double length2 = (Row(start, b) - Row(start, a)).squaredNorm();
        const double w = length2 > 0 ? 1 / length2 : 0;
        edges_.push_back({f, a, b, w});
        weight_sum += w;
      }
    }
    eps_ = 1e-9 * weight_sum / std::max<size_t>(1, edges_.size());
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(4 * edges_.size() + m_);
    for (const FaceEdge& e : edges_) {
      const int ia = unknown_[e.a], ib = unknown_[e.b];
      if (ia >= 0) triplets.emplace_back(ia, ia, e.weight);
      if (ib >= 0) triplets.emplace_back(ib, ib, e.weight);
      if (ia >= 0 && ib >= 0) {
        triplets.emplace_back(ia, ib, -e.weight);
        triplets.emplace_back(ib, ia, -e.weight);
      }
    }
    for (int i = 0; i < m_; ++i) triplets.emplace_back(i, i, eps_);
    Eigen::SparseMatrix<double> matrix(m_, m_);
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    factor_.compute(matrix);
  }

  bool ok() const { return factor_.info() == Eigen::Success; }

  // `gradient`: F_f per face; `anchor`: l, #V x 3.
  Positions Solve(const std::vector<Eigen::Matrix3d>& gradient,
                  const Positions& anchor) const {
    const int n = static_cast<int>(start_.rows());
    Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(m_, 3);
    for (const FaceEdge& e : edges_) {
      const Eigen::RowVector3d d =
          e.weight *
          (gradient[e.face] * (Row(start_, e.b) - Row(start_, e.a)))
              .transpose();
      const int ia = unknown_[e.a], ib = unknown_[e.b];
      if (ib >= 0) rhs.row(ib) += d;
      if (ia >= 0) rhs.row(ia) -= d;
      // A masked end moves to the right-hand side at its anchor.
      if (ia >= 0 && ib < 0) rhs.row(ia) += e.weight * anchor.row(e.b);
      if (ib >= 0 && ia < 0) rhs.row(ib) += e.weight * anchor.row(e.a);
    }
    for (int v = 0; v < n; ++v) {
      if (unknown_[v] >= 0) rhs.row(unknown_[v]) += eps_ * anchor.row(v);
    }
    const Eigen::MatrixX3d solved = factor_.solve(rhs);
    Positions shape = anchor;
    for (int v = 0; v < n; ++v) {
      if (unknown_[v] >= 0) shape.row(v) = solved.row(unknown_[v]);
    }
    return shape;
  }

 private:
  struct FaceEdge {
    int face, a, b;
    double weight;
  };
  const Positions& start_;
  std::vector<int> unknown_;  // per vertex: index among the unknowns, or -1
  int m_ = 0;
  std::vector<FaceEdge> edges_;
  double eps_ = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor_;
};

Eigen::Matrix3d RotationMatrix(const Eigen::Vector3d& w, double t) {
  const double angle = w.norm();
  return angle > 0 ? Eigen::AngleAxisd(t * angle, w / angle).toRotationMatrix()
                   : Eigen::Matrix3d::Identity();
}

}  // namespace

std::vector<Positions> RotationBlendShapes(
    const Faces& faces, const Topology& topology, const Positions& start,
    const Positions& end, const std::vector<double>& times,
    const std::vector<int>& fixed_vertices) {
  const int n = static_cast<int>(start.rows());
  const int num_faces = static_cast<int>(faces.rows());
  std::optional<RigidBlendFrame> rigid;
  if (fixed_vertices.empty() && n >= 3) rigid.emplace(start, end);
  const Positions& target = rigid ? rigid->Aligned() : end;

  std::vector<FaceMotion> motions(num_faces);
  for (int f = 0; f < num_faces; ++f) {
    const int a = faces(f, 0), b = faces(f, 1), c = faces(f, 2);
    motions[f] = PolarFactors(TriangleFrame(start, a, b, c),
                              TriangleFrame(target, a, b, c));
  }
  UnwrapRotations(faces, topology, &motions);

  const FaceGradientFit fit(faces, start, fixed_vertices);
  if (!fit.ok()) return {};
  std::vector<Positions> shapes;
  for (const double t : times) {
    const Positions linear = (1 - t) * start + t * target;
    std::vector<Eigen::Matrix3d> gradient(num_faces);
    for (int f = 0; f < num_faces; ++f) {
      gradient[f] = RotationMatrix(motions[f].rotation, t) *
                    ((1 - t) * Eigen::Matrix3d::Identity() +
                     t * motions[f].stretch);
    }
    const Positions shape = fit.Solve(gradient, linear);
    shapes.push_back(rigid ? rigid->Move(shape, t) : shape);
  }
  return shapes;
}

std::vector<Positions> RotationBlendPath(
    const Faces& faces, const Topology& topology, const Positions& start,
    const Positions& end, int steps, const std::vector<int>& fixed_vertices) {
  if (steps < 2) return {start, end};
  std::vector<double> times;
  for (int k = 1; k < steps; ++k)
    times.push_back(static_cast<double>(k) / steps);
  std::vector<Positions> path =
      RotationBlendShapes(faces, topology, start, end, times, fixed_vertices);
  if (path.empty()) return {};
  path.insert(path.begin(), start);
  path.push_back(end);
  return path;
}

std::vector<Eigen::Matrix3d> FaceRotations(const Faces& faces,
                                           const Positions& from,
                                           const Positions& to) {
  std::vector<Eigen::Matrix3d> rotations(faces.rows());
  for (int f = 0; f < faces.rows(); ++f) {
    const int a = faces(f, 0), b = faces(f, 1), c = faces(f, 2);
    rotations[f] = RotationMatrix(
        PolarFactors(TriangleFrame(from, a, b, c), TriangleFrame(to, a, b, c))
            .rotation,
        1.0);
  }
  return rotations;
}

std::vector<Positions> RotationGuidedPath(
    const Faces& faces, const Positions& start, const Positions& end,
    const std::vector<std::vector<Eigen::Matrix3d>>& guide,
    const std::vector<Positions>& anchors,
    const std::vector<int>& fixed_vertices) {
  const int steps = static_cast<int>(guide.size()) - 1;
  const int num_faces = static_cast<int>(faces.rows());
  std::vector<Positions> path(std::max(steps, 1) + 1);
  path.front() = start;
  path.back() = end;
  if (steps < 2) return path;
  // Per face: the stretch U_f of start -> end and the rotation d_f that
  // carries the guide's last rotation G_f(K) onto the face's own, R_f =
  // G_f(K) exp([d_f]x).
  std::vector<FaceMotion> motions(num_faces);
  std::vector<Eigen::Vector3d> residual(num_faces);
  for (int f = 0; f < num_faces; ++f) {
    const int a = faces(f, 0), b = faces(f, 1), c = faces(f, 2);
    motions[f] = PolarFactors(TriangleFrame(start, a, b, c),
                              TriangleFrame(end, a, b, c));
    const Eigen::AngleAxisd d(guide[steps][f].transpose() *
                              RotationMatrix(motions[f].rotation, 1.0));
    residual[f] = d.angle() * d.axis();
  }
  const FaceGradientFit fit(faces, start, fixed_vertices);
  if (!fit.ok()) return {};
  for (int k = 1; k < steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    std::vector<Eigen::Matrix3d> gradient(num_faces);
    for (int f = 0; f < num_faces; ++f) {
      gradient[f] = guide[k][f] * RotationMatrix(residual[f], t) *
                    ((1 - t) * Eigen::Matrix3d::Identity() +
                     t * motions[f].stretch);
    }
    path[k] = fit.Solve(gradient, anchors[k]);
  }
  return path;
}

}  // namespace shellspace
