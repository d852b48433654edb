// Conjugate gradients on a symmetric positive definite matrix with a block
// structure (the time slices of a path Hessian), preconditioned by the
// Cholesky factors of its diagonal blocks (block Jacobi).
#ifndef SHELLSPACE_SOLVERS_BLOCK_JACOBI_CG_H_
#define SHELLSPACE_SOLVERS_BLOCK_JACOBI_CG_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "shellspace/solvers/time_coupled_preconditioner.h"

namespace shellspace {

// For H = [H_ij] with diagonal blocks H_ii (rows and columns
// [offsets[i], offsets[i + 1])), the preconditioner is
//   M = diag(H_11, ..., H_BB),  M^-1 applied by B sparse Cholesky solves.
// Memory is that of B one-slice factors -- no fill across slices, unlike a
// factorisation of the whole H -- so a path Hessian with K - 1 inner shapes
// costs O(K) single-shape factorisations. For H = K T (x) G (a time
// Laplacian T = tridiag(-1, 2, -1) of a constant metric G) the
// preconditioned spectrum lies in (0, 2) with condition number
// ~ (K/pi)^2, so CG needs O(K) iterations; near a geodesic the path Hessian
// is close to that model.
//
// Stopping is deterministic: |H x - b|_2 <= tolerance |b|_2 or
// max_iterations, never a clock.
class BlockJacobiCg {
 public:
  enum class Status {
    kSolved,         // the residual reached the tolerance
    kNotPositive,    // a diagonal block is not positive definite, or CG met
                     // a direction of non-positive curvature
    kNotConverged,   // max_iterations reached first (x is the last iterate)
  };
  struct Stats {
    int factorizations = 0;  // diagonal blocks factorised, in all
    int solves = 0;
    int cg_iterations = 0;   // in all
  };

  BlockJacobiCg();
  ~BlockJacobiCg();

  // Factorises the diagonal blocks of `lower` (the lower triangle of H,
  // compressed columns). Returns false if one is not positive definite.
  bool Factorize(const Eigen::SparseMatrix<double>& lower,
                 const std::vector<int>& offsets);

  // Solves H x = b by CG from x = M^-1 b -- or from *x if warm_start --
  // with the blocks of the last Factorize as preconditioner (H may have
  // changed since: a stale preconditioner only costs iterations).
  // `iterations` receives this solve's CG iterations if given.
  Status Solve(const Eigen::SparseMatrix<double>& lower,
               const Eigen::VectorXd& b, double tolerance, int max_iterations,
               Eigen::VectorXd* x, int* iterations = nullptr,
               bool warm_start = false);

  const Stats& stats() const { return stats_; }

  // M^-1 r with the factors of the last successful Factorize.
  Eigen::VectorXd Precondition(const Eigen::VectorXd& r) const {
    return ApplyPreconditioner(r);
  }

  // Threads over the blocks: the B factorisations of Factorize and the B
  // solves of each preconditioner application run in parallel (each block
  // alone, so the results do not depend on the count).
  void set_threads(int threads) { threads_ = threads < 1 ? 1 : threads; }

  // With time coupling on, Factorize builds the TimeCoupledPreconditioner
  // of the same diagonal blocks (time_coupled_preconditioner.h: the
  // couplings of the Kronecker model kept, the same solves per
  // application) where the blocks share one sparsity pattern, and block
  // Jacobi otherwise; the coupling strengths are fitted to H
  // (TimeCoupledPreconditioner::FitCouplings). time_coupled() says which
  // the last Factorize built, couplings() its theta_i.
  void set_time_coupling(bool on) { time_coupling_ = on; }
  // How the time-coupled preconditioner keeps its factors (default single
  // precision: TimeCoupledPreconditioner::FactorPrecision).
  void set_factor_precision(TimeCoupledPreconditioner::FactorPrecision p) {
    coupled_.set_factor_precision(p);
  }
  bool time_coupled() const { return time_coupled_; }
  const std::vector<double>& couplings() const { return coupled_.couplings(); }

 private:
  struct Factors;  // CHOLMOD stays out of the public headers
  Eigen::VectorXd ApplyPreconditioner(const Eigen::VectorXd& r) const;

  std::unique_ptr<Factors> factors_;
  TimeCoupledPreconditioner coupled_;
  bool time_coupling_ = false, time_coupled_ = false;
  std::vector<int> offsets_;
  Stats stats_;
  int threads_ = 1;
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_BLOCK_JACOBI_CG_H_
