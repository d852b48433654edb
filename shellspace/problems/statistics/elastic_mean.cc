#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/problems/statistics/elastic_mean.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/connected_components.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/problems/statistics/elastic_mean_newton.h"
#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

void CheckShapeSet(const ShellSpace& space,
                   const std::vector<Positions>& shapes, const char* what) {
  if (shapes.empty()) {
    throw InputError(std::string(what) + ": need at least one shape");
  }
  for (size_t i = 0; i < shapes.size(); ++i) {
    if (shapes[i].rows() != space.num_vertices) {
      throw InputError(std::string(what) + ": shape " + std::to_string(i) +
                       " has " + std::to_string(shapes[i].rows()) +
                       " vertices, expected " +
                       std::to_string(space.num_vertices));
    }
    if (!shapes[i].allFinite()) {
      throw InputError(std::string(what) + ": shape " + std::to_string(i) +
                       " has a non-finite coordinate");
    }
  }
}

Positions AlignedVertexAverage(const std::vector<Positions>& shapes) {
  if (shapes.empty()) throw InputError("vertex average of no shapes");
  Positions sum = shapes[0];
  for (size_t i = 1; i < shapes.size(); ++i) {
    sum += AlignRigidly(shapes[i], shapes[0]);
  }
  return sum / static_cast<double>(shapes.size());
}

Eigen::VectorXd ElasticMeanGradient(const ShellSpace& space,
                                    const std::vector<Positions>& shapes,
                                    const Positions& s) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(s.size());
  for (const Positions& shape : shapes) {
    g += EnergyGradient(space, shape, s, ShellSide::kDeformed);
  }
  return g;
}

namespace {

// G(s) = sum_i D_2 W[S_i, s]; false if s has a degenerate element.
bool TryElasticMeanGradient(const ShellSpace& space,
                            const std::vector<Positions>& shapes,
                            const Positions& s, Eigen::VectorXd* g) {
  *g = Eigen::VectorXd::Zero(s.size());
  Eigen::VectorXd term;
  for (const Positions& shape : shapes) {
    if (!TryEnergyGradient(space, shape, s, ShellSide::kDeformed, &term)) {
      return false;
    }
    *g += term;
  }
  return true;
}

// E(s) = sum_i W[S_i, s]; +inf if s has a degenerate triangle.
double MeanEnergy(const ShellSpace& space,
                  const std::vector<Positions>& shapes, const Positions& s) {
  double energy = 0;
  DeformationEnergy w;
  for (const Positions& shape : shapes) {
    if (!TryEvaluateDeformationEnergy(space, shape, s, &w)) {
      return std::numeric_limits<double>::infinity();
    }
    energy += w.total;
  }
  return energy;
}

// The elastic-mean problem (elastic_mean_newton.h) with its terms summed
// over the inputs here: E and G per point, H = T^T (sum_i D_2^2 W[S_i, s])
// T assembled by AssembleDeformedSum on `threads` threads.
class ElasticMeanProblem : public ElasticMeanNewtonProblem {
 public:
  ElasticMeanProblem(const ShellSpace& space,
                     const std::vector<Positions>& shapes, int threads,
                     Positions* s)
      : ElasticMeanNewtonProblem(space.faces, s), space_(space),
        shapes_(shapes), threads_(threads), assembler_(space) {}

  EvaluationStatus Assemble(LinearSystem* system) override {
    if (!assembler_.TryAssembleDeformedSum(shapes_, At(NewtonPoint::kCurrent),
                                           basis(), threads_,
                                           &system->matrix)) {
      return EvaluationStatus::kInfeasible;
    }
    system->vertex_of = BasisColumnVertices(basis());
    system->num_vertices = space_.num_vertices;
    return EvaluationStatus::kOk;
  }

 protected:
  bool Energy(NewtonPoint point, double* energy) override {
    *energy = MeanEnergy(space_, shapes_, At(point));
    return std::isfinite(*energy);
  }
  bool Gradient(NewtonPoint point, Eigen::VectorXd* gradient) override {
    return TryElasticMeanGradient(space_, shapes_, At(point), gradient);
  }

