#include "shellspace/cost_functions/gradient_field_residual.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

#include "shellspace/runtime/parallel_for.h"

namespace shellspace {

namespace {

// Elements per task of the parallel evaluation.
constexpr int kChunk = 256;

}  // namespace

GradientFieldCache::GradientFieldCache(const ShellSpace& space,
                                       const Positions& fixed,
                                       ShellSide unknown_side,
                                       const Positions* unknown, int threads)
    : space_(space),
      fixed_(fixed),
      unknown_side_(unknown_side),
      unknown_(unknown),
      threads_(std::max(1, threads)) {
  // One Element per element of the set, in its enumeration order, with
  // storage for its gradient (3 count) and Jacobian ((3 count)^2).
  const ElementSet& set = space.elements();
  size_t gradient_size = 0, jacobian_size = 0;
  set.ForEachGroup([&](const auto& group) {
    constexpr int m = 3 * std::decay_t<decltype(group)>::kVertices;
    gradient_size += static_cast<size_t>(m) * group.size();
    jacobian_size += static_cast<size_t>(m) * m * group.size();
  });
  gradients_.assign(gradient_size, 0.0);
  jacobians_.assign(jacobian_size, 0.0);
  elements_.reserve(set.num_elements());
  size_t g = 0, j = 0;
  set.ForEachGroup([&](const auto& group) {
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    for (const auto& stencil : group.stencils) {
      Element e;
      e.count = kV;
      e.vertices = stencil.data();
      e.gradient = gradients_.data() + g;
      e.jacobian = jacobians_.data() + j;
      g += 3 * kV;
      j += 9 * kV * kV;
      elements_.push_back(e);
    }
  });
}

void GradientFieldCache::PrepareForEvaluation(bool evaluate_jacobians,
                                              bool /*new_evaluation_point*/) {
  const bool unknown_is_reference = unknown_side_ == ShellSide::kReference;
  const Positions& reference = unknown_is_reference ? *unknown_ : fixed_;
  const Positions& deformed = unknown_is_reference ? fixed_ : *unknown_;
  std::vector<char> ok(elements_.size(), 1);
  space_.elements().ForEachGroup([&](const auto& group) {
    using Group = std::decay_t<decltype(group)>;
    using E = typename Group::Element;
    constexpr int kV = Group::kVertices;
    constexpr int m = 3 * kV;
    const int first = group.first_element;
    const int chunks = (group.size() + kChunk - 1) / kChunk;
    ParallelFor(chunks, threads_, [&](int chunk) {
      ElementSecondDerivatives<kV> d;
      double ref[m], def[m];
      Vec3<double> x_ref[kV], x_def[kV];
      typename E::template Jacobian<double> jac;
      double r[E::kNumResiduals];
      const int end = std::min(group.size(), (chunk + 1) * kChunk);
      for (int i = chunk * kChunk; i < end; ++i) {
        Element& e = elements_[first + i];
        const auto& stencil = group.stencils[i];
        bool good;
        if (!evaluate_jacobians) {
          // Residual-only evaluations need just the gradient of the fixed
          // side: J^T r in doubles, no dual numbers.
          GatherVertices(reference, stencil, x_ref);
          GatherVertices(deformed, stencil, x_def);
          good = group.element.Evaluate(
              x_ref, x_def, r, unknown_is_reference ? nullptr : &jac,
              unknown_is_reference ? &jac : nullptr);
          if (good) {
            for (int col = 0; col < m; ++col) {
              double sum = 0;
              for (int k = 0; k < E::kNumResiduals; ++k)
                sum += jac(k, col) * r[k];
              e.gradient[col] = sum;
            }
          }
        } else {
          GatherCoordinates(reference, stencil, ref);
          GatherCoordinates(deformed, stencil, def);
          // Only the rows of the fixed side's gradient are used.
          good = d.Compute(group.element, ref, def, unknown_side_, 1.0,
                           unknown_is_reference
                               ? ElementSecondDerivatives<kV>::Rows::kDeformed
                               : ElementSecondDerivatives<kV>::Rows::kReference);
          if (good) {
            const auto& grad =
                unknown_is_reference ? d.grad_deformed : d.grad_reference;
            const auto& jacobian =
                unknown_is_reference ? d.d_grad_deformed : d.d_grad_reference;
            for (int row = 0; row < m; ++row) {
              e.gradient[row] = grad(row);
              for (int col = 0; col < m; ++col)
                e.jacobian[m * row + col] = jacobian(row, col);
            }
          }
        }
        ok[first + i] = good;
      }
    });
  });
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
    term.first_block = static_cast<int>(residual->local_to_block_.size());
    for (int a = 0; a < e.count; ++a) {
      if (e.vertices[a] == v) term.local_v = a;
      residual->local_to_block_.push_back(static_cast<int>(
          std::lower_bound(stencil.begin(), stencil.end(), e.vertices[a]) -
          stencil.begin()));
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
    const int m = 3 * e.count;
    for (int a = 0; a < e.count; ++a) {
      double* block = jacobians[local_to_block_[term.first_block + a]];
      if (!block) continue;
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
          block[3 * r + c] += e.jacobian[m * (row0 + r) + 3 * a + c];
        }
      }
    }
  }
  return true;
}

}  // namespace shellspace
