// Adapter from a per-element stencil (MembraneElement, BendingElement) to a
// ceres::CostFunction whose reference and deformed vertices are each either
// per-vertex parameter blocks or fixed data.
#ifndef SHELLSPACE_COST_FUNCTIONS_ELEMENT_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_ELEMENT_COST_FUNCTION_H_

#include <ceres/cost_function.h>

#include <array>
#include <cmath>

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// Residuals sqrt(weight) * Element::Evaluate(reference, deformed).
// Parameter blocks, each of size 3 (one vertex): first the kVertices reference
// vertices if the reference is variable, then the kVertices deformed vertices
// if the deformed shell is variable. Jacobian blocks are row-major
// kNumResiduals x 3. `fixed_reference` / `fixed_deformed` (3 kVertices doubles,
// copied) are given for a side that is data, nullptr for a side that is
// variable; at least one side must be variable.
template <class Element, int kVertices>
class ElementCostFunction : public ceres::CostFunction {
 public:
  static constexpr int kNumResiduals = Element::kNumResiduals;

  ElementCostFunction(const Element& element, const double* fixed_reference,
                      const double* fixed_deformed, double weight)
      : element_(element),
        reference_variable_(fixed_reference == nullptr),
        deformed_variable_(fixed_deformed == nullptr),
        sqrt_weight_(std::sqrt(weight)) {
    set_num_residuals(kNumResiduals);
    const int blocks =
        kVertices * (int(reference_variable_) + int(deformed_variable_));
    mutable_parameter_block_sizes()->assign(blocks, 3);
    for (int v = 0; v < kVertices; ++v) {
      if (fixed_reference)
        reference_[v] = Vec3<double>(fixed_reference + 3 * v);
      if (fixed_deformed) deformed_[v] = Vec3<double>(fixed_deformed + 3 * v);
    }
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    std::array<Vec3<double>, kVertices> ref = reference_, def = deformed_;
    int block = 0;
    const int ref_offset = 0;
    if (reference_variable_) {
      for (int v = 0; v < kVertices; ++v) {
        ref[v] = Vec3<double>(parameters[block++]);
      }
    }
    const int def_offset = block;
    if (deformed_variable_) {
      for (int v = 0; v < kVertices; ++v) {
        def[v] = Vec3<double>(parameters[block++]);
      }
    }
    typename Element::template Jacobian<double> jac_ref, jac_def;
    bool want_ref = false, want_def = false;
    if (jacobians) {
      for (int v = 0; v < kVertices; ++v) {
        want_ref |= reference_variable_ && jacobians[ref_offset + v];
        want_def |= deformed_variable_ && jacobians[def_offset + v];
      }
    }
    if (!element_.Evaluate(ref.data(), def.data(), residuals,
                           want_ref ? &jac_ref : nullptr,
                           want_def ? &jac_def : nullptr)) {
      return false;
    }
    for (int m = 0; m < kNumResiduals; ++m) {
      residuals[m] *= sqrt_weight_;
      if (!std::isfinite(residuals[m])) return false;
    }
    auto copy = [&](const typename Element::template Jacobian<double>& jac,
                    int offset) {
      for (int v = 0; v < kVertices; ++v) {
        double* out = jacobians[offset + v];
        if (out == nullptr) continue;
        for (int m = 0; m < kNumResiduals; ++m) {
          for (int c = 0; c < 3; ++c) {
            out[3 * m + c] = sqrt_weight_ * jac(m, 3 * v + c);
          }
        }
      }
    };
    if (want_ref) copy(jac_ref, ref_offset);
    if (want_def) copy(jac_def, def_offset);
    return true;
  }

 private:
  Element element_;
  bool reference_variable_, deformed_variable_;
  double sqrt_weight_;
  std::array<Vec3<double>, kVertices> reference_, deformed_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_ELEMENT_COST_FUNCTION_H_
