#include "shellspace/problems/statistics/elastic_mean_newton.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "shellspace/geometry/connected_components.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

NewtonSettings ElasticMeanNewtonSettings(double target, int max_steps) {
  NewtonSettings newton;
  newton.mode = NewtonMode::kMinimize;
  newton.max_steps = max_steps;
  newton.tolerance = target;
  newton.forcing = 1e-10;
  newton.max_halvings = 4;  // t = 1, ..., 1/16
  newton.accept_smaller_two_norm = true;
  newton.max_shifts = 6;  // H + lambda I where the Newton step fails
  return newton;
}

ElasticMeanNewtonProblem::ElasticMeanNewtonProblem(const Faces& faces,
                                                   Positions* s)
    : components_(ConnectedComponents(faces, static_cast<int>(s->rows()))),
      s_(s) {}

EvaluationStatus ElasticMeanNewtonProblem::Merit(NewtonPoint point,
                                                 double* merit) {
  return Energy(point, merit) && std::isfinite(*merit)
             ? EvaluationStatus::kOk
             : EvaluationStatus::kInfeasible;
}

EvaluationStatus ElasticMeanNewtonProblem::Residual(NewtonPoint point,
                                                    NewtonResidual* residual) {
  Eigen::VectorXd g;
  if (!Gradient(point, &g) || !g.allFinite()) {
    return EvaluationStatus::kInfeasible;
  }
  const Positions& s = At(point);
  Eigen::SparseMatrix<double>& basis =
      point == NewtonPoint::kCurrent ? basis_ : trial_basis_;
  basis = RigidGaugeBasis(s, ChooseGaugeVertices(s, components_));
  residual->reduced = basis.transpose() * g;
  residual->max_norm = g.cwiseAbs().maxCoeff();
  residual->two_norm = g.norm();
  return EvaluationStatus::kOk;
}

void ElasticMeanNewtonProblem::SetTrial(const Eigen::VectorXd& step) {
  trial_ = *s_;
  Eigen::Map<Eigen::VectorXd>(trial_.data(), trial_.size()) += basis_ * step;
}

void ElasticMeanNewtonProblem::AcceptTrial() {
  *s_ = trial_;
  basis_ = std::move(trial_basis_);
}

namespace {

// The problem on terms from an ElasticMeanTermsFunction, kept for the
// current and the trial point (one evaluation per point).
class SummedTermsMeanProblem : public ElasticMeanNewtonProblem {
 public:
  SummedTermsMeanProblem(const Faces& faces,
                         const ElasticMeanTermsFunction& terms, Positions* s)
      : ElasticMeanNewtonProblem(faces, s), terms_(terms) {}

  EvaluationStatus Assemble(LinearSystem* system) override {
    const ElasticMeanTerms* terms = TermsAt(NewtonPoint::kCurrent);
    if (terms == nullptr) return EvaluationStatus::kInfeasible;
    system->matrix = basis().transpose() * terms->hessian * basis();
    system->vertex_of = BasisColumnVertices(basis());
    system->num_vertices = num_vertices();
    return EvaluationStatus::kOk;
  }
  void SetTrial(const Eigen::VectorXd& step) override {
    ElasticMeanNewtonProblem::SetTrial(step);
    trial_terms_.reset();
  }
  void AcceptTrial() override {
    ElasticMeanNewtonProblem::AcceptTrial();
    current_terms_ = std::move(trial_terms_);
  }

 protected:
  bool Energy(NewtonPoint point, double* energy) override {
    const ElasticMeanTerms* terms = TermsAt(point);
    if (terms != nullptr) *energy = terms->energy;
    return terms != nullptr;
  }
  bool Gradient(NewtonPoint point, Eigen::VectorXd* gradient) override {
    const ElasticMeanTerms* terms = TermsAt(point);
    if (terms != nullptr) *gradient = terms->gradient;
    return terms != nullptr;
  }

 private:
  // The terms at `point`, evaluated on first use; nullptr if degenerate.
  const ElasticMeanTerms* TermsAt(NewtonPoint point) {
    std::optional<Evaluated>& slot =
        point == NewtonPoint::kCurrent ? current_terms_ : trial_terms_;
    if (!slot) {
      slot.emplace();
      slot->feasible = terms_(At(point), &slot->terms);
    }
    return slot->feasible ? &slot->terms : nullptr;
  }

  struct Evaluated {
    bool feasible = false;
    ElasticMeanTerms terms;
  };
  const ElasticMeanTermsFunction& terms_;
  std::optional<Evaluated> current_terms_;
  std::optional<Evaluated> trial_terms_;
};

}  // namespace

SummedTermsMeanReport ElasticMeanNewtonOnTerms(
    const Faces& faces, const ElasticMeanTermsFunction& terms,
    double tolerance, NewtonSettings settings, Positions* s) {
  SummedTermsMeanProblem problem(faces, terms, s);
  NewtonResidual start;
  if (problem.Residual(NewtonPoint::kCurrent, &start) !=
      EvaluationStatus::kOk) {
    throw InputError("elastic mean: the initial mean is degenerate");
  }
  SummedTermsMeanReport report;
  report.initial_gradient_norm = start.max_norm;
  report.gradient_target = tolerance * std::max(1.0, start.max_norm);
  settings.tolerance = report.gradient_target;
  ReusableCholesky solver;
  report.newton = SolveNewton(&problem, &solver, settings);
  return report;
}

}  // namespace shellspace
