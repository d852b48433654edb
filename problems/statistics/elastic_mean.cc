#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/problems/statistics/elastic_mean.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/problems/calculus/path_hessian.h"
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

// E(s) = sum_i W[S_i, s], G(s), |G(s)|_2 and |G(s)|_inf; all +inf if s has
// a degenerate triangle.
struct GradientNorms {
  Eigen::VectorXd g;
  double energy = std::numeric_limits<double>::infinity();
  double two = std::numeric_limits<double>::infinity();
  double inf = std::numeric_limits<double>::infinity();
};
GradientNorms NormsAt(const ShellSpace& space,
                      const std::vector<Positions>& shapes,
                      const Positions& s) {
  GradientNorms n;
  double energy = 0;
  try {
    n.g = ElasticMeanGradient(space, shapes, s);
    for (const Positions& shape : shapes) {
      energy += EvaluateDeformationEnergy(space, shape, s).total;
    }
  } catch (const InputError&) {
    return n;
  }
  if (!n.g.allFinite() || !std::isfinite(energy)) return n;
  n.energy = energy;
  n.two = n.g.norm();
  n.inf = n.g.cwiseAbs().maxCoeff();
  return n;
}

// The safeguarded Newton iteration of ElasticMeanOptions on *s, until
// |G|_inf <= target. Returns false if the safeguard stopped it.
bool NewtonFinish(const ShellSpace& space, const std::vector<Positions>& shapes,
                  double target, const ElasticMeanOptions& options,
                  const SolverSettings& settings, Positions* s,
                  int* iterations) {
  const auto clock = std::chrono::steady_clock::now();
  const PathHessianAssembler assembler(space);
  ReusableCholesky solver;
  GradientNorms current = NormsAt(space, shapes, *s);
  for (int it = 0; it < options.max_newton_iterations; ++it) {
    if (current.inf <= target) return true;
    if (!std::isfinite(current.two)) return false;
    // H = sum_i D_2^2 W[S_i, s] modulo rigid motions (p = T q).
    Eigen::VectorXd p;
    try {
      const SparseMatrix basis = RigidGaugeBasis(*s);
      const SparseMatrix h = assembler.AssembleDeformedSum(
          shapes, *s, basis, settings.num_threads);
      const std::vector<int> vertex_of = BasisColumnVertices(basis);
      Eigen::VectorXd q;
      const Eigen::VectorXd rhs = -(basis.transpose() * current.g);
      if (!solver.Solve(h, vertex_of, space.num_vertices, rhs, 1e-10, &q)) {
        return false;  // H not positive definite
      }
      p = basis * q;
    } catch (const InputError&) {
      return false;
    }
    const double slope = current.g.dot(p);
    if (!p.allFinite() || !(slope < 0)) return false;
    bool accepted = false;
    for (double t = 1.0; t >= 1.0 / 16; t *= 0.5) {
      Positions candidate = *s;
      Eigen::Map<Eigen::VectorXd>(candidate.data(), candidate.size()) += t * p;
      GradientNorms next = NormsAt(space, shapes, candidate);
      if (next.energy <= current.energy + 1e-4 * t * slope ||
          next.two < current.two) {
        *s = candidate;  // in place: the Ceres problem points into *s
        current = std::move(next);
        accepted = true;
        break;
      }
    }
    if (!accepted) return false;
    ++*iterations;
    if (settings.progress) {
      std::fprintf(stderr, "%s newton %d  |grad| %.3e  %.2f s\n",
                   settings.progress_label.c_str(), *iterations, current.inf,
                   std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - clock)
                       .count());
    }
  }
  return current.inf <= target;
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
  if (initial != nullptr) {
    if (initial->rows() != space.num_vertices || !initial->allFinite()) {
      throw InputError("elastic mean: bad initial guess");
    }
    result.mean = *initial;
  } else {
    result.mean = AlignedVertexAverage(shapes);
  }
  ceres::Problem problem;
  for (const Positions& shape : shapes) {
    AddDeformationEnergy(space, ShellArgument::Fixed(shape),
                         ShellArgument::Variable(&result.mean), 1.0, &problem);
  }
  PinRigidMotions(&result.mean, &problem);
  // The absolute target of MakeSolverOptions, fixed by the initial guess.
  result.initial_gradient_norm = GradientMaxNorm(&problem);
  const double reference = std::max(1.0, result.initial_gradient_norm);
  const double target = settings.gradient_tolerance * reference;

  if (!options.newton) {
    result.summary = SolveWithSettings(&problem, settings);
    result.lm_iterations = static_cast<int>(result.summary.iterations.size());
  }
  bool usable = !options.newton || result.summary.IsSolutionUsable();
  // LM chunks, each followed by a Newton attempt, until Newton reaches the
  // target or the LM iterations are used up.
  bool first_chunk = true;
  int attempts = 0;
  while (options.newton) {
    const int remaining = settings.max_iterations - result.lm_iterations;
    if (remaining <= 0) break;
    // The same absolute targets for every chunk: Ceres scales the relative
    // tolerance by max(1, |grad|) at the chunk's start.
    const double start_norm = std::max(1.0, GradientMaxNorm(&problem));
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
    const ceres::Solver::Summary summary = SolveWithSettings(&problem, chunk);
    if (first_chunk) result.summary = summary;
    first_chunk = false;
    result.lm_iterations += static_cast<int>(summary.iterations.size());
    usable = summary.IsSolutionUsable();
    if (!usable || last) break;
    ++attempts;
    if (NewtonFinish(space, shapes, target, options, settings, &result.mean,
                     &result.newton_iterations)) {
      break;
    }
    result.newton_fell_back = true;
  }
  result.gradient_norm = NormsAt(space, shapes, result.mean).inf;
  result.converged = usable && result.gradient_norm <= target;
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
