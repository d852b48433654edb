// Linear solves for a sequence of slowly changing sparse SPD matrices (the
// Hessians of successive Newton steps), reusing one Cholesky factorisation.
#ifndef SHELLSPACE_SOLVERS_REUSABLE_CHOLESKY_H_
#define SHELLSPACE_SOLVERS_REUSABLE_CHOLESKY_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "shellspace/solvers/linear_solver.h"

namespace shellspace {

// Solves H x = b, H symmetric (lower triangle given). If a factorisation
// L L^T of an earlier H0 is held, it first runs preconditioned conjugate
// gradients on H with M = H0 as preconditioner, from x = M^-1 b, until
// |H x - b| <= tolerance |b| (2-norms) within max_cg_iterations. Otherwise,
// or if CG does not get there (or meets a direction of non-positive
// curvature), it factorises H itself -- supernodal CHOLMOD with the
// space-time ordering (space_time_ordering.h) -- and solves directly.
// Near a minimiser successive Newton Hessians differ little, and a few CG
// iterations (each one triangular solve pair and one product with H) cost
// far less than a factorisation of a path Hessian (finger, K = 8: 28 ms
// against 0.7 s). CG also gives up once its iterations have cost as much
// as the last factorisation: for one shape (a midpoint) a factorisation is
// cheap and reuse rarely pays. The costs are deterministic work estimates in
// flops, not timings (the iteration count must not depend on machine load):
// a factorisation costs CHOLMOD's flop count of its analysis
// (cholmod_common::fl), one CG iteration 4 nnz(L) (a forward and a backward
// triangular solve) + 2 (2 nnz(lower) - n) (the product with H); the start
// (x = M^-1 b, r = b - H x, z = M^-1 r) is counted as one such iteration
// (it has one triangular-solve pair more: an estimate, not an exact count).
// Implements LinearSolver (linear_solver.h) for the Newton engine.
class ReusableCholesky : public LinearSolver {
 public:
  using Stats = LinearSolverStats;

  ReusableCholesky();
  ~ReusableCholesky() override;

  // LinearSolver: Solve(system.matrix (lower triangle), system.vertex_of,
  // system.num_vertices, b, tolerance, x).
  bool Solve(const LinearSystem& system, const Eigen::VectorXd& b,
             double tolerance, Eigen::VectorXd* x) override;

  // vertex_of[i]: the mesh vertex of unknown i (for the ordering). Returns
  // false if H had to be factorised and is not positive definite.
  bool Solve(const Eigen::SparseMatrix<double>& lower,
             const std::vector<int>& vertex_of, int num_vertices,
             const Eigen::VectorXd& b, double tolerance, Eigen::VectorXd* x);

  // Preconditioner: the Cholesky factor of the whole system.matrix; false
  // if it is not positive definite. A later Solve reuses it (as after its
  // own factorisations).
  class AsPreconditioner : public Preconditioner {
   public:
    explicit AsPreconditioner(ReusableCholesky* owner) : owner_(owner) {}
    bool Factorize(const LinearSystem& system) override {
      return owner_->Factorize(system.matrix, system.vertex_of,
                               system.num_vertices);
    }
    Eigen::VectorXd Apply(const Eigen::VectorXd& r) const override {
      return owner_->ApplyInverse(r);
    }

   private:
    ReusableCholesky* owner_;
  };
  Preconditioner* preconditioner() override { return &as_preconditioner_; }
  void CountCg(int iterations, double seconds) override {
    stats_.cg_iterations += iterations;
    stats_.cg_seconds += seconds;
  }

  int max_cg_iterations = 25;
  const Stats& stats() const override { return stats_; }
  const char* name() const override { return "direct"; }

 private:
  struct Factor;  // CHOLMOD stays out of the public headers
  bool Factorize(const Eigen::SparseMatrix<double>& lower,
                 const std::vector<int>& vertex_of, int num_vertices);
  Eigen::VectorXd ApplyInverse(const Eigen::VectorXd& b) const;

  std::unique_ptr<Factor> factor_;
  bool factorized_ = false;
  Stats stats_;
  double last_factorization_flops_ = 0;  // work estimate, see above
  double factor_nonzeros_ = 0;           // nnz(L) of the held factor
  AsPreconditioner as_preconditioner_{this};
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_REUSABLE_CHOLESKY_H_
