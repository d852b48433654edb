// A preconditioner for path Hessians that couples the time slices: the
// Kronecker model of a discrete geodesic's Hessian with one metric per
// slice, applied with the slices' own Cholesky factors.
#ifndef SHELLSPACE_SOLVERS_TIME_COUPLED_PRECONDITIONER_H_
#define SHELLSPACE_SOLVERS_TIME_COUPLED_PRECONDITIONER_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <vector>

namespace shellspace {

// TimeCoupledPreconditioner::FitCouplings: the largest relative misfit of a
// coupled pair.
inline constexpr double kMaxCouplingMisfit = 0.2;

// FitCouplings' probes by default (FitProbes): 2 on slices of fewer
// unknowns than this, 1 from there. Each probe samples every coupling
// twice (from either slice), and a sample's trace estimate z^T E z / m
// has the standard deviation sqrt(2) |offdiag(E)|_F / m; for a pair the fit
// keeps (misfit <= kMaxCouplingMisfit) that is at most (theta / 2)
// sqrt(2 kMaxCouplingMisfit / m). So theta's relative error is at most
// sqrt(kMaxCouplingMisfit / (probes m)): 0.45 % with one probe from 10,000
// unknowns, below 1 % with two from 1,000. A probe costs about 1.5 CG
// iterations.
inline constexpr int kOneFitProbeFromUnknowns = 10000;

// The number of probes FitCouplings uses by default on slices of
// `block_size` unknowns (kOneFitProbeFromUnknowns).
int FitProbes(int block_size);

// Near a discrete geodesic W[a, b] ~ 1/2 (b - a)^T G (b - a), so the Hessian
// of E_K over the B = K - 1 inner shapes is close to K T (x) G with the
// Dirichlet time Laplacian T = tridiag(-1, 2, -1) (B x B): each diagonal
// block H_ii ~ 2 K G, each coupling H_i,i+1 ~ -K G. Block Jacobi keeps the
// diagonal blocks only, and its CG needs O(K) iterations on that model.
// This preconditioner keeps the coupling too. With the Cholesky factors
// H_ii = C_i C_i^T (one fill-reducing ordering P shared by every slice,
// C_i = P^T L_i), the model is
//   M = C ((T / 2) (x) I) C^T,   C = blockdiag(C_1, ..., C_B):
// its diagonal blocks are exactly H_ii, its couplings -C_i C_{i+1}^T / 2,
// which is H_i,i+1 when neighbouring slices have the same metric. M is
// symmetric positive definite whatever the blocks (C invertible, T SPD), and
//   M^-1 r = C^-T ((2 T^-1) (x) I) C^-1 r
// costs the same triangular solves as block Jacobi, plus B^2 vector updates
// of one slice's length: per slice y_i = L_i^-1 P r_i, then
// z_i = sum_j 2 (T^-1)_ij y_j, then x_i = P^T L_i^-T z_i. For H = K T (x) G
// exactly, M = H / K and CG converges in one iteration.
// Coupling strength: far from that model (a plate rolled in 8 steps: the
// stiff membrane directions turn from slice to slice) the full coupling can
// be worse than none. In the whitened coordinates C^-1 H C^-T the diagonal
// blocks are I and the model's couplings are -theta_i I / 2; FitCouplings
// sets each theta_i in [0, 1] to the best fit of the true coupling's trace,
//   theta_i = -2 tr(C_i^-1 H_i,i+1 C_i+1^-T) / m,
// estimated with fixed Rademacher probes (Hutchinson; deterministic, the
// same probes every time), and the model's time matrix becomes
// T_theta = tridiag(-theta, 2, -theta) (SPD for theta in [0, 1]; theta = 0
// is block Jacobi). Where the model explains the coupling poorly -- the
// probes' |E_i + theta_i I / 2|_F^2 above kMaxCouplingMisfit times
// |theta_i I / 2|_F^2 -- theta_i = 0: on that plate coupling the two
// middle pairs (misfits 0.5 and 0.67) cost 78 CG iterations against block
// Jacobi's 43, and the fitted thetas still 55; with them uncoupled, 43. On
// the finger and cactus ring masks the misfits stay below 0.015 and the
// fitted model needs 2-4x fewer iterations than block Jacobi. Without
// FitCouplings every theta_i is 1.
// The shared ordering needs every diagonal block to have the same size and
// sparsity pattern (a mask: the same free vertices in every slice);
// Factorize returns kDifferentPatterns otherwise.
// Deterministic: the result does not depend on the thread count.
class TimeCoupledPreconditioner {
 public:
  enum class Status { kFactorized, kNotPositive, kDifferentPatterns };
  // How the slices' factors L_i are kept (SupernodalFactor): kSingle halves
  // their memory and the time of Apply (bound by reading the factors), and
  // M is then the model of the rounded factors -- still symmetric positive
  // definite, its diagonal blocks within about 1e-7 relative of H_ii's.
  enum class FactorPrecision { kDouble, kSingle };
  void set_factor_precision(FactorPrecision precision) {
    precision_ = precision;
  }

  TimeCoupledPreconditioner();
  ~TimeCoupledPreconditioner();

  // Factorises the blocks (lower triangles, compressed columns, sorted),
  // analysing the common pattern once; `threads` factorisations at a time.
  Status Factorize(const std::vector<Eigen::SparseMatrix<double>>& blocks,
                   int threads);
  // The same for `count` blocks made on demand: block(i, &b) sets b to block
  // i; it is called once for block 0 (the analysis) and once by the task
  // that factorises each block, which frees it after (at most `threads`
  // blocks plus block 0 exist at a time).
  using BlockSource =
      std::function<void(int, Eigen::SparseMatrix<double>*)>;
  Status Factorize(int count, const BlockSource& block, int threads);

  // Fits theta (above) to the couplings of `lower` (the lower triangle of
  // the whole H whose diagonal blocks were factorised) with `probes`
  // Rademacher vectors (0: FitProbes of the slices' size); per probe, one
  // triangular solve per slice for the colourings and two for the
  // whitenings, and products with the coupling blocks only (the probe
  // vectors vanish on the other slices): about 1.5 probes CG iterations.
  void FitCouplings(const Eigen::SparseMatrix<double>& lower, int threads,
                    int probes = 0);

  // M^-1 r for r laid out slice after slice (each slice's block size).
  Eigen::VectorXd Apply(const Eigen::VectorXd& r, int threads) const;

  int slices() const { return static_cast<int>(mixing_.rows()); }
  // theta_i of the couplings (slices - 1 entries).
  const std::vector<double>& couplings() const { return theta_; }

 private:
  struct Factors;
  std::unique_ptr<Factors> factors_;
  // y_i = L_i^-1 P r_i (whiten) and x_i = P^T L_i^-T z_i (colour).
  Eigen::VectorXd Whiten(int slice, const Eigen::VectorXd& r) const;
  Eigen::VectorXd Colour(int slice, const Eigen::VectorXd& z) const;
  void SetCouplings(const std::vector<double>& theta);

  FactorPrecision precision_ = FactorPrecision::kSingle;
  Eigen::MatrixXd mixing_;  // 2 T_theta^-1
  std::vector<double> theta_;
  int block_size_ = 0;
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_TIME_COUPLED_PRECONDITIONER_H_