 private:
  const ShellSpace& space_;
  const std::vector<Positions>& shapes_;
  const int threads_;
  const PathHessianAssembler assembler_;
};

// The safeguarded Newton iteration of ElasticMeanOptions on *s, until
// |G|_inf <= target. Returns false if the safeguard stopped it.
bool NewtonFinish(const ShellSpace& space, const std::vector<Positions>& shapes,
                  double target, const ElasticMeanOptions& options,
                  const SolverSettings& settings, Positions* s,
                  int* iterations, std::string* stop_reason) {
  ElasticMeanProblem problem(space, shapes, settings.num_threads, s);
  NewtonSettings newton =
      ElasticMeanNewtonSettings(target, options.max_newton_iterations);
  newton.stop = settings.stop;
  const int before = *iterations;
  if (settings.progress) {
    newton.progress = [&](const NewtonReport& r, double, bool accepted) {
      if (!accepted) return;
      std::fprintf(stderr, "%s newton %d  |grad| %.3e  %.2f s\n",
                   settings.progress_label.c_str(), before + r.steps,
                   r.final_gradient, r.seconds);
    };
  }
  ReusableCholesky solver;
  const NewtonReport report = SolveNewton(&problem, &solver, newton);
  *iterations += report.steps;
  *stop_reason = report.stop_reason;
  return report.converged;
}

// The start of the mean: `initial` if given (refused unless it is a finite
// shape of the space), else the aligned vertex average of `shapes`.
Positions StartingMean(const ShellSpace& space,
                       const std::vector<Positions>& shapes,
                       const Positions* initial) {
  if (initial != nullptr) {
    if (initial->rows() != space.num_vertices || !initial->allFinite()) {
      throw InputError("elastic mean: bad initial guess");
    }
    return *initial;
  }
  return AlignedVertexAverage(shapes);
}

// LM chunks on `problem` (the mean's Ceres problem), each followed by a
// Newton attempt, until Newton reaches `target` or the LM iterations are
// used up: the first chunk's summary, the LM and Newton iterations, the
// fallbacks in *result and the last Newton stop reason in *newton_stop.
// Returns whether the last chunk's solution is usable (`usable` if no chunk
// ran).
bool LmChunksWithNewton(const ShellSpace& space,
                        const std::vector<Positions>& shapes,
                        const SolverSettings& settings,
                        const ElasticMeanOptions& options, double target,
                        double reference, bool usable, ceres::Problem* problem,
                        ElasticMeanResult* result, std::string* newton_stop) {
  bool first_chunk = true;
  int attempts = 0;
  while (true) {
    const int remaining = settings.max_iterations - result->lm_iterations -
                          result->newton_iterations;
    if (remaining <= 0) break;
    // The same absolute targets for every chunk: Ceres scales the relative
    // tolerance by max(1, |grad|) at the chunk's start.
    const double start_norm = std::max(1.0, GradientMaxNorm(problem));
    SolverSettings chunk = settings;
    // After a failed Newton attempt LM aims at the final target (else it
    // would stop at once, still at the switch tolerance); after the last
    // attempt it gets all remaining iterations.
    const bool last = attempts >= options.max_newton_attempts;
    chunk.max_iterations =
        last ? remaining : std::min(remaining, options.lm_chunk_iterations);
    chunk.gradient_tolerance =
        (attempts > 0
             ? target
             : std::max(target, options.switch_tolerance * reference)) /
        start_norm;
    const ceres::Solver::Summary summary = SolveWithSettings(problem, chunk);
    if (first_chunk) result->summary = summary;
    first_chunk = false;
    result->lm_iterations +=
        std::max(0, static_cast<int>(summary.iterations.size()) - 1);
    usable = summary.IsSolutionUsable();
    if (!usable || last || StoppedByRequest(summary)) break;
    ++attempts;
    ElasticMeanOptions attempt = options;
    attempt.max_newton_iterations =
        std::min(options.max_newton_iterations, settings.max_iterations -
                                                    result->lm_iterations -
                                                    result->newton_iterations);
    if (attempt.max_newton_iterations <= 0) break;
    if (NewtonFinish(space, shapes, target, attempt, settings, &result->mean,
                     &result->newton_iterations, newton_stop) ||
        settings.stop.stop_requested()) {
      break;
    }
    result->newton_fell_back = true;
  }
  return usable;
}

// |G(mean)|_inf, +inf if the mean has a degenerate element.
double MeanGradientNorm(const ShellSpace& space,
                        const std::vector<Positions>& shapes, int threads,
                        Positions* mean) {
  NewtonResidual g;
  ElasticMeanProblem at_mean(space, shapes, threads, mean);
  return at_mean.Residual(NewtonPoint::kCurrent, &g) == EvaluationStatus::kOk
             ? g.max_norm
             : std::numeric_limits<double>::infinity();
}

// Why the mean's solve ended, for ElasticMeanResult::termination.
std::string ElasticMeanTermination(const ElasticMeanResult& result, bool usable,
                                   const SolverSettings& settings,
                                   const std::string& newton_stop) {
  if (result.converged) {
    return "converged";
  } else if (!usable) {
    return "LM failed";
  } else if (result.lm_iterations + result.newton_iterations >=
             settings.max_iterations) {
    return "max iterations";
  } else if (!newton_stop.empty()) {
    return "Newton: " + newton_stop;
  } else {
    return std::string("LM: ") +
           ceres::TerminationTypeToString(result.summary.termination_type);
  }
}

}  // namespace

