// Sparse LU (UMFPACK) behind the LinearSolver interface: the non-symmetric
// Jacobians of root-finding Newton iterations (the EXP step).
#ifndef SHELLSPACE_SOLVERS_SPARSE_LU_H_
#define SHELLSPACE_SOLVERS_SPARSE_LU_H_

#include "shellspace/solvers/linear_solver.h"

namespace shellspace {

// Solves A x = b by a fresh UMFPACK LU factorisation of A (all of `matrix`,
// n x n, any pattern) per call; `tolerance`, vertex_of and num_vertices are
// ignored. Returns false if the factorisation or the solve fails (A
// numerically singular) or x is not finite.
class SparseLu : public LinearSolver {
 public:
  bool Solve(const LinearSystem& system, const Eigen::VectorXd& b,
             double tolerance, Eigen::VectorXd* x) override;
  const LinearSolverStats& stats() const override { return stats_; }
  const char* name() const override { return "lu"; }

 private:
  LinearSolverStats stats_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_SPARSE_LU_H_
