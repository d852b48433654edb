#include "shellspace/cost_functions/shell/energy_derivatives.h"

#include <ceres/jet.h>

#include <type_traits>
#include <vector>

namespace shellspace {
namespace {

[[noreturn]] void ThrowDegenerate(const ElementFailure& failure) {
  throw InputError("degenerate element while differentiating W: " +
                   failure.description);
}

// Calls visit(group) for the groups of `set` in order until one returns
// false (an element failed); returns whether all returned true.
template <typename Visitor>
bool VisitGroupsUntilFailure(const ElementSet& set, Visitor&& visit) {
  bool ok = true;
  set.ForEachGroup([&](const auto& group) {
    if (ok) ok = visit(group);
  });
  return ok;
}

}  // namespace

bool TryEnergyGradient(const ShellSpace& space, const Positions& reference,
                       const Positions& deformed, ShellSide side,
                       Eigen::VectorXd* gradient, ElementFailure* failure) {
  const bool of_reference = side == ShellSide::kReference;
  return TryEnergyGradients(space, reference, deformed,
                            of_reference ? gradient : nullptr,
                            of_reference ? nullptr : gradient, failure);
}

bool TryEnergyGradients(const ShellSpace& space, const Positions& reference,
                        const Positions& deformed,
                        Eigen::VectorXd* of_reference,
                        Eigen::VectorXd* of_deformed, ElementFailure* failure) {
  const ElementSet& set = space.elements();
  if (of_reference) of_reference->setZero(3 * space.num_vertices);
  if (of_deformed) of_deformed->setZero(3 * space.num_vertices);
  return VisitGroupsUntilFailure(set, [&](const auto& group) {
    using Group = std::decay_t<decltype(group)>;
    using E = typename Group::Element;
    constexpr int kV = Group::kVertices;
    typename E::template Jacobian<double> jac_ref, jac_def;
    double r[E::kNumResiduals];
    Vec3<double> x_ref[kV], x_def[kV];
    // (*out)(3 v_a + c) += sum_i jac(i, 3 a + c) r_i.
    const auto add = [&](const auto& jac, const auto& vs,
                         Eigen::VectorXd* out) {
      for (int a = 0; a < kV; ++a) {
        for (int c = 0; c < 3; ++c) {
          double g = 0;
          for (int i = 0; i < E::kNumResiduals; ++i)
            g += jac(i, 3 * a + c) * r[i];
          (*out)(3 * vs[a] + c) += g;
        }
      }
    };
    for (int e = 0; e < group.size(); ++e) {
      const auto& vs = group.stencils[e];
      GatherVertices(reference, vs, x_ref);
      GatherVertices(deformed, vs, x_def);
      if (!group.element.Evaluate(x_ref, x_def, r,
                                  of_reference ? &jac_ref : nullptr,
                                  of_deformed ? &jac_def : nullptr)) {
        set.Fail(group.first_element + e, failure);
        return false;
      }
      if (of_reference) add(jac_ref, vs, of_reference);
      if (of_deformed) add(jac_def, vs, of_deformed);
    }
    return true;
  });
}

Eigen::VectorXd EnergyGradient(const ShellSpace& space,
                               const Positions& reference,
                               const Positions& deformed, ShellSide side) {
  Eigen::VectorXd gradient;
  ElementFailure failure;
  if (!TryEnergyGradient(space, reference, deformed, side, &gradient,
                         &failure)) {
    ThrowDegenerate(failure);
  }
  return gradient;
}

bool TryEnergyGradientDerivative(const ShellSpace& space,
                                 const Positions& reference,
                                 const Positions& deformed, ShellSide gradient,
                                 ShellSide moved, const Eigen::VectorXd& p,
                                 Eigen::VectorXd* out,
                                 ElementFailure* failure) {
  using J = ceres::Jet<double, 1>;
  const ElementSet& set = space.elements();
  out->setZero(3 * space.num_vertices);
  const bool of_reference = gradient == ShellSide::kReference;
  const bool ok = VisitGroupsUntilFailure(set, [&](const auto& group) {
    using Group = std::decay_t<decltype(group)>;
    using E = typename Group::Element;
    constexpr int kV = Group::kVertices;
    if constexpr (HasAnalyticSecondDerivatives<E>::value) {
      // The element's own block of the Hessian times p (only the rows of
      // `gradient`).
      using D = ElementSecondDerivatives<kV>;
      D d;
      double ref[3 * kV], def[3 * kV];
      Eigen::Matrix<double, 3 * kV, 1> p_local;
      const auto rows = of_reference ? D::Rows::kReference : D::Rows::kDeformed;
      for (int e = 0; e < group.size(); ++e) {
        const auto& vs = group.stencils[e];
        GatherCoordinates(reference, vs, ref);
        GatherCoordinates(deformed, vs, def);
        for (int a = 0; a < kV; ++a)
          p_local.template segment<3>(3 * a) = p.segment<3>(3 * vs[a]);
        if (!d.Compute(group.element, ref, def, moved, 1.0, rows)) {
          set.Fail(group.first_element + e, failure);
          return false;
        }
        const Eigen::Matrix<double, 3 * kV, 1> local =
            (of_reference ? d.d_grad_reference : d.d_grad_deformed) * p_local;
        for (int a = 0; a < kV; ++a)
          out->segment<3>(3 * vs[a]) += local.template segment<3>(3 * a);
      }
      return true;
    }
    Vec3<J> x_ref[kV], x_def[kV];
    J r[E::kNumResiduals];
    typename E::template Jacobian<J> jac;
    for (int e = 0; e < group.size(); ++e) {
      const auto& vs = group.stencils[e];
      for (int a = 0; a < kV; ++a) {
        for (int c = 0; c < 3; ++c) {
          x_ref[a](c) = J(reference(vs[a], c));
          x_def[a](c) = J(deformed(vs[a], c));
          J& x = moved == ShellSide::kReference ? x_ref[a](c) : x_def[a](c);
          x.v[0] = p(3 * vs[a] + c);
        }
      }
      if (!group.element.Evaluate(x_ref, x_def, r,
                                  of_reference ? &jac : nullptr,
                                  of_reference ? nullptr : &jac)) {
        set.Fail(group.first_element + e, failure);
        return false;
      }
      for (int a = 0; a < kV; ++a) {
        for (int c = 0; c < 3; ++c) {
          J g(0.0);
          for (int i = 0; i < E::kNumResiduals; ++i)
            g += jac(i, 3 * a + c) * r[i];
          (*out)(3 * vs[a] + c) += g.v[0];
        }
      }
    }
    return true;
  });
  return ok;
}

Eigen::VectorXd EnergyGradientDerivative(const ShellSpace& space,
                                         const Positions& reference,
                                         const Positions& deformed,
                                         ShellSide gradient, ShellSide moved,
                                         const Eigen::VectorXd& p) {
  Eigen::VectorXd out;
  ElementFailure failure;
  if (!TryEnergyGradientDerivative(space, reference, deformed, gradient, moved,
                                   p, &out, &failure)) {
    ThrowDegenerate(failure);
  }
  return out;
}

bool TryEnergyHessianColumns(const ShellSpace& space,
                             const Positions& reference,
                             const Positions& deformed, ShellSide cols,
                             std::pair<SparseMatrix, SparseMatrix>* out,
                             ElementFailure* failure) {
  const ElementSet& set = space.elements();
  std::vector<Eigen::Triplet<double>> rows_reference, rows_deformed;
  const bool ok = VisitGroupsUntilFailure(set, [&](const auto& group) {
    using Group = std::decay_t<decltype(group)>;
    constexpr int kV = Group::kVertices;
    ElementSecondDerivatives<kV> d;
    double ref[3 * kV], def[3 * kV];
    for (int e = 0; e < group.size(); ++e) {
      const auto& vs = group.stencils[e];
      GatherCoordinates(reference, vs, ref);
      GatherCoordinates(deformed, vs, def);
      if (!d.Compute(group.element, ref, def, cols, 1.0)) {
        set.Fail(group.first_element + e, failure);
        return false;
      }
      for (int a = 0; a < kV; ++a) {
        for (int b = 0; b < kV; ++b) {
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
    }
    return true;
  });
  if (!ok) return false;
  const int n = 3 * space.num_vertices;
  out->first = SparseMatrix(n, n);
  out->second = SparseMatrix(n, n);
  out->first.setFromTriplets(rows_reference.begin(), rows_reference.end());
  out->second.setFromTriplets(rows_deformed.begin(), rows_deformed.end());
  return true;
}

std::pair<SparseMatrix, SparseMatrix> EnergyHessianColumns(
    const ShellSpace& space, const Positions& reference,
    const Positions& deformed, ShellSide cols) {
  std::pair<SparseMatrix, SparseMatrix> out;
  ElementFailure failure;
  if (!TryEnergyHessianColumns(space, reference, deformed, cols, &out,
                               &failure)) {
    ThrowDegenerate(failure);
  }
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
