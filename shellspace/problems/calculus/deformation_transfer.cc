#include "shellspace/problems/calculus/deformation_transfer.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace shellspace {

namespace {

// Squared distance from p to the triangle (a, b, c) (Ericson's region tests).
double PointTriangleDistanceSquared(const Eigen::Vector3d& p,
                                    const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return (p - (a + v * ab)).squaredNorm();
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return (p - (a + w * ac)).squaredNorm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (p - (b + w * (c - b))).squaredNorm();
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return (p - (a + ab * v + ac * w)).squaredNorm();
}

// [e1 e2 n] of a triangle (unit normal n).
Eigen::Matrix3d FaceFrame(const Positions& x, const Faces& faces, int f) {
  const Eigen::Vector3d x0 = x.row(faces(f, 0)).transpose();
  const Eigen::Vector3d e1 = x.row(faces(f, 1)).transpose() - x0;
  const Eigen::Vector3d e2 = x.row(faces(f, 2)).transpose() - x0;
  Eigen::Matrix3d frame;
  frame << e1, e2, e1.cross(e2).normalized();
  return frame;
}

// A uniform grid over points, for nearest-point queries.
class PointGrid {
 public:
  PointGrid(const Positions& points) : points_(points) {
    lower_ = points.colwise().minCoeff().transpose();
    const Eigen::Vector3d upper = points.colwise().maxCoeff().transpose();
    const double extent = std::max((upper - lower_).maxCoeff(), 1e-300);
    const double cells = std::max(1.0, std::cbrt(double(points.rows())));
    cell_ = extent / cells;
    for (int i = 0; i < points.rows(); ++i) cells_[Key(Cell(points.row(i)))].push_back(i);
  }
  // The index of the nearest point to p.
  int Nearest(const Eigen::Vector3d& p) const {
    const Eigen::Vector3i c = Cell(p.transpose());
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (int radius = 0; ; ++radius) {
      for (int dx = -radius; dx <= radius; ++dx)
        for (int dy = -radius; dy <= radius; ++dy)
          for (int dz = -radius; dz <= radius; ++dz) {
            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != radius) continue;
            auto it = cells_.find(Key(c + Eigen::Vector3i(dx, dy, dz)));
            if (it == cells_.end()) continue;
            for (int i : it->second) {
              const double d = (points_.row(i).transpose() - p).squaredNorm();
              if (d < best_d) { best_d = d; best = i; }
            }
          }
      // Every point within radius * cell_ of p has been seen.
      if (best >= 0 && std::sqrt(best_d) <= radius * cell_) return best;
      if (radius > 4 * static_cast<int>(cells_.size()) + 8) return best;
    }
  }

 private:
  Eigen::Vector3i Cell(const Eigen::RowVector3d& p) const {
    return ((p.transpose() - lower_) / cell_).array().floor().cast<int>();
  }
  static long long Key(const Eigen::Vector3i& c) {
    return (static_cast<long long>(c(0)) * 1000003LL + c(1)) * 1000033LL + c(2);
  }
  const Positions& points_;
  Eigen::Vector3d lower_;
  double cell_ = 1;
  std::unordered_map<long long, std::vector<int>> cells_;
};

}  // namespace

struct Prolongation::Solver {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::SparseMatrix<double> coupling;  // free rows x survivor columns
  std::vector<double> face_weight;       // a_f of the fine reference
};

namespace {

// For each fine face, the coarse face nearest its centroid among those
// around the coarse vertex nearest it and their neighbours (all in the
// reference shapes).
std::vector<int> NearestCoarseFaces(const Faces& fine_faces,
                                    const Positions& fine_reference,
                                    const Faces& coarse_faces,
                                    const Positions& coarse_reference) {
  // Coarse faces around each coarse vertex.
  std::vector<std::vector<int>> faces_of(coarse_reference.rows());
  for (int t = 0; t < coarse_faces.rows(); ++t) {
    for (int c = 0; c < 3; ++c) faces_of[coarse_faces(t, c)].push_back(t);
  }
  // Fine face -> coarse face: the nearest coarse triangle to the fine
  // centroid among those around the nearest survivor and its coarse
  // neighbours.
  const PointGrid grid(coarse_reference);
  std::vector<int> coarse_face_of(fine_faces.rows(), 0);
  for (int f = 0; f < fine_faces.rows(); ++f) {
    const Eigen::Vector3d centroid =
        (fine_reference.row(fine_faces(f, 0)) + fine_reference.row(fine_faces(f, 1)) +
         fine_reference.row(fine_faces(f, 2))).transpose() / 3.0;
    const int near = grid.Nearest(centroid);
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> candidates;
    for (int t : faces_of[near]) {
      for (int c = 0; c < 3; ++c) {
        for (int u : faces_of[coarse_faces(t, c)]) candidates.push_back(u);
      }
    }
    for (int t : candidates) {
      const double d = PointTriangleDistanceSquared(
          centroid, coarse_reference.row(coarse_faces(t, 0)).transpose(),
          coarse_reference.row(coarse_faces(t, 1)).transpose(),
          coarse_reference.row(coarse_faces(t, 2)).transpose());
      if (d < best) {
        best = d;
        coarse_face_of[f] = t;
      }
    }
  }
  return coarse_face_of;
}

}  // namespace

