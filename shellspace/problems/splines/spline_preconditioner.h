// Preconditioning of the spline / regression functional for L-BFGS by a
// linear change of variables.
#ifndef SHELLSPACE_PROBLEMS_SPLINES_SPLINE_PRECONDITIONER_H_
#define SHELLSPACE_PROBLEMS_SPLINES_SPLINE_PRECONDITIONER_H_

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "shellspace/problems/splines/spline_energy.h"

namespace shellspace {

// Near a shape s, W[a, b] ~ 1/2 (b - a)^T G (b - a) with the metric
// G = D_2^2 W[s, s] (= J^T J; docs/math.md, "Elastic mean and shell PCA"),
// and s_k - m_k ~ -1/2 (s_{k-1} - 2 s_k + s_{k+1}); with one metric for all,
//   R[s] ~ 1/2 sum_j |s_{k_j} - S_j|^2_G + sigma 1/2 K^3 sum_k |D_k s|^2_G,
// whose Hessian over the free shapes is the Kronecker product A (x) G,
//   A = E + sigma K^3 D^T D   (restricted to the free shapes),
// E = diag(number of data at each index), D the second differences in time
// of the spline terms (wrapping around if periodic). The metric does change
// along the path (a rolled plate is stiff in other directions than a flat
// one), so the model takes G_i at the initial free shape i, G_i + alpha_i I
// = B_i B_i^T, and H0_ij = a_ij B_i B_j^T. In the variables y of
//   x = x0 + T y,  T = blockdiag(B_i^-T) (L_A^-T (x) I),  A = L_A L_A^T,
// the model Hessian T^T H0 T is the identity: L-BFGS on the stiff R
// (membrane modes against soft bending modes) then behaves as on a
// well-conditioned problem. G_i has the rigid motions as null space;
// alpha_i = regularization * mean(diag G_i) keeps B_i invertible, and A gets
// the same relative ridge (shapes without data in a regression with small
// sigma).
class SplinePreconditioner {
 public:
  // `threads`: the free shapes' factorisations run in parallel.
  SplinePreconditioner(const ShellSpace& space, const SplineSpec& spec,
                       double regularization = 1e-6, int threads = 1);
  ~SplinePreconditioner();

  int num_parameters() const { return size_; }
  // dx = T y  (free shapes' coordinates, in SplineObjective's layout).
  void Apply(const double* y, double* dx) const;
  // gy = T^T gx.
  void ApplyTransposed(const double* gx, double* gy) const;

  // The time matrix A (free shapes x free shapes).
  const Eigen::MatrixXd& time_matrix() const { return a_; }

 private:
  struct SpaceFactor;  // sparse Cholesky of G_i + alpha_i I
  std::vector<std::unique_ptr<SpaceFactor>> space_factors_;
  Eigen::MatrixXd a_;
  Eigen::MatrixXd l_a_;  // lower Cholesky factor of A
  int block_ = 0;        // 3 n
  int free_ = 0;         // free shapes
  int size_ = 0;
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINES_SPLINE_PRECONDITIONER_H_
