// The result classes of the solving functions (python/module_results.h).
#include "python/module_results.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "python/module_common.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace pymodule {
namespace {

using workflows::EnergySplit;
using workflows::MaterialChoice;
using workflows::SolveStatus;

std::string Repr(const py::handle& value) {
  return py::repr(value).cast<std::string>();
}

// "Name(a=1, b='x')" of the attributes `fields` of `self`.
std::string ReprOf(const py::object& self, const char* name,
                   const std::vector<const char*>& fields) {
  std::string out = std::string(name) + "(";
  for (size_t i = 0; i < fields.size(); ++i) {
    out += (i ? ", " : "") + std::string(fields[i]) + "=" +
           Repr(self.attr(fields[i]));
  }
  return out + ")";
}

template <class T>
std::vector<double> ListOf(const T& values) {
  return std::vector<double>(values.data(), values.data() + values.size());
}

void RegisterParts(py::module_& m) {
  py::class_<SolveStatus>(
      m, "SolveStatus",
      "How a result's solves ended: name 'converged', 'not converged' (a "
      "solve stopped short of its criterion), 'stopped' (time_limit or "
      "Ctrl-C) or 'failed' (a solve could not run); message one line; "
      "failures one line per solve that missed its criterion.")
      .def_property_readonly("name",
                             [](const SolveStatus& s) {
                               return std::string(SolveStatusName(s.code));
                             })
      .def_property_readonly("converged", &SolveStatus::ok)
      .def_readonly("message", &SolveStatus::message)
      .def_readonly("failures", &SolveStatus::failures)
      .def("__repr__", [](const py::object& self) {
        return ReprOf(self, "SolveStatus", {"name", "message", "failures"});
      });
  py::class_<EnergySplit>(
      m, "EnergySplit",
      "An energy split into its membrane and bending parts (eta included): "
      "membrane + bending = total; bending_share = bending / total.")
      .def_readonly("membrane", &EnergySplit::membrane)
      .def_readonly("bending", &EnergySplit::bending)
      .def_property_readonly("total", &EnergySplit::total)
      .def_property_readonly("bending_share", &EnergySplit::bending_share)
      .def("to_dict",
           [](const EnergySplit& s) {
             py::dict d;
             d["membrane"] = s.membrane;
             d["bending"] = s.bending;
             d["bending_share"] = s.bending_share();
             return d;
           })
      .def("__repr__", [](const py::object& self) {
        return ReprOf(self, "EnergySplit", {"membrane", "bending", "total"});
      });
  py::class_<MaterialChoice>(
      m, "Material",
      "The material of a solve as resolved: mu, lambda_, eta (absolute; "
      "eta_absolute: given as eta rather than relative_eta), the bending "
      "model and the membrane law.")
      .def_property_readonly(
          "mu", [](const MaterialChoice& c) { return c.material.mu; })
      .def_property_readonly(
          "lambda_", [](const MaterialChoice& c) { return c.material.lambda; })
      .def_property_readonly(
          "eta", [](const MaterialChoice& c) { return c.material.eta; })
      .def_readonly("eta_absolute", &MaterialChoice::eta_absolute)
      .def_property_readonly(
          "bending",
          [](const MaterialChoice& c) {
            return std::string(BendingModelName(c.material.bending_model));
          })
      .def_property_readonly(
          "membrane",
          [](const MaterialChoice& c) {
            return std::string(MembraneLawName(c.material.membrane_law));
          })
      .def("__repr__", [](const py::object& self) {
        return ReprOf(self, "Material",
                      {"mu", "lambda_", "eta", "bending", "membrane"});
      });
}

// The material of a workflow's result (the log's is its geodesic's).
template <class Run>
const MaterialChoice& MaterialOfRun(const Run& run) {
  return run.material;
}
const MaterialChoice& MaterialOfRun(const workflows::LogResult& run) {
  return run.geodesic.material;
}

// The class of BoundResult<Run>: the value under `value_name`, summary,
// to_dict, status, converged, material, the pair protocol, and a repr of
// status and `fields`.
template <class Run>
py::class_<BoundResult<Run>> BindResult(py::module_& m, const char* name,
                                        const char* doc, const char* value_name,
                                        std::vector<const char*> fields) {
  using R = BoundResult<Run>;
  py::class_<R> c(m, name, doc);
  c.def_property_readonly(value_name, [](const R& r) { return r.value; })
      .def_property_readonly("summary", [](const R& r) { return r.summary; })
      .def(
          "to_dict",
          [](const R& r) {
            return py::dict(
                py::module_::import("copy").attr("deepcopy")(r.summary));
          },
          "The summary dict (a deep copy: writing into it changes nothing "
          "else): the CLI verb's --json keys.")
      .def_property_readonly("status",
                             [](const R& r) { return StatusOfRun(r.run); })
      .def_property_readonly("converged",
                             [](const R& r) { return StatusOfRun(r.run).ok(); })
      .def_property_readonly("material",
                             [](const R& r) { return MaterialOfRun(r.run); })
      .def("__len__", [](const R&) { return 2; })
      .def("__iter__",
           [](const R& r) {
             return py::iter(py::make_tuple(r.value, r.summary));
           })
      .def("__getitem__",
           [](const R& r, int i) -> py::object {
             if (i < 0) i += 2;
             if (i == 0) return r.value;
             if (i == 1) return r.summary;
             throw py::index_error("a result is the pair (value, summary)");
           })
      // Pickled (to another process, a Dask worker's result) as the plain
      // pair (value, summary): the C++ result stays in this process.
      .def("__reduce__",
           [](const R& r) {
             return py::make_tuple(
                 py::module_::import("builtins").attr("tuple"),
                 py::make_tuple(py::make_tuple(r.value, r.summary)));
           })
      .def("__repr__", [name, fields](const py::object& self) {
        std::string out = std::string(name) +
                          "(status=" + Repr(self.attr("status").attr("name"));
        for (const char* field : fields) {
          out += ", " + std::string(field) + "=" + Repr(self.attr(field));
        }
        return out + ")";
      });
  return c;
}

// The results of geodesic, log, shoot and transport.
void BindCalculusResults(py::module_& m) {
  using Geodesic = BoundResult<workflows::GeodesicResult>;
  BindResult<workflows::GeodesicResult>(
      m, "GeodesicResult",
      "shellspace.geodesic's result: path ((K + 1) x #V x 3), path_energy "
      "E_K, its energy_split, step_energies W[s_k-1, s_k], iterations (LM + "
      "Newton), the initial and final gradient max-norms, init (the initial "
      "path's choice and reason), warnings. Unpacks as (path, summary).",
      "path", {"path_energy", "iterations"})
      .def_property_readonly(
          "path_energy", [](const Geodesic& r) { return r.run.path_energy(); })
      .def_property_readonly(
          "energy_split", [](const Geodesic& r) { return r.run.energy_split; })
      .def_property_readonly(
          "step_energies",
          [](const Geodesic& r) { return r.run.geodesic().step_energies; })
      .def_property_readonly(
          "iterations",
          [](const Geodesic& r) { return r.run.geodesic().iterations; })
      .def_property_readonly(
          "initial_gradient",
          [](const Geodesic& r) { return r.run.geodesic().initial_gradient; })
      .def_property_readonly(
          "final_gradient",
          [](const Geodesic& r) { return r.run.geodesic().final_gradient; })
      .def_property_readonly(
          "init",
          [](const Geodesic& r) { return r.run.geodesic().init.reason; })
      .def_property_readonly("warnings",
                             [](const Geodesic& r) { return r.run.warnings; });

  using Log = BoundResult<workflows::LogResult>;
  BindResult<workflows::LogResult>(
      m, "LogResult",
      "shellspace.log's result: log (#V x 3, K (s_1 - s_0)), log_max_norm, "
      "the geodesic's path, path_energy, energy_split and iterations. "
      "Unpacks as (log, summary).",
      "log", {"log_max_norm", "path_energy", "iterations"})
      .def_property_readonly("log_max_norm",
                             [](const Log& r) { return r.run.log_max_norm; })
      .def_property_readonly(
          "path",
          [](const Log& r) {
            return ReadOnlyArrays(FromPath(r.run.geodesic.path()));
          })
      .def_property_readonly(
          "path_energy",
          [](const Log& r) { return r.run.geodesic.path_energy(); })
      .def_property_readonly(
          "energy_split",
          [](const Log& r) { return r.run.geodesic.energy_split; })
      .def_property_readonly("iterations", [](const Log& r) {
        return r.run.geodesic.geodesic().iterations;
      });

  using Shoot = BoundResult<workflows::ShootResult>;
  BindResult<workflows::ShootResult>(
      m, "ShootResult",
      "shellspace.shoot's result: path ((K + 1) x #V x 3), its energy_split, "
      "exp_steps_solved (one bool per EXP step: F = 0 solved). Unpacks as "
      "(path, summary).",
      "path", {"exp_steps_solved"})
      .def_property_readonly("energy_split",
                             [](const Shoot& r) { return r.run.energy_split; })
      .def_property_readonly("exp_steps_solved", [](const Shoot& r) {
        std::vector<bool> solved;
        for (const ExpStepResult& step : r.run.shot.exp_steps)
          solved.push_back(step.solved);
        return solved;
      });

  using Transport = BoundResult<workflows::TransportResult>;
  BindResult<workflows::TransportResult>(
      m, "TransportResult",
      "shellspace.transport's result: shapes (s_k + epsilon xi_k, (K + 1) x "
      "#V x 3), epsilon, their energy_split, rungs_solved (one bool per "
      "rung of the ladder), warnings. Unpacks as (shapes, summary).",
      "shapes", {"epsilon", "rungs_solved"})
      .def_property_readonly("epsilon",
                             [](const Transport& r) { return r.run.epsilon; })
      .def_property_readonly(
          "energy_split", [](const Transport& r) { return r.run.energy_split; })
      .def_property_readonly("rungs_solved",
                             [](const Transport& r) {
                               std::vector<bool> solved;
                               for (const auto& rung : r.run.transport.rungs)
                                 solved.push_back(rung.solved);
                               return solved;
                             })
      .def_property_readonly("warnings",
                             [](const Transport& r) { return r.run.warnings; });
}

// The results of spline and regress.
void BindSplineResults(py::module_& m) {
  using Spline = BoundResult<workflows::SplineResult>;
  BindResult<workflows::SplineResult>(
      m, "SplineResult",
      "shellspace.spline's result: path ((K + 1) x #V x 3), method, "
      "spline_energy F_K, the energy_split of the path's E_K, iterations "
      "(L-BFGS), optimised (the outer solve ran). Unpacks as (path, "
      "summary).",
      "path", {"method", "spline_energy", "iterations"})
      .def_property_readonly("method",
                             [](const Spline& r) { return r.run.method; })
      .def_property_readonly(
          "spline_energy",
          [](const Spline& r) { return r.run.spline.spline_energy; })
      .def_property_readonly("energy_split",
                             [](const Spline& r) { return r.run.energy_split; })
      .def_property_readonly(
          "iterations", [](const Spline& r) { return r.run.spline.iterations; })
      .def_property_readonly("optimised",
                             [](const Spline& r) { return r.run.optimised; });

  using Regress = BoundResult<workflows::RegressResult>;
  BindResult<workflows::RegressResult>(
      m, "RegressResult",
      "shellspace.regress's result: path ((K + 1) x #V x 3), sigma, "
      "spline_energy F_K, data_energy, objective (data + sigma F_K), the "
      "energy_split of the path's E_K, iterations (L-BFGS). Unpacks as "
      "(path, summary).",
      "path", {"objective", "data_energy", "spline_energy", "iterations"})
      .def_property_readonly("sigma",
                             [](const Regress& r) { return r.run.sigma; })
      .def_property_readonly(
          "spline_energy",
          [](const Regress& r) { return r.run.spline.spline_energy; })
      .def_property_readonly(
          "data_energy",
          [](const Regress& r) { return r.run.spline.data_energy; })
      .def_property_readonly(
          "objective", [](const Regress& r) { return r.run.spline.objective; })
      .def_property_readonly(
          "energy_split", [](const Regress& r) { return r.run.energy_split; })
      .def_property_readonly("iterations", [](const Regress& r) {
        return r.run.spline.iterations;
      });
}

// The results of mean and pca.
void BindStatisticsResults(py::module_& m) {
  using Mean = BoundResult<workflows::MeanResult>;
  BindResult<workflows::MeanResult>(
      m, "MeanResult",
      "shellspace.mean's result: mean (#V x 3), energy (sum_i W[mean, "
      "s_i]), energies (each W), its energy_split, iterations (LM + Newton), "
      "far_inputs (names of inputs far from the mean). Unpacks as (mean, "
      "summary).",
      "mean", {"energy", "iterations"})
      .def_property_readonly("energy",
                             [](const Mean& r) { return r.run.mean.energy; })
      .def_property_readonly("energies",
                             [](const Mean& r) { return r.run.mean.energies; })
      .def_property_readonly("energy_split",
                             [](const Mean& r) { return r.run.energy_split; })
      .def_property_readonly("iterations",
                             [](const Mean& r) {
                               return r.run.mean.lm_iterations +
                                      r.run.mean.newton_iterations;
                             })
      .def_property_readonly("far_inputs",
                             [](const Mean& r) { return r.run.far_inputs; });

  using Pca = BoundResult<workflows::PcaResult>;
  BindResult<workflows::PcaResult>(
      m, "PcaResult",
      "shellspace.pca's result: shapes (dict name -> #V x 3: mean, "
      "mode_j_minus / mode_j_plus, ...), mean (#V x 3), eigenvalues "
      "(lambda_1 >= ... of the shell PCA; empty if it did not run), "
      "failed_shapes, far_inputs. Unpacks as (shapes, summary).",
      "shapes", {"eigenvalues"})
      .def_property_readonly(
          "mean",
          [](const Pca& r) {
            return ReadOnlyArrays(FromPositions(r.run.mean.mean));
          })
      .def_property_readonly("eigenvalues",
                             [](const Pca& r) {
                               return r.run.model
                                          ? ListOf(r.run.model->eigenvalues)
                                          : std::vector<double>();
                             })
      .def_property_readonly("failed_shapes",
                             [](const Pca& r) { return r.run.failed_shapes; })
      .def_property_readonly("far_inputs",
                             [](const Pca& r) { return r.run.far_inputs; });
}

}  // namespace

void RegisterResults(py::module_& m) {
  RegisterParts(m);
  BindCalculusResults(m);
  BindSplineResults(m);
  BindStatisticsResults(m);
}

}  // namespace pymodule
}  // namespace shellspace
