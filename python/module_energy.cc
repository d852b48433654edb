// The module's elastic energy of one pair of shells and its derivatives:
// energy, energy_gradient, energy_hessian; and the rigid motions:
// solve_modulo_rigid_motions, align_rigidly.
#include <cmath>
#include <string>
#include <vector>

#include "python/array_arguments.h"
#include "python/module_common.h"
#include "python/parameter_docs.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/reports/shape_reports.h"
#include "shellspace/solvers/gauge_reduced_solve.h"

namespace shellspace {
namespace pymodule {
namespace {

ShellSide Side(const std::string& side, const std::string& name) {
  if (side == "reference") return ShellSide::kReference;
  if (side == "deformed") return ShellSide::kDeformed;
  throw InputError(name + " must be 'reference' or 'deformed', got '" + side +
                   "'");
}

py::object EnergyPy(const py::object& reference, const py::object& deformed,
                    const py::object& F, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const DeformationEnergy e =
      EvaluateDeformationEnergy(space, shell.mesh.positions, d);
  return ToDict(EnergyJson(e, space.material));
}

py::array_t<double> GradientPy(const py::object& reference,
                               const py::object& deformed, const py::object& F,
                               const std::string& side, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const Eigen::VectorXd g =
      EnergyGradient(space, shell.mesh.positions, d, Side(side, "side"));
  Positions out(shell.mesh.num_vertices(), 3);
  std::copy(g.data(), g.data() + g.size(), out.data());
  return FromPositions(out);
}

py::tuple HessianPy(const py::object& reference, const py::object& deformed,
                    const py::object& F, const std::string& rows,
                    const std::string& cols, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const SparseMatrix H = EnergyHessian(space, shell.mesh.positions, d,
                                       Side(rows, "rows"), Side(cols, "cols"));
  const py::ssize_t nnz = H.nonZeros();
  py::array_t<long long> r(nnz), c(nnz);
  py::array_t<double> v(nnz);
  py::ssize_t i = 0;
  for (int k = 0; k < H.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(H, k); it; ++it, ++i) {
      r.mutable_data()[i] = it.row();
      c.mutable_data()[i] = it.col();
      v.mutable_data()[i] = it.value();
    }
  }
  return py::make_tuple(r, c, v);
}

// SolveModuloRigidMotions (solvers/gauge_reduced_solve.h) of the triplets
// of H (duplicates summed), for a caller that sums the Hessian and gradient
// itself. Returns (p #V x 3, positive_definite).
py::tuple SolveModuloRigidMotionsPy(const py::object& rows_object,
                                    const py::object& cols_object,
                                    const py::object& vals_object,
                                    const py::object& rhs_object,
                                    const py::object& shape_object,
                                    double shift) {
  const Positions shape = PositionsArgument(shape_object, "shape");
  const Positions rhs = PositionsArgument(rhs_object, "rhs");
  const long long n = 3 * static_cast<long long>(shape.rows());
  if (rhs.rows() != shape.rows()) {
    throw InputError("rhs: " + std::to_string(rhs.rows()) +
                     " rows, expected " + std::to_string(shape.rows()));
  }
  if (!(shift >= 0) || !std::isfinite(shift)) {
    throw InputError("shift must be finite and >= 0");
  }
  const SparseMatrix h = TripletsArgument(rows_object, cols_object, vals_object, n);
  const GaugeReducedStep step = SolveModuloRigidMotions(
      h, Eigen::Map<const Eigen::VectorXd>(rhs.data(), rhs.size()), shape,
      shift);
  Positions p(shape.rows(), 3);
  std::copy(step.p.data(), step.p.data() + step.p.size(), p.data());
  return py::make_tuple(FromPositions(p), step.positive_definite);
}

}  // namespace

void RegisterEnergy(py::module_& m) {
  m.def("energy", WithMaterialArgs(&EnergyPy), py::arg("reference"),
        py::arg("deformed"), py::arg("F"), SHELLSPACE_MATERIAL_ARGS,
        WithParameters(
            "energy",
            "W[reference, deformed] = W_mem + eta W_bend: the `energy` verb's "
            "summary {membrane, bending, total, mu, lambda, eta}.")
            .c_str());
  m.def("energy_gradient", WithMaterialArgs(&GradientPy), py::arg("reference"),
        py::arg("deformed"), py::arg("F"), py::arg("side") = "deformed",
        SHELLSPACE_MATERIAL_ARGS,
        WithParameters(
            "energy_gradient",
            "D_2 W (side='deformed') or D_1 W (side='reference') as a #V x 3 "
            "array (the derivative by vertex v, coordinate c at [v, c]).")
            .c_str());
  m.def(
      "energy_hessian", WithMaterialArgs(&HessianPy), py::arg("reference"),
      py::arg("deformed"), py::arg("F"), py::arg("rows") = "deformed",
      py::arg("cols") = "deformed", SHELLSPACE_MATERIAL_ARGS,
      WithParameters(
          "energy_hessian",
          "The 3#V x 3#V block d_rows d_cols W (coordinate 3 v + c) as "
          "triplets (rows, cols, vals): scipy.sparse.coo_matrix((vals, (rows, "
          "cols)), shape=(3 * nV, 3 * nV)). rows/cols: 'deformed' or "
          "'reference' ('reference', 'deformed' is the mixed D_1 D_2 W).")
          .c_str());

  m.def("solve_modulo_rigid_motions", &SolveModuloRigidMotionsPy,
        py::arg("rows"), py::arg("cols"), py::arg("vals"), py::arg("rhs"),
        py::arg("shape"), py::arg("shift") = 0.0,
        WithParameters(
            "solve_modulo_rigid_motions",
            "p solving H p = rhs modulo rigid motions: H the 3#V x 3#V "
            "triplets (rows, cols, vals; duplicates summed) of a rigidly "
            "invariant energy's Hessian at `shape`, p = T q with T the "
            "coordinates left by the rigid gauge of `shape` (three gauge "
            "vertices pinned) and (T^T H T + shift I) q = T^T rhs (sparse "
            "LDL^T). Returns (p #V x 3, positive_definite): "
            "positive_definite is True when the factorisation succeeded, "
            "every pivot of the reduced matrix is > 0 and p is finite; when "
            "the factorisation fails p is all zeros (and False).")
            .c_str());
  m.def(
      "align_rigidly",
      [](const py::object& source, const py::object& target) {
        const Positions s = PositionsArgument(source, "source");
        const Positions t = PositionsArgument(target, "target");
        if (s.rows() != t.rows()) {
          throw InputError("source and target: different vertex counts");
        }
        return FromPositions(AlignRigidly(s, t));
      },
      py::arg("source"), py::arg("target"),
      WithParameters(
          "align_rigidly",
          "source moved by the rigid motion (rotation and translation, no "
          "reflection; unweighted Kabsch) that best fits it to target.")
          .c_str());
}

}  // namespace pymodule
}  // namespace shellspace