ElasticMeanResult ComputeElasticMean(const ShellSpace& space,
                                     const std::vector<Positions>& shapes,
                                     const SolverSettings& settings,
                                     const Positions* initial,
                                     const ElasticMeanOptions& options) {
  CheckShapeSet(space, shapes, "elastic mean");
  if (!(options.switch_tolerance > 0) || options.max_newton_iterations < 0) {
    throw InputError("elastic mean: bad Newton options");
  }
  ElasticMeanResult result;
  result.mean = StartingMean(space, shapes, initial);
  ceres::Problem problem;
  for (const Positions& shape : shapes) {
    AddDeformationEnergy(space, ShellArgument::Fixed(shape),
                         ShellArgument::Variable(&result.mean), 1.0, &problem);
  }
  PinRigidMotions(&result.mean, &problem,
                  ConnectedComponents(space.faces, space.num_vertices));
  // The absolute target of MakeSolverOptions, fixed by the initial guess.
  result.initial_gradient_norm = GradientMaxNorm(&problem);
  const double reference = std::max(1.0, result.initial_gradient_norm);
  const double target = settings.gradient_tolerance * reference;

  if (!options.newton) {
    result.summary = SolveWithSettings(&problem, settings);
    result.lm_iterations =
        std::max(0, static_cast<int>(result.summary.iterations.size()) - 1);
  }
  std::string newton_stop;
  bool usable = !options.newton || result.summary.IsSolutionUsable();
  // LM chunks, each followed by a Newton attempt, until Newton reaches the
  // target or the LM iterations are used up.
  if (options.newton) {
    usable =
        LmChunksWithNewton(space, shapes, settings, options, target, reference,
                           usable, &problem, &result, &newton_stop);
  }
  result.gradient_norm =
      MeanGradientNorm(space, shapes, settings.num_threads, &result.mean);
  result.gradient_target = target;
  result.converged = usable && result.gradient_norm <= target;
  result.termination =
      ElasticMeanTermination(result, usable, settings, newton_stop);
  result.mean = AlignRigidly(result.mean, shapes[0]);
  for (const Positions& shape : shapes) {
    result.energies.push_back(
        EvaluateDeformationEnergy(space, shape, result.mean).total);
    result.energy += result.energies.back();
  }
  return result;
}

double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<int> FarInputs(const std::vector<double>& energies,
                           double factor) {
  std::vector<int> far;
  if (energies.size() < 3) return far;
  const double median = Median(energies);
  if (!(median > 0)) return far;
  for (int i = 0; i < static_cast<int>(energies.size()); ++i) {
    if (energies[i] > factor * median) far.push_back(i);
  }
  return far;
}

}  // namespace shellspace
