#include "shellspace/problems/calculus/path_newton.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <array>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/runtime/blas_threads.h"
#include "shellspace/problems/calculus/path_energy.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/problems/calculus/stiff_vertex_elimination.h"
#include "shellspace/geometry/connected_components.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/solvers/block_jacobi_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/rigid_gauge.h"

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

using GaugeTriples = std::vector<std::array<int, 3>>;

// ChooseGaugeVertices of `shape`, one triple per connected component of the
// solve's space (`components`). One component: chosen in the caller's
// numbering and given as vertices of the solve's space
// (PathNewtonSettings::renumbering; null: the same).
GaugeTriples GaugeVertices(const Positions& shape,
                           const RenumberedShellSpace* renumbering,
                           const std::vector<std::vector<int>>& components) {
  if (components.size() > 1) return ChooseGaugeVertices(shape, components);
  if (renumbering == nullptr) return {ChooseGaugeVertices(shape)};
  std::array<int, 3> vertices =
      ChooseGaugeVertices(renumbering->ToOriginal(shape));
  for (int& v : vertices) v = renumbering->new_vertex[v];
  return {vertices};
}

// Without a mask: one choice of gauge vertices for every inner shape (those
// of the middle one), so that all slices have the same free coordinates and
// their Hessian blocks one pattern (the time-coupled preconditioner needs
// it); none if a, b, c of a triple are nearly collinear in some inner shape
// (c closer than 1e-3 |ab| to the line ab), and each shape then gets its
// own.
std::optional<GaugeTriples> SharedGaugeVertices(
    const ShellPath& path, const RenumberedShellSpace* renumbering,
    const std::vector<std::vector<int>>& components) {
  const int K = static_cast<int>(path.size()) - 1;
  if (K < 2) return std::nullopt;
  const GaugeTriples triples =
      GaugeVertices(path[K / 2], renumbering, components);
  for (const auto& [a, b, c] : triples) {
    for (int k = 1; k < K; ++k) {
      const Eigen::Vector3d ab = (path[k].row(b) - path[k].row(a)).transpose();
      const Eigen::Vector3d ac = (path[k].row(c) - path[k].row(a)).transpose();
      if (!(ab.norm() > 0) ||
          !(ab.cross(ac).norm() >= 1e-3 * ab.squaredNorm())) {
        return std::nullopt;
      }
    }
  }
  return triples;
}

ReducedCoordinates MakeReducedCoordinates(
    const ShellSpace& space, const std::vector<int>& fixed,
    const ShellPath& path, const std::optional<GaugeTriples>& gauge,
    const RenumberedShellSpace* renumbering,
    const std::vector<std::vector<int>>& components) {
  ReducedCoordinates r;
  const int K = static_cast<int>(path.size()) - 1;
  for (int k = 1; k < K; ++k) {
    r.basis.push_back(
        !fixed.empty() ? FreeVertexBasis(space.num_vertices, fixed)
        : gauge        ? RigidGaugeBasis(path[k], *gauge)
                       : RigidGaugeBasis(path[k], GaugeVertices(path[k],
                                                                renumbering,
                                                                components)));
    r.offset.push_back(r.size);
    const std::vector<int> vertices = BasisColumnVertices(r.basis.back());
    r.vertex_of.insert(r.vertex_of.end(), vertices.begin(), vertices.end());
    r.size += static_cast<int>(vertices.size());
  }
  return r;
}

