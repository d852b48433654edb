#include "shellspace/cost_functions/gradient_field_residual.h"

#include <algorithm>
#include <cstring>
#include <thread>
#include <type_traits>

namespace shellspace {

GradientFieldCache::GradientFieldCache(const ShellSpace& space,
                                       const Positions& fixed,
                                       ShellSide unknown_side,
                                       const Positions* unknown)
    : space_(space),
      fixed_(fixed),
      unknown_side_(unknown_side),
      unknown_(unknown) {
  // Element list in ForEachElement order.
  ForEachElement(
      space, fixed, fixed,
      [&](const int* vs, int count, const double*, const double*, const auto&) {
        Element e;
        e.count = count;
        std::copy(vs, vs + count, e.vertices);
        elements_.push_back(e);
      });
}

void GradientFieldCache::PrepareForEvaluation(bool evaluate_jacobians,
                                              bool /*new_evaluation_point*/) {
  const bool unknown_is_reference = unknown_side_ == ShellSide::kReference;
  const Positions& reference = unknown_is_reference ? *unknown_ : fixed_;
  const Positions& deformed = unknown_is_reference ? fixed_ : *unknown_;
  const MembraneElement membrane = space_.material.membrane();
  const BendingElement bending = space_.material.bending();
  const int n = static_cast<int>(elements_.size());
  std::vector<char> ok(n, 1);
  auto work = [&](int begin, int end) {
    ElementSecondDerivatives<3> d3;
    ElementSecondDerivatives<4> d4;
    double ref[12], def[12];
    for (int i = begin; i < end; ++i) {
      Element& e = elements_[i];
      for (int a = 0; a < e.count; ++a) {
        for (int c = 0; c < 3; ++c) {
          ref[3 * a + c] = reference(e.vertices[a], c);
          def[3 * a + c] = deformed(e.vertices[a], c);
        }
      }
      auto store = [&](const auto& d) {
        const auto& grad =
            unknown_is_reference ? d.grad_deformed : d.grad_reference;
        const auto& jac =
            unknown_is_reference ? d.d_grad_deformed : d.d_grad_reference;
        const int m = 3 * e.count;
        for (int r = 0; r < m; ++r) {
          e.gradient[r] = grad(r);
          for (int c = 0; c < m; ++c) e.jacobian[r][c] = jac(r, c);
        }
      };
      // Residual-only evaluations need just the gradient of the fixed side:
      // J^T r in doubles, no dual numbers.
      auto gradient_only = [&](const auto& element, auto vertices_tag) {
        using E = std::decay_t<decltype(element)>;
        constexpr int kV = decltype(vertices_tag)::value;
        Vec3<double> x_ref[kV], x_def[kV];
        for (int a = 0; a < kV; ++a) {
          x_ref[a] = Vec3<double>(ref + 3 * a);
          x_def[a] = Vec3<double>(def + 3 * a);
        }
        typename E::template Jacobian<double> jac;
        double r[E::kNumResiduals];
        if (!element.Evaluate(x_ref, x_def, r,
                              unknown_is_reference ? nullptr : &jac,
                              unknown_is_reference ? &jac : nullptr)) {
          return false;
        }
        for (int col = 0; col < 3 * kV; ++col) {
          double g = 0;
          for (int m = 0; m < E::kNumResiduals; ++m) g += jac(m, col) * r[m];
          e.gradient[col] = g;
        }
        return true;
      };
      const ShellSide active = unknown_side_;
      bool good;
      if (!evaluate_jacobians) {
        good = e.count == 3
                   ? gradient_only(membrane, std::integral_constant<int, 3>())
                   : gradient_only(bending, std::integral_constant<int, 4>());
      } else if (e.count == 3) {
        good = d3.Compute(membrane, ref, def, active, 1.0);
        if (good) store(d3);
      } else {
        good = d4.Compute(bending, ref, def, active, 1.0);
        if (good) store(d4);
      }
      ok[i] = good;
    }
  };
  const int half = n / 2;
  std::thread second(work, half, n);
  work(0, half);
  second.join();
  ok_ = std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
}

VertexGradientResidual* VertexGradientResidual::Create(
    const GradientFieldCache* cache, int v, const double* constant,
    const std::vector<int>& incident) {
  auto* residual = new VertexGradientResidual();
  residual->cache_ = cache;
  residual->vertex_ = v;
  std::copy(constant, constant + 3, residual->constant_);
  for (int index : incident) {
    const auto& e = cache->elements()[index];
    for (int a = 0; a < e.count; ++a)
      residual->stencil_.push_back(e.vertices[a]);
  }
  auto& stencil = residual->stencil_;
  std::sort(stencil.begin(), stencil.end());
  stencil.erase(std::unique(stencil.begin(), stencil.end()), stencil.end());
  for (int index : incident) {
    const auto& e = cache->elements()[index];
    Term term;
    term.element = index;
    term.local_v = -1;
    for (int a = 0; a < e.count; ++a) {
      if (e.vertices[a] == v) term.local_v = a;
      term.local_to_block[a] = static_cast<int>(
          std::lower_bound(stencil.begin(), stencil.end(), e.vertices[a]) -
          stencil.begin());
    }
    residual->terms_.push_back(term);
  }
  residual->set_num_residuals(3);
  residual->mutable_parameter_block_sizes()->assign(stencil.size(), 3);
  return residual;
}

bool VertexGradientResidual::Evaluate(double const* const* /*parameters*/,
                                      double* residuals,
                                      double** jacobians) const {
  if (!cache_->ok()) return false;
  for (int c = 0; c < 3; ++c) residuals[c] = constant_[c];
  if (jacobians) {
    for (size_t b = 0; b < stencil_.size(); ++b) {
      if (jacobians[b]) std::memset(jacobians[b], 0, 9 * sizeof(double));
    }
  }
  const auto& elements = cache_->elements();
  for (const Term& term : terms_) {
    const auto& e = elements[term.element];
    const int row0 = 3 * term.local_v;
    for (int c = 0; c < 3; ++c) residuals[c] += e.gradient[row0 + c];
    if (!jacobians) continue;
    for (int a = 0; a < e.count; ++a) {
      double* block = jacobians[term.local_to_block[a]];
      if (!block) continue;
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
          block[3 * r + c] += e.jacobian[row0 + r][3 * a + c];
        }
      }
    }
  }
  return true;
}

}  // namespace shellspace
