#include "shellspace/solvers/block_jacobi_solver.h"

#include <chrono>

namespace shellspace {

namespace {
// Wall clock for the report counters only.
double Since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}

bool PartitionsMatrix(const std::vector<int>& offsets, int n) {
  if (offsets.size() < 2 || offsets.front() != 0 || offsets.back() != n) {
    return false;
  }
  for (size_t i = 0; i + 1 < offsets.size(); ++i) {
    if (offsets[i + 1] <= offsets[i]) return false;
  }
  return true;
}
}  // namespace

void BlockJacobiSolver::Configure() {
  cg_.set_threads(threads);
  cg_.set_time_coupling(time_coupling);
  cg_.set_factor_precision(
      single_precision_factors
          ? TimeCoupledPreconditioner::FactorPrecision::kSingle
          : TimeCoupledPreconditioner::FactorPrecision::kDouble);
}

bool BlockJacobiSolver::Factorize(const LinearSystem& system) {
  const Eigen::SparseMatrix<double>& h = system.matrix;
  if (!PartitionsMatrix(system.block_offsets, static_cast<int>(h.rows())) ||
      h.cols() != h.rows()) {
    return false;
  }
  Configure();
  const auto start = std::chrono::steady_clock::now();
  factored_offsets_.clear();
  const bool positive = cg_.Factorize(h, system.block_offsets);
  ++stats_.factorizations;
  if (cg_.time_coupled()) ++stats_.time_coupled_factorizations;
  stats_.factorization_seconds += Since(start);
  if (positive) factored_offsets_ = system.block_offsets;
  return positive;
}

Eigen::VectorXd BlockJacobiSolver::Apply(const Eigen::VectorXd& r) const {
  return cg_.Precondition(r);
}

bool BlockJacobiSolver::Solve(const LinearSystem& system,
                              const Eigen::VectorXd& b, double tolerance,
                              Eigen::VectorXd* x) {
  const Eigen::SparseMatrix<double>& h = system.matrix;
  if (!PartitionsMatrix(system.block_offsets, static_cast<int>(h.rows())) ||
      h.cols() != h.rows() || b.size() != h.rows()) {
    return false;
  }
  ++stats_.cg_solves;
  Configure();
  const auto run_cg = [&](int budget, bool warm_start) {
    const auto start = std::chrono::steady_clock::now();
    int iterations = 0;
    const BlockJacobiCg::Status status =
        cg_.Solve(h, b, tolerance, budget, x, &iterations, warm_start);
    stats_.cg_iterations += iterations;
    stats_.cg_seconds += Since(start);
    return status;
  };
  // Whether CG on the fresh factors continues from the stale run's iterate.
  bool continue_stale = false;
  if (factored_offsets_ == system.block_offsets) {
    const BlockJacobiCg::Status status = run_cg(stale_iteration_budget, false);
    if (status == BlockJacobiCg::Status::kSolved) return true;
    if (status == BlockJacobiCg::Status::kNotPositive) return false;
    continue_stale = x->size() == b.size() && x->allFinite();
  }
  if (!Factorize(system)) return false;
  const BlockJacobiCg::Status status = run_cg(max_iterations, continue_stale);
  if (status == BlockJacobiCg::Status::kNotPositive) return false;
  if (status == BlockJacobiCg::Status::kNotConverged) {
    ++stats_.cg_not_converged;
  }
  return true;
}

}  // namespace shellspace