// Reduced gradient T^T G of E_K; false if an element is degenerate.
bool TryReducedGradient(const ShellSpace& space, const ShellPath& path,
                        const ReducedCoordinates& r, int threads,
                        Eigen::VectorXd* g) {
  g->resize(r.size);
  return ForEachInnerShapeGradient(
      space, path, threads, [&](int i, const Eigen::VectorXd& gk) {
        g->segment(r.offset[i], r.basis[i].cols()) =
            r.basis[i].transpose() * gk;
      });
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

// E_K over the inner shapes of *path (ends fixed) for SolveNewton: merit
// E_K, residual the reduced gradient T^T G, H by PathHessianAssembler on the
// bases of the current shapes, retraction s_k += T_k p_k.
class PathEnergyProblem : public NewtonProblem {
 public:
  PathEnergyProblem(const ShellSpace& space, const std::vector<int>& fixed,
                    int threads, HessianModel model, double min_area_fraction,
                    const RenumberedShellSpace* renumbering, ShellPath* path)
      : space_(space),
        min_area_fraction_(min_area_fraction),
        fixed_(fixed),
        threads_(threads),
        assembler_(space, model),
        path_(path),
        renumbering_(renumbering),
        components_(fixed.empty() ? ConnectedComponents(space.faces,
                                                        space.num_vertices)
                                  : std::vector<std::vector<int>>{}),
        gauge_(fixed.empty()
                   ? SharedGaugeVertices(*path, renumbering, components_)
                   : std::nullopt),
        reduced_(MakeReducedCoordinates(space, fixed, *path, gauge_,
                                        renumbering, components_)) {}

  EvaluationStatus Merit(NewtonPoint point, double* merit) override {
    const ShellPath& path = point == NewtonPoint::kCurrent ? *path_ : trial_;
    if (point == NewtonPoint::kTrial && min_area_fraction_ > 0 &&
        CrushesATriangle(*path_, trial_)) {
      return EvaluationStatus::kInfeasible;
    }
    const std::optional<double> energy = TryPathEnergy(space_, path);
    if (!energy) return EvaluationStatus::kInfeasible;
    *merit = *energy;
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Residual(NewtonPoint point,
                            NewtonResidual* residual) override {
    if (point == NewtonPoint::kTrial) {
      trial_reduced_ =
          MakeReducedCoordinates(space_, fixed_, trial_, gauge_, renumbering_,
                                 components_);
    }
    const ShellPath& path = point == NewtonPoint::kCurrent ? *path_ : trial_;
    const ReducedCoordinates& r =
        point == NewtonPoint::kCurrent ? reduced_ : trial_reduced_;
    Eigen::VectorXd g;
    if (!TryReducedGradient(space_, path, r, threads_, &g)) {
      return EvaluationStatus::kInfeasible;
    }
    *residual = NewtonResidual::OfReduced(g);
    if (point == NewtonPoint::kTrial) {
      trial_norm_ = residual->max_norm;
    } else if (!(current_norm_ >= 0)) {
      current_norm_ = best_norm_ = residual->max_norm;  // the stage's start
    }
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Assemble(LinearSystem* system) override {
    // The last H is overwritten in place (its storage reused: the pattern
    // is the same every iteration); the assembler allocates the element
    // blocks of the new one only after it has the storage.
    if (!assembler_.TryAssemble(*path_, reduced_.basis, threads_,
                                &system->matrix)) {
      return EvaluationStatus::kInfeasible;
    }
    system->vertex_of = reduced_.vertex_of;
    system->num_vertices = space_.num_vertices;
    system->block_offsets = reduced_.offset;
    system->block_offsets.push_back(reduced_.size);
    return EvaluationStatus::kOk;
  }
  int unknowns() const { return reduced_.size; }
  // PathNewtonSettings::min_area_fraction: a triangle of an inner shape of
  // `trial` below that fraction of its area in `current`, or turned over.
  bool CrushesATriangle(const ShellPath& current,
                        const ShellPath& trial) const {
    const Faces& faces = space_.faces;
    const int K = static_cast<int>(current.size()) - 1;
    for (int k = 1; k < K; ++k) {
      for (int f = 0; f < faces.rows(); ++f) {
        const Eigen::Vector3d before = FaceNormal(faces, current[k], f);
        const Eigen::Vector3d after = FaceNormal(faces, trial[k], f);
        if (after.dot(before) < 0 ||
            after.norm() < min_area_fraction_ * before.norm()) {
          return true;
        }
      }
    }
    return false;
  }
  void SetTrial(const Eigen::VectorXd& step) override {
    trial_ = StepPath(*path_, reduced_, step);
    if (elimination_ != nullptr) {
      // The elimination's own trials keep min_area_fraction of the areas it
      // starts from; its result is held to the step limit against the
      // current path, as the plain trial is, and dropped if it breaks it
      // (the plain trial is then judged as it is).
      // Solve changes only the stiff rows of the inner shapes: those are
      // kept, not the whole path.
      const std::vector<int>& stiff = elimination_->stiff_vertices();
      const int K = static_cast<int>(trial_.size()) - 1;
      std::vector<Positions> plain(K + 1);
      for (int k = 1; k < K; ++k) plain[k] = trial_[k](stiff, Eigen::all);
      elimination_->Solve(kEliminationNewtonSteps, elimination_tolerance_,
                          &trial_);
      if (min_area_fraction_ > 0 && CrushesATriangle(*path_, trial_)) {
        ShellPath relaxed_rows = trial_;
        for (int k = 1; k < K; ++k) trial_[k](stiff, Eigen::all) = plain[k];
        if (CrushesATriangle(*path_, trial_)) trial_ = std::move(relaxed_rows);
      }
    }
  }
  void SetElimination(StiffVertexElimination* elimination,
                      double tolerance) {
    elimination_ =
        elimination != nullptr && !elimination->empty() ? elimination : nullptr;
    elimination_tolerance_ = tolerance;
  }
  void AcceptTrial() override {
    // Leaving the best iterate for a worse one: keep a copy of it.
    if (current_is_best_ && !(trial_norm_ < best_norm_)) best_ = *path_;
    // Copy into the existing shapes: a ceres::Problem may hold pointers to
    // their coordinates.
    const int K = static_cast<int>(path_->size()) - 1;
    for (int k = 1; k < K; ++k) (*path_)[k] = trial_[k];
    reduced_ = std::move(trial_reduced_);
    current_norm_ = trial_norm_;
    current_is_best_ = current_norm_ < best_norm_;
    if (current_is_best_) best_norm_ = current_norm_;
  }
  // The best-iterate rule: if an accepted step has left the iterate with the
  // smallest gradient max norm (the stage's start included) for a worse one,
  // puts that iterate back into the path and returns its norm; otherwise
  // returns a negative number (the path is the best iterate).
  double RestoreBestIterate() {
    if (current_is_best_ || best_.empty()) return -1;
    const int K = static_cast<int>(path_->size()) - 1;
    for (int k = 1; k < K; ++k) (*path_)[k] = best_[k];
    current_is_best_ = true;
    current_norm_ = best_norm_;
    return best_norm_;
  }
  double current_norm() const { return current_norm_; }

 private:
  const ShellSpace& space_;
  const double min_area_fraction_;
  const std::vector<int>& fixed_;
  const int threads_;
  const PathHessianAssembler assembler_;
  ShellPath* path_;
  const RenumberedShellSpace* renumbering_;
  // Without a mask: the solve space's connected components (a rigid gauge
  // in each), and the gauge vertices of every inner shape, chosen once.
  const std::vector<std::vector<int>> components_;
  const std::optional<GaugeTriples> gauge_;
  ReducedCoordinates reduced_;
  ShellPath trial_;
  ReducedCoordinates trial_reduced_;
  StiffVertexElimination* elimination_ = nullptr;
  double elimination_tolerance_ = 0;
  // Gradient max norms: of the last trial evaluated, of the current point,
  // of the best point so far (-1: not yet evaluated); the best point's path
  // while the current point is another.
  double trial_norm_ = -1, current_norm_ = -1, best_norm_ = -1;
  bool current_is_best_ = true;
  ShellPath best_;
};

}  // namespace

namespace {

// PathNewtonSettings::keep_best_iterate: where the stage ended above the
// smallest gradient it met, that iterate is put back and reported.
PathNewtonReport KeepBestIterate(const PathNewtonSettings& settings,
                                 PathEnergyProblem* problem,
                                 PathNewtonReport report) {
  if (!settings.keep_best_iterate || report.converged) return report;
  const double last = report.final_gradient;
  const double best = problem->RestoreBestIterate();
  if (best < 0) return report;
  double merit = 0;
  problem->Merit(NewtonPoint::kCurrent, &merit);
  report.final_gradient = best;
  report.final_merit = merit;
  report.restored_best = true;
  char text[160];
  std::snprintf(text, sizeof text,
                "; the best iterate kept (|grad| %.3g, the last %.3g)", best,
                last);
  report.stop_reason += text;
  return report;
}

}  // namespace

PathLinearSolver ChooseLinearSolver(PathLinearSolver choice, int unknowns) {
  if (choice != PathLinearSolver::kAuto) return choice;
  return unknowns >= kBlockJacobiFromUnknowns ? PathLinearSolver::kBlockJacobi
                                              : PathLinearSolver::kDirect;
}

PathLinearSolvers::PathLinearSolvers() = default;
PathLinearSolvers::~PathLinearSolvers() = default;

BlockJacobiSolver& PathLinearSolvers::block_jacobi() {
  if (!block_jacobi_) block_jacobi_ = std::make_unique<BlockJacobiSolver>();
  return *block_jacobi_;
}

namespace {

// The Newton engine's settings of a path solve with these settings
// (progress lines "LABEL step ..." when settings.progress).
NewtonSettings EngineSettings(const PathNewtonSettings& settings) {
  const bool levenberg_marquardt =
      settings.globalisation ==
      NewtonSettings::Globalisation::kLevenbergMarquardt;
  NewtonSettings newton;
  newton.mode = NewtonMode::kMinimize;
  newton.max_steps = settings.max_steps;
  newton.tolerance = settings.gradient_tolerance;
  newton.forcing_rule = NewtonSettings::Forcing::kInexactNewton;
  newton.forcing = settings.forcing;
  newton.max_halvings = 2;
  newton.accept_smaller_max_norm = true;
  newton.merit_round_off = 1e-10;
  newton.max_shifts = settings.max_shifts;
  newton.stop = settings.stop;
  newton.hand_over_contraction = settings.hand_over_contraction;
  newton.stall_steps = settings.stall_steps;
  newton.tr_basin_ratio = settings.basin_ratio;
  newton.globalisation = settings.globalisation;
  if (levenberg_marquardt) {
    newton.lm_initial = settings.lm_initial;
    if (settings.model == HessianModel::kGaussNewton) {
      // Far from the geodesic: a rough step is enough.
      newton.forcing_rule = NewtonSettings::Forcing::kFixed;
      newton.forcing = 1e-1;
    }
  }
  if (settings.progress) {
    const std::string label = settings.progress_label;
    newton.progress = [label](const NewtonReport& r, double energy,
                              bool accepted) {
      std::fprintf(stderr,
                   "%s step %2d  E_K %.12e  |grad| %.3e  %s%s  %.2f s"
                   " (Hessian %.2f s, %d %s factorisations %.2f s, %d CG"
                   " %.2f s)\n",
                   label.c_str(), r.steps, energy,
                   r.final_gradient, accepted ? "ok " : "rej",
                   r.max_shift > 0                ? " shifted"
                   : r.negative_curvature_steps > 0 ? " neg-curv"
                   : r.boundary_steps > 0           ? " boundary"
                                                    : "",
                   r.seconds,
                   r.assembly_seconds, r.factorizations,
                   r.linear_solver.c_str(),
                   r.factorization_seconds, r.cg_iterations, r.cg_seconds);
    };
  }
  return newton;
}

}  // namespace

PathNewtonReport PolishPathNewton(const ShellSpace& space,
                                  const std::vector<int>& fixed_vertices,
                                  const PathNewtonSettings& settings,
                                  ShellPath* path) {
  const int K = static_cast<int>(path->size()) - 1;
  if (K < 2) {
    PathNewtonReport report;
    report.converged = true;
    report.stop = NewtonStop::kConverged;
    report.stop_reason = "no inner shapes";
    return report;
  }
  // The line search always runs on the exact Hessian (with its shifts).
  const bool line_search =
      settings.globalisation == NewtonSettings::Globalisation::kLineSearch;
  PathEnergyProblem problem(
      space, fixed_vertices, std::max(1, settings.num_threads),
      line_search ? HessianModel::kExact : settings.model,
      settings.min_area_fraction, settings.renumbering, path);
  problem.SetElimination(settings.elimination, settings.gradient_tolerance);
  const NewtonSettings newton = EngineSettings(settings);
  // The block-Jacobi solver of the stage before (settings.solvers: its
  // analysis kept, its factors dropped) or of this stage alone.
  PathLinearSolvers own_solvers;
  PathLinearSolvers& solvers =
      settings.solvers != nullptr ? *settings.solvers : own_solvers;
  if (ChooseLinearSolver(settings.linear_solver, problem.unknowns()) ==
      PathLinearSolver::kBlockJacobi) {
    // The blocks' factorisations and solves run in parallel over the
    // slices; OpenBLAS inside each with one thread (two levels of threads
    // would only spin).
    const ScopedBlasThreads one_blas_thread(1);
    BlockJacobiSolver& linear_solver = solvers.block_jacobi();
    linear_solver.ForgetFactors();
    linear_solver.threads = std::max(1, settings.num_threads);
    linear_solver.time_coupling = settings.time_coupled_preconditioner;
    return KeepBestIterate(settings, &problem,
                           SolveNewton(&problem, &linear_solver, newton));
  }
  ReusableCholesky linear_solver;
  return KeepBestIterate(settings, &problem,
                         SolveNewton(&problem, &linear_solver, newton));
}

}  // namespace shellspace
