#include "shellspace/solvers/reusable_cholesky.h"

#include <Eigen/CholmodSupport>
#include <chrono>

#include "shellspace/solvers/space_time_ordering.h"

namespace shellspace {

namespace {
// Wall clock for the report counters only.
double Since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}
}  // namespace

struct ReusableCholesky::Factor {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation;
};

ReusableCholesky::ReusableCholesky() : factor_(std::make_unique<Factor>()) {
  // The permutation is ours (SpaceTimeOrdering); CHOLMOD only postorders.
  factor_->llt.cholmod().nmethods = 1;
  factor_->llt.cholmod().method[0].ordering = CHOLMOD_NATURAL;
  factor_->llt.cholmod().postorder = 1;
  // An indefinite H is an answer (Solve returns false), not a warning.
  factor_->llt.cholmod().print = 0;
}

ReusableCholesky::~ReusableCholesky() = default;

bool ReusableCholesky::Factorize(const Eigen::SparseMatrix<double>& lower,
                                 const std::vector<int>& vertex_of,
                                 int num_vertices) {
  const auto start = std::chrono::steady_clock::now();
  factor_->permutation = SpaceTimeOrdering(lower, vertex_of, num_vertices);
  Eigen::SparseMatrix<double> permuted(lower.rows(), lower.cols());
  permuted.selfadjointView<Eigen::Lower>() =
      lower.selfadjointView<Eigen::Lower>().twistedBy(factor_->permutation);
  factor_->llt.compute(permuted);
  factorized_ = factor_->llt.info() == Eigen::Success;
  ++stats_.factorizations;
  // Set by cholmod_analyze for the ordering used (ours, postordered).
  last_factorization_flops_ = factor_->llt.cholmod().fl;
  factor_nonzeros_ = factor_->llt.cholmod().lnz;
  stats_.factorization_seconds += Since(start);
  return factorized_;
}

bool ReusableCholesky::Solve(const LinearSystem& system,
                             const Eigen::VectorXd& b, double tolerance,
                             Eigen::VectorXd* x) {
  return Solve(system.matrix, system.vertex_of, system.num_vertices, b,
               tolerance, x);
}

Eigen::VectorXd ReusableCholesky::ApplyInverse(const Eigen::VectorXd& b) const {
  return factor_->permutation.inverse() *
         factor_->llt.solve(factor_->permutation * b);
}

bool ReusableCholesky::Solve(const Eigen::SparseMatrix<double>& lower,
                             const std::vector<int>& vertex_of,
                             int num_vertices, const Eigen::VectorXd& b,
                             double tolerance, Eigen::VectorXd* x) {
  if (factorized_ && factor_->llt.rows() == lower.rows()) {
    const auto start = std::chrono::steady_clock::now();
    const auto h = lower.selfadjointView<Eigen::Lower>();
    const double target = tolerance * b.norm();
    const double n = static_cast<double>(lower.rows());
    const double iteration_flops =
        4 * factor_nonzeros_ + 2 * (2 * double(lower.nonZeros()) - n);
    double cg_flops = iteration_flops;  // the start below
    *x = ApplyInverse(b);
    Eigen::VectorXd r = b - h * *x;
    Eigen::VectorXd z = ApplyInverse(r);
    Eigen::VectorXd d = z;
    double rz = r.dot(z);
    bool converged = r.norm() <= target;
    for (int it = 0; it < max_cg_iterations && !converged; ++it) {
      if (cg_flops >= last_factorization_flops_) break;
      cg_flops += iteration_flops;
      ++stats_.cg_iterations;
      const Eigen::VectorXd hd = h * d;
      const double curvature = d.dot(hd);
      if (!(curvature > 0)) break;
      const double alpha = rz / curvature;
      *x += alpha * d;
      r -= alpha * hd;
      converged = r.norm() <= target;
      if (converged) break;
      z = ApplyInverse(r);
      const double rz_next = r.dot(z);
      d = z + (rz_next / rz) * d;
      rz = rz_next;
    }
    stats_.cg_seconds += Since(start);
    if (converged) {
      ++stats_.cg_solves;
      return true;
    }
  }
  if (!Factorize(lower, vertex_of, num_vertices)) return false;
  *x = ApplyInverse(b);
  return true;
}

}  // namespace shellspace
