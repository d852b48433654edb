#include "shellspace/problems/calculus/exp_step_newton.h"

#include <cmath>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/connected_components.h"
#include "shellspace/geometry/vertex_flags.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/rigid_gauge.h"
#include "shellspace/solvers/sparse_lu.h"

namespace shellspace {

namespace {

// Near a singular J the Newton step can be huge: halve down to 2^-20.
constexpr int kMaxHalvings = 20;
// Newton that has not halved max |F| after this many accepted steps is not
// converging (damped steps crawling along a valley of |F| with no root
// nearby): give up, the caller has a fallback.
constexpr int kProgressSteps = 8;

double TwoNorm(const Eigen::VectorXd& f, const std::vector<char>& is_fixed) {
  double sum = 0;
  for (int v = 0; v < static_cast<int>(is_fixed.size()); ++v) {
    if (!is_fixed[v]) sum += f.segment<3>(3 * v).squaredNorm();
  }
  return std::sqrt(sum);
}

// F(s) as a status: infeasible if s has a degenerate element.
EvaluationStatus TryResidual(const ShellSpace& space, const Positions& fixed,
                             ShellSide unknown_side,
                             const Eigen::VectorXd& constant,
                             const Positions& s, Eigen::VectorXd* f) {
  const bool ok = unknown_side == ShellSide::kDeformed
                      ? TryEnergyGradient(space, fixed, s,
                                          ShellSide::kReference, f)
                      : TryEnergyGradient(space, s, fixed,
                                          ShellSide::kDeformed, f);
  if (!ok) return EvaluationStatus::kInfeasible;
  *f += constant;
  return EvaluationStatus::kOk;
}

}  // namespace

double ExpResidualMaxNorm(const ExpStepEquation& equation,
                          const Positions& s) {
  Eigen::VectorXd f;
  if (TryResidual(equation.space, equation.fixed, equation.unknown_side,
                  equation.constant, s, &f) != EvaluationStatus::kOk) {
    return HUGE_VAL;
  }
  return UnflaggedMaxNorm(
      f, VertexFlags(equation.space.num_vertices, equation.fixed_vertices));
}

namespace {

// F(s) = 0 for SolveNewton in root-finding mode: residual R^T F (rows: the
// rigid gauge of the fixed shell, or the free vertices), norms of F on the
// unmasked vertices, J = R^T (dF/ds) C (columns C: the rigid gauge of the
// current s, or the free vertices), retraction s += C q.
class ExpStepProblem : public NewtonProblem {
 public:
  ExpStepProblem(const ShellSpace& space, const Positions& fixed,
                 ShellSide unknown_side, const Eigen::VectorXd& constant,
                 const std::vector<int>& fixed_vertices, Positions* s)
      : space_(space),
        fixed_(fixed),
        unknown_side_(unknown_side),
        constant_(constant),
        is_fixed_(VertexFlags(space.num_vertices, fixed_vertices)),
        gauge_(fixed_vertices.empty()),
        components_(gauge_
                        ? ConnectedComponents(space.faces, space.num_vertices)
                        : std::vector<std::vector<int>>{}),
        rows_(gauge_ ? RigidGaugeBasis(fixed,
                                       ChooseGaugeVertices(fixed, components_))
                     : FreeVertexBasis(space.num_vertices, fixed_vertices)),
        assembler_(space),
        s_(s) {}

  EvaluationStatus Merit(NewtonPoint, double*) override {
    return EvaluationStatus::kInfeasible;  // root finding has no merit
  }
  EvaluationStatus Residual(NewtonPoint point,
                            NewtonResidual* residual) override {
    const Positions& s = point == NewtonPoint::kCurrent ? *s_ : trial_;
    Eigen::VectorXd f;
    if (TryResidual(space_, fixed_, unknown_side_, constant_, s, &f) !=
        EvaluationStatus::kOk) {
      return EvaluationStatus::kInfeasible;
    }
    residual->max_norm = UnflaggedMaxNorm(f, is_fixed_);
    residual->two_norm = TwoNorm(f, is_fixed_);
    residual->reduced = rows_.transpose() * f;
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Assemble(LinearSystem* system) override {
    columns_ = gauge_ ? RigidGaugeBasis(
                            *s_, ChooseGaugeVertices(*s_, components_))
                      : rows_;
    // J = dF/ds: rows on the fixed shell's gradient, columns on s, reduced
    // to R^T J C straight from the element blocks.
    const bool ok =
        unknown_side_ == ShellSide::kDeformed
            ? assembler_.TryAssembleMixed(fixed_, *s_, ShellSide::kReference,
                                          rows_, columns_, &system->matrix)
            : assembler_.TryAssembleMixed(*s_, fixed_, ShellSide::kDeformed,
                                          rows_, columns_, &system->matrix);
    return ok ? EvaluationStatus::kOk : EvaluationStatus::kInfeasible;
  }
  void SetTrial(const Eigen::VectorXd& step) override {
    trial_ = *s_;
    Eigen::Map<Eigen::VectorXd>(trial_.data(), trial_.size()) +=
        columns_ * step;
  }
  void AcceptTrial() override { *s_ = trial_; }

 private:
  const ShellSpace& space_;
  const Positions& fixed_;
  const ShellSide unknown_side_;
  const Eigen::VectorXd& constant_;
  const std::vector<char> is_fixed_;
  const bool gauge_;
  // Without a mask: the mesh's connected components, each with a rigid
  // gauge of its own (a shell in two pieces moves rigidly in each).
  const std::vector<std::vector<int>> components_;
  const SparseMatrix rows_;
  const PathHessianAssembler assembler_;
  Positions* s_;
  SparseMatrix columns_;
  Positions trial_;
};

}  // namespace

ExpNewtonReport SolveExpStepNewton(const ExpStepEquation& equation,
                                   const ExpNewtonStopping& stopping,
                                   Positions* s) {
  ExpStepProblem problem(equation.space, equation.fixed, equation.unknown_side,
                         equation.constant, equation.fixed_vertices, s);
  NewtonSettings newton;
  newton.mode = NewtonMode::kRootFind;
  newton.max_steps = stopping.max_steps;
  newton.tolerance = stopping.tolerance;
  newton.max_halvings = kMaxHalvings;
  newton.accept_smaller_max_norm = true;
  newton.accept_smaller_two_norm = true;
  newton.round_off_floor = stopping.stall_tolerance;
  newton.round_off_factor = 0.5;
  newton.progress_steps = kProgressSteps;
  newton.progress_factor = 0.5;
  SparseLu lu;
  return SolveNewton(&problem, &lu, newton);
}

}  // namespace shellspace
