#include "shellspace/problems/calculus/exp_step_newton.h"

#include <Eigen/UmfPackSupport>
#include <cmath>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/problems/calculus/path_hessian.h"

namespace shellspace {

namespace {

// Near a singular J the Newton step can be huge: halve down to this.
constexpr double kMinStepLength = 1.0 / (1 << 20);
// Newton that has not halved max |F| after this many accepted steps is not
// converging (damped steps crawling along a valley of |F| with no root
// nearby): give up, the caller has a fallback.
constexpr int kProgressSteps = 8;

// F(s) over all coordinates (the masked rows are ignored by the norms).
Eigen::VectorXd Residual(const ShellSpace& space, const Positions& fixed,
                         ShellSide unknown_side,
                         const Eigen::VectorXd& constant, const Positions& s) {
  return constant + (unknown_side == ShellSide::kDeformed
                         ? EnergyGradient(space, fixed, s,
                                          ShellSide::kReference)
                         : EnergyGradient(space, s, fixed,
                                          ShellSide::kDeformed));
}

double MaxNorm(const Eigen::VectorXd& f, const std::vector<char>& is_fixed) {
  double norm = 0;
  for (int v = 0; v < static_cast<int>(is_fixed.size()); ++v) {
    if (!is_fixed[v]) norm = std::max(norm, f.segment<3>(3 * v).cwiseAbs().maxCoeff());
  }
  return norm;
}

double TwoNorm(const Eigen::VectorXd& f, const std::vector<char>& is_fixed) {
  double sum = 0;
  for (int v = 0; v < static_cast<int>(is_fixed.size()); ++v) {
    if (!is_fixed[v]) sum += f.segment<3>(3 * v).squaredNorm();
  }
  return std::sqrt(sum);
}

std::vector<char> FixedFlags(int num_vertices,
                             const std::vector<int>& fixed_vertices) {
  std::vector<char> is_fixed(num_vertices, 0);
  for (int v : fixed_vertices) is_fixed[v] = 1;
  return is_fixed;
}

}  // namespace

double ExpResidualMaxNorm(const ShellSpace& space, const Positions& fixed,
                          ShellSide unknown_side,
                          const Eigen::VectorXd& constant,
                          const std::vector<int>& fixed_vertices,
                          const Positions& s) {
  try {
    return MaxNorm(Residual(space, fixed, unknown_side, constant, s),
                   FixedFlags(space.num_vertices, fixed_vertices));
  } catch (const InputError&) {
    return HUGE_VAL;
  }
}

ExpNewtonReport SolveExpStepNewton(const ShellSpace& space,
                                   const Positions& fixed,
                                   ShellSide unknown_side,
                                   const Eigen::VectorXd& constant,
                                   const std::vector<int>& fixed_vertices,
                                   double tolerance,
                                   double stall_tolerance, int max_steps,
                                   Positions* s) {
  ExpNewtonReport report;
  const std::vector<char> is_fixed =
      FixedFlags(space.num_vertices, fixed_vertices);
  const bool gauge = fixed_vertices.empty();
  const SparseMatrix rows = gauge
                                ? RigidGaugeBasis(fixed)
                                : FreeVertexBasis(space.num_vertices,
                                                  fixed_vertices);
  Eigen::VectorXd f;
  try {
    f = Residual(space, fixed, unknown_side, constant, *s);
  } catch (const InputError&) {
    report.stop_reason = "degenerate initial guess";
    return report;
  }
  report.initial_residual = report.final_residual = MaxNorm(f, is_fixed);
  report.stop_reason = "max steps";
  const PathHessianAssembler assembler(space);
  while (true) {
    if (report.final_residual <= tolerance) {
      report.converged = true;
      report.stop_reason = "converged";
      break;
    }
    if (report.steps >= max_steps) break;
    const SparseMatrix columns = gauge ? RigidGaugeBasis(*s) : rows;
    // J = dF/ds: rows on the fixed shell's gradient, columns on s, reduced
    // to R^T J C straight from the element blocks.
    const SparseMatrix reduced =
        unknown_side == ShellSide::kDeformed
            ? assembler.AssembleMixed(fixed, *s, ShellSide::kReference, rows,
                                      columns)
            : assembler.AssembleMixed(*s, fixed, ShellSide::kDeformed, rows,
                                      columns);
    Eigen::UmfPackLU<SparseMatrix> lu(reduced);
    if (lu.info() != Eigen::Success) {
      report.stop_reason = "singular Jacobian";
      break;
    }
    const Eigen::VectorXd rhs = -(rows.transpose() * f);
    const Eigen::VectorXd q = lu.solve(rhs);
    if (lu.info() != Eigen::Success || !q.allFinite()) {
      report.stop_reason = "singular Jacobian";
      break;
    }
    const Eigen::VectorXd step = columns * q;
    bool accepted = false, stalled = false;
    const double two_norm = TwoNorm(f, is_fixed);
    for (double length = 1; length >= kMinStepLength && !accepted;
         length *= 0.5) {
      Positions candidate = *s;
      Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) +=
          length * step;
      Eigen::VectorXd f_new;
      try {
        f_new = Residual(space, fixed, unknown_side, constant, candidate);
      } catch (const InputError&) {
        continue;  // a degenerate triangle: shorter step
      }
      const double norm = MaxNorm(f_new, is_fixed);
      if (!(norm < report.final_residual) &&
          !(TwoNorm(f_new, is_fixed) < two_norm)) {
        continue;
      }
      stalled = norm <= stall_tolerance && !(norm <= 0.5 * report.final_residual);
      *s = candidate;
      f = std::move(f_new);
      report.final_residual = norm;
      ++report.steps;
      accepted = true;
    }
    if (!accepted) {
      report.stop_reason = "no decrease of |F| along the Newton step";
      break;
    }
    if (stalled && !(report.final_residual <= tolerance)) {
      report.stop_reason = "round-off floor";
      break;
    }
    if (report.steps >= kProgressSteps &&
        !(report.final_residual <= 0.5 * report.initial_residual)) {
      report.stop_reason = "no progress";
      break;
    }
  }
  return report;
}

}  // namespace shellspace
