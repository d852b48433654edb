// The linear solver of a Newton step: A x = b for the (reduced) Hessian or
// Jacobian A of one Newton iteration, behind one interface so that the
// Newton engine (newton_solver.h) does not know which factorisation runs.
#ifndef SHELLSPACE_SOLVERS_LINEAR_SOLVER_H_
#define SHELLSPACE_SOLVERS_LINEAR_SOLVER_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace shellspace {

// One linear system A (n x n, sparse). For a symmetric solver only the lower
// triangle of `matrix` is read. vertex_of[i] (optional, size n) is the mesh
// vertex of unknown i out of num_vertices: a fill-reducing ordering hint
// (space_time_ordering.h); solvers that do not use it ignore it.
// block_offsets (optional; empty or B + 1 increasing entries from 0 to n):
// unknowns [block_offsets[i], block_offsets[i + 1]) form block i (the time
// slices of a path Hessian), for block solvers (block_jacobi_solver.h).
struct LinearSystem {
  Eigen::SparseMatrix<double> matrix;
  std::vector<int> vertex_of;
  int num_vertices = 0;
  std::vector<int> block_offsets;
};

// Work counters of a linear solver, summed over its solves. The seconds are
// wall clock, for reports only: no decision of any solver depends on them.
struct LinearSolverStats {
  int factorizations = 0;
  // of which the preconditioner coupled the time slices
  // (time_coupled_preconditioner.h)
  int time_coupled_factorizations = 0;
  int cg_solves = 0;      // solves finished by CG on a reused factor
  int cg_iterations = 0;  // in all
  int cg_not_converged = 0;  // iterative solves that returned their last
                             // iterate short of the tolerance
  double factorization_seconds = 0;
  double cg_seconds = 0;
};

// An SPD approximation M of a system's matrix A, applied as M^-1: the
// preconditioner of the engine's own conjugate gradients (the trust-region
// subproblem, steihaug_cg.h). A linear solver that factorises offers its
// factorisation as one (LinearSolver::preconditioner).
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // Factorises M from `system` (the whole matrix, or its diagonal blocks).
  // False if that factorisation is not positive definite; the caller may
  // then shift the matrix's diagonal and try again.
  virtual bool Factorize(const LinearSystem& system) = 0;
  // M^-1 r with the last successful Factorize.
  virtual Eigen::VectorXd Apply(const Eigen::VectorXd& r) const = 0;
};

// Solves A x = b. `tolerance` is the relative residual |A x - b|_2 <=
// tolerance |b|_2 an iterative solver may stop at; a direct solver solves to
// round-off and ignores it. Returns false (x unspecified) if A is singular
// or, for an SPD solver, not positive definite; then x is not finite-checked
// by the caller.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual bool Solve(const LinearSystem& system, const Eigen::VectorXd& b,
                     double tolerance, Eigen::VectorXd* x) = 0;
  virtual const LinearSolverStats& stats() const = 0;
  // What runs, for reports: "direct" (space-time Cholesky), "block-jacobi",
  // "lu".
  virtual const char* name() const = 0;
  // The solver's factorisation as a Preconditioner of the same systems, or
  // nullptr. Its factorisations count in stats().
  virtual Preconditioner* preconditioner() { return nullptr; }
  // Adds CG work done by the caller on preconditioner() to stats().
  virtual void CountCg(int iterations, double seconds) {
    (void)iterations;
    (void)seconds;
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_LINEAR_SOLVER_H_
