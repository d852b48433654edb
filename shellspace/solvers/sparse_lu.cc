#include "shellspace/solvers/sparse_lu.h"

#include <Eigen/UmfPackSupport>
#include <chrono>

namespace shellspace {

bool SparseLu::Solve(const LinearSystem& system, const Eigen::VectorXd& b,
                     double /*tolerance*/, Eigen::VectorXd* x) {
  const auto start = std::chrono::steady_clock::now();  // report only
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu(system.matrix);
  ++stats_.factorizations;
  bool ok = lu.info() == Eigen::Success;
  if (ok) {
    *x = lu.solve(b);
    ok = lu.info() == Eigen::Success && x->allFinite();
  }
  stats_.factorization_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  return ok;
}

}  // namespace shellspace
