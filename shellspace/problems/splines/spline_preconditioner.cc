#include "shellspace/problems/splines/spline_preconditioner.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/runtime/parallel_for.h"

namespace shellspace {

struct SplinePreconditioner::SpaceFactor {
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> llt;
};

SplinePreconditioner::SplinePreconditioner(const ShellSpace& space,
                                           const SplineSpec& spec,
                                           double regularization,
                                           int threads) {
  const int K = spec.steps;
  const int shapes = static_cast<int>(spec.initial.size());
  std::vector<int> column(shapes, -1);  // free shape -> column of A
  for (int k = 0; k < shapes; ++k) {
    if (spec.is_free[k]) column[k] = free_++;
  }
  block_ = 3 * space.num_vertices;
  size_ = free_ * block_;
  if (free_ == 0) return;

  // A = E + sigma K^3 D^T D on the free shapes.
  a_ = Eigen::MatrixXd::Zero(free_, free_);
  for (const SplineDatum& d : spec.data) {
    if (column[d.index] >= 0) a_(column[d.index], column[d.index]) += 1;
  }
  const double weight = spec.sigma * double(K) * K * K;
  const int first = spec.periodic ? 0 : 1, last = spec.periodic ? K : K - 1;
  for (int k = first; k < last; ++k) {
    const int idx[3] = {(k - 1 + shapes) % shapes, k, (k + 1) % shapes};
    const double coef[3] = {1, -2, 1};
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        if (column[idx[p]] < 0 || column[idx[q]] < 0) continue;
        a_(column[idx[p]], column[idx[q]]) += weight * coef[p] * coef[q];
      }
    }
  }
  const double a_ridge = regularization * a_.diagonal().maxCoeff();
  a_.diagonal().array() += std::max(a_ridge, 1e-300);
  l_a_ = Eigen::LLT<Eigen::MatrixXd>(a_).matrixL();

  // The free shapes' factors, independent of each other: in parallel.
  std::vector<int> free_shapes;
  for (int k = 0; k < shapes; ++k) {
    if (column[k] >= 0) free_shapes.push_back(k);
  }
  space_factors_.resize(free_shapes.size());
  std::vector<char> positive(free_shapes.size(), 0);
  ParallelFor(static_cast<int>(free_shapes.size()), threads, [&](int i) {
    const Positions& s = spec.initial[free_shapes[i]];
    SparseMatrix g =
        EnergyHessian(space, s, s, ShellSide::kDeformed, ShellSide::kDeformed);
    SparseMatrix identity(block_, block_);
    identity.setIdentity();
    g += regularization * g.diagonal().mean() * identity;
    space_factors_[i] = std::make_unique<SpaceFactor>();
    space_factors_[i]->llt.compute(g);
    positive[i] = space_factors_[i]->llt.info() == Eigen::Success;
  });
  for (size_t i = 0; i < free_shapes.size(); ++i) {
    if (!positive[i]) {
      throw InputError("spline preconditioner: the metric at shape " +
                       std::to_string(free_shapes[i]) +
                       " is not positive definite");
    }
  }
}

SplinePreconditioner::~SplinePreconditioner() = default;

// With Y the block_ x free_ matrix of y (one column per free shape):
// column i of T y is B_i^-T (Y L_A^-1)_i, and T^T g = [B_i^-1 g_i] L_A^-T.
void SplinePreconditioner::Apply(const double* y, double* dx) const {
  if (free_ == 0) return;
  Eigen::Map<const Eigen::MatrixXd> ym(y, block_, free_);
  // Z = Y L_A^-1: solve Z L_A = Y, i.e. L_A^T Z^T = Y^T.
  const Eigen::MatrixXd z =
      l_a_.transpose().triangularView<Eigen::Upper>().solve(ym.transpose())
          .transpose();
  Eigen::Map<Eigen::MatrixXd> out(dx, block_, free_);
  // B = P^T L (P G P^T = L L^T): B^-T z = P^T L^-T z.
  for (int c = 0; c < free_; ++c) {
    const auto& llt = space_factors_[c]->llt;
    const Eigen::VectorXd w = llt.matrixU().solve(Eigen::VectorXd(z.col(c)));
    out.col(c) = llt.permutationPinv() * w;
  }
}

void SplinePreconditioner::ApplyTransposed(const double* gx,
                                           double* gy) const {
  if (free_ == 0) return;
  Eigen::Map<const Eigen::MatrixXd> gm(gx, block_, free_);
  Eigen::MatrixXd w(block_, free_);
  // B^-1 g = L^-1 P g.
  for (int c = 0; c < free_; ++c) {
    const auto& llt = space_factors_[c]->llt;
    w.col(c) = llt.matrixL().solve(Eigen::VectorXd(llt.permutationP() *
                                                   Eigen::VectorXd(gm.col(c))));
  }
  // W L_A^-T: solve X L_A^T = W, i.e. L_A X^T = W^T.
  Eigen::Map<Eigen::MatrixXd>(gy, block_, free_) =
      l_a_.triangularView<Eigen::Lower>().solve(w.transpose()).transpose();
}

}  // namespace shellspace
