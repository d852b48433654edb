// Newton's method on the elastic-mean energy E(s) = sum_i W[S_i, s] over
// the mean s (the finish of ComputeElasticMean, elastic_mean.h), on the
// coordinates left by a rigid gauge in each connected component: the
// engine's settings, the problem with its terms left to a subclass (summed
// over the inputs in this process, elastic_mean.cc), and the finish on
// terms summed by the caller (e.g. as tasks on a cluster).
#ifndef SHELLSPACE_PROBLEMS_STATISTICS_ELASTIC_MEAN_NEWTON_H_
#define SHELLSPACE_PROBLEMS_STATISTICS_ELASTIC_MEAN_NEWTON_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <optional>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/newton_solver.h"

namespace shellspace {

// The settings of the finish: minimisation to |G|_inf <= target in at most
// max_steps accepted steps; step lengths 1, 1/2, ..., 1/16 under Armijo's
// condition on E, or a trial that lowers |G|_2 without raising E beyond
// round-off; H + lambda I where the Newton step cannot be used (up to 6
// shifts: ElasticMeanOptions in elastic_mean.h says why).
NewtonSettings ElasticMeanNewtonSettings(double target, int max_steps);

// E over s (in place) for SolveNewton: merit E, residual G(s) (norms on all
// 3n coordinates, reduced T^T G with T = RigidGaugeBasis(s) with a gauge in
// each connected component of `faces`), retraction s += T q. A subclass
// evaluates E and G at a point and assembles T^T H T at the current one.
class ElasticMeanNewtonProblem : public NewtonProblem {
 public:
  ElasticMeanNewtonProblem(const Faces& faces, Positions* s);

  EvaluationStatus Merit(NewtonPoint point, double* merit) override;
  EvaluationStatus Residual(NewtonPoint point,
                            NewtonResidual* residual) override;
  void SetTrial(const Eigen::VectorXd& step) override;
  void AcceptTrial() override;

 protected:
  // E and G at `point` (false: degenerate there).
  virtual bool Energy(NewtonPoint point, double* energy) = 0;
  virtual bool Gradient(NewtonPoint point, Eigen::VectorXd* gradient) = 0;
  const Positions& At(NewtonPoint point) const {
    return point == NewtonPoint::kCurrent ? *s_ : trial_;
  }
  const Eigen::SparseMatrix<double>& basis() const { return basis_; }
  int num_vertices() const { return static_cast<int>(s_->rows()); }

 private:
  // A rigid gauge in each connected component of the mesh.
  const std::vector<std::vector<int>> components_;
  Positions* s_;
  Eigen::SparseMatrix<double> basis_;  // RigidGaugeBasis(*s_, its gauge)
  Positions trial_;
  Eigen::SparseMatrix<double> trial_basis_;
};

// The terms of E at a shape s: E(s), G(s) = sum_i D_2 W[S_i, s] (3n,
// vertex-major) and H(s) = sum_i D_2^2 W[S_i, s] (3n x 3n).
struct ElasticMeanTerms {
  double energy = 0;
  Eigen::VectorXd gradient;
  Eigen::SparseMatrix<double> hessian;
};
// Evaluates the terms at s; false if s has a degenerate element.
using ElasticMeanTermsFunction =
    std::function<bool(const Positions& s, ElasticMeanTerms* terms)>;

// How the finish on summed terms went: the engine's report, |G(s_0)|_inf
// and the target tolerance * max(1, |G(s_0)|_inf) (ComputeElasticMean's).
struct SummedTermsMeanReport {
  NewtonReport newton;
  double initial_gradient_norm = 0;
  double gradient_target = 0;
};

// The finish from *s (left at the last accepted point) with the terms of
// `terms`, evaluated once per point (E, G and H together: one round of the
// caller's tasks per trial). `settings`: ElasticMeanNewtonSettings' rules;
// its tolerance is set here from `tolerance`, its stop and progress are the
// caller's. Throws InputError if s_0 is degenerate.
SummedTermsMeanReport ElasticMeanNewtonOnTerms(
    const Faces& faces, const ElasticMeanTermsFunction& terms,
    double tolerance, NewtonSettings settings, Positions* s);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_STATISTICS_ELASTIC_MEAN_NEWTON_H_