Prolongation::Prolongation(const Faces& fine_faces,
                           const Positions& fine_reference,
                           const SharedDecimation& level,
                           const Positions& coarse_reference)
    : fine_faces_(fine_faces),
      fine_reference_(fine_reference),
      coarse_faces_(level.faces),
      coarse_reference_(coarse_reference),
      survivors_(level.survivors),
      solver_(std::make_unique<Solver>()) {
  const int n = static_cast<int>(fine_reference.rows());
  const int nc = level.num_vertices();
  if (coarse_reference.rows() != nc) {
    throw InputError("prolongation: the coarse reference has " +
                     std::to_string(coarse_reference.rows()) +
                     " vertices, the coarse level " + std::to_string(nc));
  }
  coarse_face_of_ = NearestCoarseFaces(fine_faces, fine_reference,
                                       coarse_faces_, coarse_reference_);
  // The weighted edge Laplacian, split into free and anchored vertices.
  free_index_.assign(n, 0);
  for (int v : survivors_) free_index_[v] = -1;
  int num_free = 0;
  for (int v = 0; v < n; ++v) {
    if (free_index_[v] >= 0) free_index_[v] = num_free++;
  }
  std::vector<int> anchor_index(n, -1);
  for (int i = 0; i < nc; ++i) anchor_index[survivors_[i]] = i;
  std::vector<Eigen::Triplet<double>> free_free, free_anchor;
  solver_->face_weight.resize(fine_faces.rows());
  for (int f = 0; f < fine_faces.rows(); ++f) {
    const Eigen::Vector3d e1 = (fine_reference.row(fine_faces(f, 1)) -
                                fine_reference.row(fine_faces(f, 0))).transpose();
    const Eigen::Vector3d e2 = (fine_reference.row(fine_faces(f, 2)) -
                                fine_reference.row(fine_faces(f, 0))).transpose();
    const double a = 0.5 * e1.cross(e2).norm();
    solver_->face_weight[f] = a;
    for (int c = 0; c < 3; ++c) {
      const int i = fine_faces(f, c), j = fine_faces(f, (c + 1) % 3);
      for (auto [p, q] : {std::pair<int, int>{i, j}, std::pair<int, int>{j, i}}) {
        if (free_index_[p] < 0) continue;
        free_free.emplace_back(free_index_[p], free_index_[p], a);
        if (free_index_[q] >= 0) {
          free_free.emplace_back(free_index_[p], free_index_[q], -a);
        } else {
          free_anchor.emplace_back(free_index_[p], anchor_index[q], -a);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> laplacian(num_free, num_free);
  laplacian.setFromTriplets(free_free.begin(), free_free.end());
  solver_->coupling.resize(num_free, nc);
  solver_->coupling.setFromTriplets(free_anchor.begin(), free_anchor.end());
  if (num_free > 0) {
    solver_->ldlt.compute(laplacian);
    if (solver_->ldlt.info() != Eigen::Success) {
      throw InputError(
          "prolongation: a part of the fine mesh has no surviving vertex");
    }
  }
}

Prolongation::~Prolongation() = default;

Positions Prolongation::Apply(const Positions& coarse_deformed) const {
  const int n = static_cast<int>(fine_reference_.rows());
  const int nc = static_cast<int>(survivors_.size());
  if (coarse_deformed.rows() != nc) {
    throw InputError("prolongation: the coarse shape has " +
                     std::to_string(coarse_deformed.rows()) +
                     " vertices, the coarse level " + std::to_string(nc));
  }
  std::vector<Eigen::Matrix3d> gradient(coarse_faces_.rows());
  for (int t = 0; t < coarse_faces_.rows(); ++t) {
    gradient[t] = FaceFrame(coarse_deformed, coarse_faces_, t) *
                  FaceFrame(coarse_reference_, coarse_faces_, t).inverse();
  }
  const int num_free = static_cast<int>(solver_->coupling.rows());
  // Right-hand side: sum over the edges of a_f D_T(f) (X_p - X_q) at p.
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(num_free, 3);
  for (int f = 0; f < fine_faces_.rows(); ++f) {
    const Eigen::Matrix3d& d = gradient[coarse_face_of_[f]];
    const double a = solver_->face_weight[f];
    for (int c = 0; c < 3; ++c) {
      const int i = fine_faces_(f, c), j = fine_faces_(f, (c + 1) % 3);
      const Eigen::Vector3d target =
          d * (fine_reference_.row(i) - fine_reference_.row(j)).transpose();
      if (free_index_[i] >= 0) rhs.row(free_index_[i]) += a * target.transpose();
      if (free_index_[j] >= 0) rhs.row(free_index_[j]) -= a * target.transpose();
    }
  }
  const Eigen::MatrixXd anchors = coarse_deformed;
  rhs -= solver_->coupling * anchors;
  Positions fine(n, 3);
  for (int i = 0; i < nc; ++i) fine.row(survivors_[i]) = coarse_deformed.row(i);
  if (num_free > 0) {
    const Eigen::MatrixXd x = solver_->ldlt.solve(rhs);
    for (int v = 0; v < n; ++v) {
      if (free_index_[v] >= 0) fine.row(v) = x.row(free_index_[v]);
    }
  }
  return fine;
}

}  // namespace shellspace
