#include "shellspace/problems/calculus/path_newton.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/geometry/parallel_for.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/reusable_cholesky.h"

namespace shellspace {

namespace {

// The free-coordinate bases of the inner shapes and their offsets in the
// reduced unknown vector.
struct ReducedCoordinates {
  std::vector<SparseMatrix> basis;  // [k - 1] for inner shape k
  std::vector<int> offset;
  std::vector<int> vertex_of;  // mesh vertex of each reduced unknown
  int size = 0;
};

ReducedCoordinates MakeReducedCoordinates(const ShellSpace& space,
                                          const std::vector<int>& fixed,
                                          const ShellPath& path) {
  ReducedCoordinates r;
  const int K = static_cast<int>(path.size()) - 1;
  for (int k = 1; k < K; ++k) {
    r.basis.push_back(fixed.empty()
                          ? RigidGaugeBasis(path[k])
                          : FreeVertexBasis(space.num_vertices, fixed));
    r.offset.push_back(r.size);
    const std::vector<int> vertices = BasisColumnVertices(r.basis.back());
    r.vertex_of.insert(r.vertex_of.end(), vertices.begin(), vertices.end());
    r.size += static_cast<int>(vertices.size());
  }
  return r;
}

// Reduced gradient T^T G of E_K.
Eigen::VectorXd ReducedGradient(const ShellSpace& space, const ShellPath& path,
                                const ReducedCoordinates& r, int threads) {
  const int K = static_cast<int>(path.size()) - 1;
  Eigen::VectorXd g(r.size);
  ParallelFor(K - 1, threads, [&](int i) {
    const int k = i + 1;
    const Eigen::VectorXd full =
        double(K) * (EnergyGradient(space, path[k - 1], path[k],
                            ShellSide::kDeformed) +
             EnergyGradient(space, path[k], path[k + 1],
                            ShellSide::kReference));
    g.segment(r.offset[i], r.basis[i].cols()) = r.basis[i].transpose() * full;
  });
  return g;
}

// Applies s_k += T_k p_k to the inner shapes.
ShellPath StepPath(const ShellPath& path, const ReducedCoordinates& r,
                   const Eigen::VectorXd& p) {
  ShellPath moved = path;
  for (size_t i = 0; i < r.basis.size(); ++i) {
    Positions& s = moved[i + 1];
    Eigen::Map<Eigen::VectorXd>(s.data(), s.size()) +=
        r.basis[i] * p.segment(r.offset[i], r.basis[i].cols());
  }
  return moved;
}

}  // namespace

PathNewtonReport PolishPathNewton(const ShellSpace& space,
                                  const std::vector<int>& fixed_vertices,
                                  const PathNewtonSettings& settings,
                                  ShellPath* path) {
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&]() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
        .count();
  };
  PathNewtonReport report;
  const int K = static_cast<int>(path->size()) - 1;
  if (K < 2) {
    report.converged = true;
    report.stop_reason = "no inner shapes";
    return report;
  }
  const int threads = std::max(1, settings.num_threads);
  const PathHessianAssembler assembler(space);
  ReducedCoordinates r = MakeReducedCoordinates(space, fixed_vertices, *path);
  Eigen::VectorXd g = ReducedGradient(space, *path, r, threads);
  double energy = PathEnergy(space, *path);
  report.initial_gradient = report.final_gradient = g.cwiseAbs().maxCoeff();
  report.stop_reason = "max steps";
  ReusableCholesky linear_solver;
  const double initial_norm = std::max(g.norm(), 1e-300);
  while (true) {
    if (report.final_gradient <= settings.gradient_tolerance) {
      report.converged = true;
      report.stop_reason = "converged";
      break;
    }
    if (report.steps >= settings.max_steps) break;
    double t0 = seconds();
    const SparseMatrix h = assembler.Assemble(*path, r.basis, threads);
    report.assembly_seconds += seconds() - t0;
    Eigen::VectorXd p;
    // Inexact Newton: relative residual of the linear solve (2-norm), tighter
    // as the gradient falls, but no tighter than needed to land below the
    // tolerance (the new gradient is the linear residual to first order).
    const double g_two_norm = std::max(g.norm(), 1e-300);
    const double forcing = std::min(
        0.1, std::max(std::min(1e-2, g_two_norm / initial_norm),
                      0.25 * settings.gradient_tolerance / g_two_norm));
    if (!linear_solver.Solve(h, r.vertex_of, space.num_vertices, -g, forcing,
                             &p)) {
      report.stop_reason = "Hessian not positive definite";
      break;
    }
    bool accepted = false;
    for (double length = 1; length >= 0.25 && !accepted; length *= 0.5) {
      ShellPath candidate = StepPath(*path, r, length * p);
      double candidate_energy = 0;
      try {
        candidate_energy = PathEnergy(space, candidate);
      } catch (const InputError&) {
        continue;  // a degenerate triangle: shorter step
      }
      // Sufficient decrease (Armijo), or, once E_K changes only at round-off
      // level, a smaller gradient.
      const double slope = g.dot(p);  // < 0: H is positive definite
      const bool decrease = candidate_energy <= energy + 1e-4 * length * slope;
      const bool round_off =
          std::abs(candidate_energy - energy) <= 1e-10 * std::abs(energy);
      if (!decrease && !round_off) continue;
      ReducedCoordinates r_new =
          MakeReducedCoordinates(space, fixed_vertices, candidate);
      Eigen::VectorXd g_new = ReducedGradient(space, candidate, r_new, threads);
      const double g_norm = g_new.cwiseAbs().maxCoeff();
      if (!decrease && !(g_norm < report.final_gradient)) continue;
      // Copy into the existing shapes: a ceres::Problem may hold pointers
      // to their coordinates.
      for (int k = 1; k < K; ++k) (*path)[k] = candidate[k];
      r = std::move(r_new);
      g = std::move(g_new);
      energy = candidate_energy;
      report.final_gradient = g_norm;
      ++report.steps;
      accepted = true;
    }
    if (settings.progress) {
      std::fprintf(stderr,
                   "%s step %2d  E_K %.12e  |grad| %.3e  %s  %.2f s"
                   " (Hessian %.2f s, %d Cholesky %.2f s, %d CG %.2f s)\n",
                   settings.progress_label.c_str(), report.steps, energy,
                   report.final_gradient, accepted ? "ok " : "rej", seconds(),
                   report.assembly_seconds,
                   linear_solver.stats().factorizations,
                   linear_solver.stats().factorization_seconds,
                   linear_solver.stats().cg_iterations,
                   linear_solver.stats().cg_seconds);
    }
    if (!accepted) {
      report.stop_reason = "no decrease along the Newton direction";
      break;
    }
  }
  report.seconds = seconds();
  report.factorizations = linear_solver.stats().factorizations;
  report.cg_iterations = linear_solver.stats().cg_iterations;
  report.factorization_seconds = linear_solver.stats().factorization_seconds;
  report.cg_seconds = linear_solver.stats().cg_seconds;
  return report;
}

}  // namespace shellspace

