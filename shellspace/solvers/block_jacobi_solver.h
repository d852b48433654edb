// The LinearSolver of a block-structured SPD system (a path Hessian, block
// tridiagonal in time) by block-Jacobi CG: memory O(B * one block's factor)
// instead of the fill of a factorisation of the whole matrix.
#ifndef SHELLSPACE_SOLVERS_BLOCK_JACOBI_SOLVER_H_
#define SHELLSPACE_SOLVERS_BLOCK_JACOBI_SOLVER_H_

#include <Eigen/Core>

#include "shellspace/solvers/block_jacobi_cg.h"
#include "shellspace/solvers/linear_solver.h"

namespace shellspace {

// Solves H x = b (H = system.matrix, lower triangle; blocks
// system.block_offsets, required: B + 1 entries from 0 to n) by CG
// preconditioned with the Cholesky factors of the diagonal blocks H_ii
// (BlockJacobiCg), to |H x - b|_2 <= tolerance |b|_2.
// Factor reuse across Newton steps (deterministic, iteration counts only):
//  - with factors of an earlier H0 held (same block_offsets), CG runs on
//    them for at most stale_iteration_budget iterations;
//  - if that does not reach the tolerance (or nothing is held), the blocks
//    of the current H are factorised and CG restarts -- from the stale
//    run's iterate if there was one, else from M^-1 b -- for at most
//    max_iterations; if even that falls short, the last iterate is
//    returned (true) and stats().cg_not_converged counts it -- a CG iterate
//    of an SPD H still gives the Newton engine a direction to check.
// Returns false -- "not positive definite", as ReusableCholesky -- if a
// diagonal block of the current H is not positive definite or CG meets a
// direction d with d^T H d <= 0 (negative curvature of H itself, whichever
// factors precondition), or if block_offsets does not partition H.
// stats(): factorizations counts block-set factorisations (all B blocks
// once), cg_iterations all CG iterations, cg_solves the solves.
class BlockJacobiSolver : public LinearSolver, public Preconditioner {
 public:
  // Preconditioner: the factors of the diagonal blocks (the time-coupled
  // model where the blocks share a pattern) of system.matrix; false if a
  // block is not positive definite or block_offsets does not partition it.
  // A later Solve on the same blocks reuses them as its stale factors.
  bool Factorize(const LinearSystem& system) override;
  Eigen::VectorXd Apply(const Eigen::VectorXd& r) const override;
  // Drops the held factors (the next Solve factorises); the blocks'
  // pattern analysis is kept.
  void ForgetFactors() { factored_offsets_.clear(); }
  Preconditioner* preconditioner() override { return this; }
  void CountCg(int iterations, double seconds) override {
    stats_.cg_iterations += iterations;
    stats_.cg_seconds += seconds;
  }

  bool Solve(const LinearSystem& system, const Eigen::VectorXd& b,
             double tolerance, Eigen::VectorXd* x) override;
  const LinearSolverStats& stats() const override { return stats_; }
  const char* name() const override { return "block-jacobi"; }

  // About the cost of one factorisation in CG iterations on the scale
  // cases (25-32); the stale run's iterate is the fresh run's start.
  int stale_iteration_budget = 30;
  int max_iterations = 2000;
  int threads = 1;  // over the blocks (BlockJacobiCg::set_threads)
  // The time-coupled preconditioner where the blocks share a pattern
  // (BlockJacobiCg::set_time_coupling); stats().time_coupled_factorizations
  // counts the factorisations that built it.
  bool time_coupling = true;
  // Its factors in single precision (half the memory and time of its
  // solves; CG's answer is the same to its tolerance), or double.
  bool single_precision_factors = true;

 private:
  void Configure();
  BlockJacobiCg cg_;
  std::vector<int> factored_offsets_;  // empty: nothing held
  LinearSolverStats stats_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_BLOCK_JACOBI_SOLVER_H_
