// The module's pieces of the elastic mean and shell PCA for a caller that
// schedules the per-shape work itself (shellspace.collections: tasks in
// this process or on a Dask cluster): elastic_mean_newton (the library's
// Newton finish of the mean on terms the caller sums) and pca_modes (the
// Gram matrix, its eigenpairs and the modes of given displacements),
// shoot_from_mean (a mode shape's EXP shot with the library's safeguard),
// aligned_vertex_average (the mean's start), and the --scheduler values of
// the command line (_parse_scheduler, _most_local_workers).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "python/array_arguments.h"
#include "python/module_common.h"
#include "python/parameter_docs.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/io/scheduler_choice.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/elastic_mean_newton.h"
#include "shellspace/problems/statistics/shell_pca.h"

namespace shellspace {
namespace pymodule {
namespace {

// The terms of a Python callable terms(s) -> None (s degenerate) or
// (energy, gradient #V x 3, (rows, cols, vals): the Hessian's triplets).
ElasticMeanTermsFunction TermsOf(const py::object& terms, int vertices) {
  if (!PyCallable_Check(terms.ptr())) {
    throw InputError("terms must be callable");
  }
  return [terms, vertices](const Positions& s, ElasticMeanTerms* out) {
    const py::object value = terms(FromPositions(s));
    if (value.is_none()) return false;
    const py::tuple parts = py::cast<py::tuple>(value);
    if (parts.size() != 3) {
      throw InputError("terms: expected None or (energy, gradient, "
                       "(rows, cols, vals))");
    }
    out->energy = py::cast<double>(parts[0]);
    const Positions gradient = PositionsArgument(parts[1], "gradient");
    if (gradient.rows() != vertices) {
      throw InputError("terms: the gradient is not #V x 3");
    }
    out->gradient =
        Eigen::Map<const Eigen::VectorXd>(gradient.data(), gradient.size());
    const py::tuple hessian = py::cast<py::tuple>(parts[2]);
    if (hessian.size() != 3) {
      throw InputError("terms: the Hessian is not (rows, cols, vals)");
    }
    out->hessian = TripletsArgument(hessian[0], hessian[1], hessian[2],
                                    3 * vertices);
    return true;
  };
}

// The library's Newton finish of the elastic mean (elastic_mean_newton.h)
// from `initial` on the terms the callable `terms` returns; on_step(|G|_inf,
// E, accepted) after every line search, stop() polled before every step.
py::dict ElasticMeanNewtonPy(const py::object& initial, const py::object& F,
                             const py::object& terms, double tolerance,
                             int max_iterations, const py::object& on_step,
                             const py::object& stop) {
  const Shell shell = MakeShell(initial, F, "initial");
  if (!(tolerance > 0) || !std::isfinite(tolerance)) {
    throw InputError("tolerance must be finite and > 0");
  }
  CheckAtLeast("max_iterations", max_iterations, 1);
  NewtonSettings settings = ElasticMeanNewtonSettings(0, max_iterations);
  if (!on_step.is_none()) {
    settings.progress = [&on_step](const NewtonReport& report, double merit,
                                   bool accepted) {
      on_step(report.final_gradient, merit, accepted);
    };
  }
  if (!stop.is_none()) {
    settings.stop = StopToken([&stop]() { return py::cast<bool>(stop()); });
  }
  Positions s = shell.mesh.positions;
  const SummedTermsMeanReport report = ElasticMeanNewtonOnTerms(
      shell.mesh.faces, TermsOf(terms, shell.mesh.num_vertices()), tolerance,
      settings, &s);
  py::dict out;
  out["mean"] = FromPositions(s);
  out["iterations"] = report.newton.steps;
  out["converged"] = report.newton.converged;
  out["termination"] = report.newton.stop == NewtonStop::kMaxSteps
                           ? std::string("max iterations")
                           : report.newton.stop_reason;
  out["stopped"] = report.newton.stop == NewtonStop::kStopped;
  out["initial_gradient_norm"] = report.initial_gradient_norm;
  out["gradient_norm"] = report.newton.final_gradient;
  out["gradient_target"] = report.gradient_target;
  return out;
}

// ShellGram and ModesFromGram (problems/statistics/shell_pca.h) of the
// displacements at `mean`: (gram, eigenvalues, modes m x #V x 3).
py::tuple PcaModesPy(const py::object& mean, const py::object& displacements,
                     const py::object& F, double relative_cutoff,
                     const MaterialArgs& material_args) {
  const auto [shell, same, space] =
      MakeShellPair(mean, mean, F, "mean", "mean", material_args);
  const std::vector<Positions> v =
      ShapeListArgument(displacements, "displacements");
  for (const Positions& d : v) {
    if (d.rows() != shell.mesh.num_vertices()) {
      throw InputError("displacements: not the mean's vertex count");
    }
  }
  if (!(relative_cutoff >= 0) || !std::isfinite(relative_cutoff)) {
    throw InputError("relative_cutoff must be finite and >= 0");
  }
  const Eigen::MatrixXd gram = ShellGram(ShellMetric(space, shell.mesh.positions), v);
  const GramModes modes = ModesFromGram(gram, v, relative_cutoff);
  py::array_t<double> gram_array({gram.rows(), gram.cols()});
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic,
                           Eigen::RowMajor>>(gram_array.mutable_data(),
                                             gram.rows(), gram.cols()) = gram;
  py::array_t<double> eigenvalues(modes.eigenvalues.size());
  std::copy(modes.eigenvalues.data(),
            modes.eigenvalues.data() + modes.eigenvalues.size(),
            eigenvalues.mutable_data());
  py::array_t<double> mode_array = FromPath(modes.modes);
  return py::make_tuple(gram_array, eigenvalues, mode_array);
}

// TryShootFromMean (problems/statistics/shell_pca.h): EXP_K(mean,
// variation) with the safeguard (K = exp_steps, doubled up to
// max_exp_steps), aligned rigidly to the mean; InputError naming the
// failure if the shot failed.
py::array_t<double> ShootFromMeanPy(const py::object& mean,
                                    const py::object& variation,
                                    const py::object& F, int exp_steps,
                                    int max_exp_steps,
                                    const MaterialArgs& material_args,
                                    const SolverOptions& solver) {
  const Shell shell = MakeShell(mean, F, "mean");
  const Positions v = PositionsArgument(variation, "variation");
  if (v.rows() != shell.mesh.num_vertices()) {
    throw InputError("variation: not the mean's vertex count");
  }
  CheckAtLeast("exp_steps", exp_steps, 1);
  if (max_exp_steps < exp_steps) {
    throw InputError("max_exp_steps must be at least exp_steps");
  }
  const ShellSpace space(shell.mesh, shell.topology,
                         Material(material_args, shell.mesh));
  ShellPcaOptions options;
  options.exp_steps = exp_steps;
  options.max_exp_steps = max_exp_steps;
  Positions shot;
  ExpShotReport report;
  bool ok = false;
  {
    SolveControl::Solving solving(*solver.control);
    ok = TryShootFromMean(space, shell.mesh.positions, v, options,
                          solver.Settings("shoot_from_mean"), &shot, &report);
  }
  if (!ok) throw InputError(report.failure);
  return FromPositions(AlignRigidly(shot, shell.mesh.positions));
}

// ParseScheduler (io/scheduler_choice.h): ("none", None), ("local", N; 0
// for the front end's default) or ("address", ADDRESS).
py::tuple ParseSchedulerPy(const std::string& value) {
  const SchedulerChoice choice = ParseScheduler(value);
  switch (choice.kind) {
    case SchedulerChoice::Kind::kLocal:
      return py::make_tuple("local", choice.local_workers);
    case SchedulerChoice::Kind::kAddress:
      return py::make_tuple("address", choice.address);
    case SchedulerChoice::Kind::kNone:
      break;
  }
  return py::make_tuple("none", py::none());
}

}  // namespace

void RegisterCollections(py::module_& m) {
  m.def("elastic_mean_newton", &ElasticMeanNewtonPy, py::arg("initial"),
        py::arg("F"), py::arg("terms"), py::arg("tolerance") = 1e-8,
        py::arg("max_iterations") = 100, py::arg("on_step") = py::none(),
        py::arg("stop") = py::none(),
        WithParameters(
            "elastic_mean_newton",
            "The Newton finish of the elastic mean argmin_s sum_i W[S_i, s] "
            "(the library's, as shellspace.mean ends) from `initial`, on "
            "terms the caller sums: terms(s) returns None (s degenerate) or "
            "(E(s), G(s) #V x 3, (rows, cols, vals)) with E = sum_i W[S_i, "
            "s], G = sum_i D_2 W[S_i, s] and the triplets of H = sum_i "
            "D_2^2 W[S_i, s]; it is called once per point (the start and "
            "every trial). Steps modulo rigid motions, a line search on E "
            "and H + lambda I where the Newton step fails, until |G|_inf <= "
            "tolerance * max(1, |G(initial)|_inf) or max_iterations "
            "accepted steps. on_step(|G|_inf, E, accepted) after every "
            "line search; stop() is polled before every step (True ends "
            "it). Returns {mean (not aligned), iterations, converged, "
            "termination, stopped, initial_gradient_norm, gradient_norm, "
            "gradient_target}.")
            .c_str());
  m.def(
      "aligned_vertex_average",
      [](const py::object& shapes) {
        const std::vector<Positions> list = ShapeListArgument(shapes, "shapes");
        for (const Positions& shape : list) {
          if (shape.rows() != list[0].rows()) {
            throw InputError("shapes: different vertex counts");
          }
        }
        return FromPositions(AlignedVertexAverage(list));
      },
      py::arg("shapes"),
      WithParameters(
          "aligned_vertex_average",
          "The vertex average (1/n) sum_i A_i(S_i) of the shapes, each "
          "aligned rigidly to the first (A_i: align_rigidly): the start of "
          "the elastic mean.")
          .c_str());
  m.def("shoot_from_mean", WithMaterialAndSolverArgs(&ShootFromMeanPy),
        py::arg("mean"), py::arg("variation"), py::arg("F"),
        py::arg("exp_steps") = 4,
        py::arg("max_exp_steps") = ShellPcaOptions().max_exp_steps,
        SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
        WithParameters(
            "shoot_from_mean",
            "EXP_K(mean, variation) with shellspace.pca's safeguard (K = "
            "exp_steps, doubled up to max_exp_steps while a step has no "
            "solution or the step energies drift by more than half of the "
            "first), aligned rigidly to the mean: a mode shape of the "
            "collections' PCA. InputError naming the step if every attempt "
            "failed.")
            .c_str());
  m.def("_parse_scheduler", &ParseSchedulerPy, py::arg("value"),
        "The --scheduler of the collection front ends (io/scheduler_choice.h):"
        " ('none', None), ('local', N; 0: the default count) or ('address', "
        "ADDRESS); InputError for anything else.");
  m.def("_most_local_workers", &MostLocalWorkers,
        "The most workers local:N starts on this machine: one per core (at "
        "least 2), and 512 MiB of physical memory each.");
  m.def("pca_modes", WithMaterialArgs(&PcaModesPy), py::arg("mean"),
        py::arg("displacements"), py::arg("F"),
        py::arg("relative_cutoff") = ShellPcaOptions().relative_cutoff,
        SHELLSPACE_MATERIAL_ARGS,
        WithParameters(
            "pca_modes",
            "Shell PCA of given displacements v_i at `mean` (shellspace.pca's "
            "model): the metric g(u, w) = 1/2 u^T D_2^2 W[mean, mean] w, the "
            "Gram matrix Gamma_ij = g(v_i, v_j) / n, its eigenvalues "
            "lambda_1 >= ... >= lambda_n and the g-orthonormal modes w_j = "
            "sum_i a^j_i v_i / sqrt(n lambda_j) of the lambda_j > "
            "relative_cutoff * lambda_1 (each signed so that its largest "
            "coefficient a^j_i is positive). Returns (gram n x n, "
            "eigenvalues n, modes m x #V x 3).")
            .c_str());
}

}  // namespace pymodule
}  // namespace shellspace
