#include "shellspace/cost_functions/shell/energy_derivatives.h"

#include <ceres/jet.h>

#include <vector>

namespace shellspace {
namespace {

template <int kVertices, class Element>
const ElementSecondDerivatives<kVertices>& Derive(
    const Element& element, const double* ref, const double* def,
    ShellSide active, ElementSecondDerivatives<kVertices>* out) {
  if (!out->Compute(element, ref, def, active, 1.0)) {
    throw InputError("degenerate triangle while differentiating W");
  }
  return *out;
}

}  // namespace

Eigen::VectorXd EnergyGradient(const ShellSpace& space,
                               const Positions& reference,
                               const Positions& deformed, ShellSide side) {
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(3 * space.num_vertices);
  auto accumulate = [&](const int* vs, int count, const double* ref,
                        const double* def, const auto& element) {
    using E = std::decay_t<decltype(element)>;
    constexpr int kV = E::kNumResiduals == 4 ? 3 : 4;
    typename E::template Jacobian<double> jac_ref, jac_def;
    double r[E::kNumResiduals];
    Vec3<double> x_ref[kV], x_def[kV];
    for (int a = 0; a < kV; ++a) {
      x_ref[a] = Vec3<double>(ref + 3 * a);
      x_def[a] = Vec3<double>(def + 3 * a);
    }
    const bool want_ref = side == ShellSide::kReference;
    if (!element.Evaluate(x_ref, x_def, r, want_ref ? &jac_ref : nullptr,
                          want_ref ? nullptr : &jac_def)) {
      throw InputError("degenerate triangle while differentiating W");
    }
    const auto& jac = want_ref ? jac_ref : jac_def;
    for (int a = 0; a < count; ++a) {
      for (int c = 0; c < 3; ++c) {
        double g = 0;
        for (int i = 0; i < E::kNumResiduals; ++i)
          g += jac(i, 3 * a + c) * r[i];
        gradient(3 * vs[a] + c) += g;
      }
    }
  };
  ForEachElement(space, reference, deformed, accumulate);
  return gradient;
}

Eigen::VectorXd EnergyGradientDerivative(const ShellSpace& space,
                                         const Positions& reference,
                                         const Positions& deformed,
                                         ShellSide gradient, ShellSide moved,
                                         const Eigen::VectorXd& p) {
  using J = ceres::Jet<double, 1>;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(3 * space.num_vertices);
  auto accumulate = [&](const int* vs, int count, const double* ref,
                        const double* def, const auto& element) {
    using E = std::decay_t<decltype(element)>;
    constexpr int kV = E::kNumResiduals == 4 ? 3 : 4;
    Vec3<J> x_ref[kV], x_def[kV];
    for (int a = 0; a < kV; ++a) {
      for (int c = 0; c < 3; ++c) {
        x_ref[a](c) = J(ref[3 * a + c]);
        x_def[a](c) = J(def[3 * a + c]);
        J& x = moved == ShellSide::kReference ? x_ref[a](c) : x_def[a](c);
        x.v[0] = p(3 * vs[a] + c);
      }
    }
    J r[E::kNumResiduals];
    typename E::template Jacobian<J> jac;
    const bool of_reference = gradient == ShellSide::kReference;
    if (!element.Evaluate(x_ref, x_def, r, of_reference ? &jac : nullptr,
                          of_reference ? nullptr : &jac)) {
      throw InputError("degenerate triangle while differentiating W");
    }
    for (int a = 0; a < count; ++a) {
      for (int c = 0; c < 3; ++c) {
        J g(0.0);
        for (int i = 0; i < E::kNumResiduals; ++i) g += jac(i, 3 * a + c) * r[i];
        out(3 * vs[a] + c) += g.v[0];
      }
    }
  };
  ForEachElement(space, reference, deformed, accumulate);
  return out;
}

std::pair<SparseMatrix, SparseMatrix> EnergyHessianColumns(
    const ShellSpace& space, const Positions& reference,
    const Positions& deformed, ShellSide cols) {
  std::vector<Eigen::Triplet<double>> rows_reference, rows_deformed;
  ElementSecondDerivatives<3> d3;
  ElementSecondDerivatives<4> d4;
  auto accumulate = [&](const int* vs, int count, const double* ref,
                        const double* def, const auto& element) {
    using E = std::decay_t<decltype(element)>;
    auto add = [&](const auto& d) {
      for (int a = 0; a < count; ++a) {
        for (int b = 0; b < count; ++b) {
          for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
              const int r = 3 * vs[a] + i, c = 3 * vs[b] + j;
              rows_reference.emplace_back(
                  r, c, d.d_grad_reference(3 * a + i, 3 * b + j));
              rows_deformed.emplace_back(
                  r, c, d.d_grad_deformed(3 * a + i, 3 * b + j));
            }
          }
        }
      }
    };
    if constexpr (E::kNumResiduals == 4) {
      add(Derive<3>(element, ref, def, cols, &d3));
    } else {
      add(Derive<4>(element, ref, def, cols, &d4));
    }
  };
  ForEachElement(space, reference, deformed, accumulate);
  const int n = 3 * space.num_vertices;
  std::pair<SparseMatrix, SparseMatrix> out{SparseMatrix(n, n),
                                            SparseMatrix(n, n)};
  out.first.setFromTriplets(rows_reference.begin(), rows_reference.end());
  out.second.setFromTriplets(rows_deformed.begin(), rows_deformed.end());
  return out;
}

SparseMatrix EnergyHessian(const ShellSpace& space, const Positions& reference,
                           const Positions& deformed, ShellSide rows,
                           ShellSide cols) {
  auto blocks = EnergyHessianColumns(space, reference, deformed, cols);
  return rows == ShellSide::kReference ? std::move(blocks.first)
                                       : std::move(blocks.second);
}

}  // namespace shellspace
