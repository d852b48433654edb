// The residual of one discrete exponential-map step (docs/math.md, "Exponential
// map"): per vertex v, F_v(s) = c_v + (D_fixed W)_v, the gradient of W w.r.t.
// its fixed argument as a function of the unknown shell s in the other.
//   forward step  s_{k+1}:  F(s) = D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s]
//     (fixed = s_k as reference, unknown s deformed);
//   backward step s_{k-1}:  F(s) = D_2 W[s, s_k] + D_1 W[s_k, s_{k+1}]
//     (fixed = s_k as deformed, unknown s reference).
// The Jacobian dF/ds is the mixed second derivative of W.
#ifndef SHELLSPACE_COST_FUNCTIONS_GRADIENT_FIELD_RESIDUAL_H_
#define SHELLSPACE_COST_FUNCTIONS_GRADIENT_FIELD_RESIDUAL_H_

#include <ceres/cost_function.h>
#include <ceres/evaluation_callback.h>

#include <memory>
#include <vector>

#include "shellspace/cost_functions/shell/energy_derivatives.h"

namespace shellspace {

// Evaluates, once per evaluation point, every element's gradient w.r.t. the
// fixed argument and (when Jacobians are wanted) its derivative w.r.t. the
// unknown argument; the per-vertex cost functions then only gather. Register
// it as the problem's evaluation_callback (Ceres has written the current point
// into `unknown` when PrepareForEvaluation runs).
class GradientFieldCache : public ceres::EvaluationCallback {
 public:
  // `unknown_side`: the argument of W that the unknown shell occupies.
  // Elements are evaluated on `threads` threads (runtime/parallel_for.h);
  // the results do not depend on it.
  GradientFieldCache(const ShellSpace& space, const Positions& fixed,
                     ShellSide unknown_side, const Positions* unknown,
                     int threads = 2);
  GradientFieldCache(const GradientFieldCache&) = delete;
  GradientFieldCache& operator=(const GradientFieldCache&) = delete;

  void PrepareForEvaluation(bool evaluate_jacobians,
                            bool new_evaluation_point) override;

  // One element of space.elements(), in its enumeration order.
  struct Element {
    int count = 0;                  // vertices in its stencil
    const int* vertices = nullptr;  // the stencil (count vertices)
    double* gradient = nullptr;     // 3 count: d e / d fixed, local coords
    // 3 count x 3 count, row-major: d gradient / d unknown (row: fixed
    // coordinate); valid after an evaluation with Jacobians.
    double* jacobian = nullptr;
  };
  const std::vector<Element>& elements() const { return elements_; }
  // False if some element was degenerate at the current point.
  bool ok() const { return ok_; }

 private:
  const ShellSpace& space_;
  const Positions& fixed_;
  ShellSide unknown_side_;
  const Positions* unknown_;
  int threads_;
  std::vector<Element> elements_;
  std::vector<double> gradients_, jacobians_;  // storage of elements_
  bool ok_ = true;
};

// Residual F_v in R^3 of one vertex v (not a fixed Dirichlet vertex): its
// parameter blocks are the unknown shell's vertices in the stencil of the
// elements around v (each a block of size 3), in `stencil()` order; the
// Jacobian block of stencil vertex w is sum_e d(gradient_e)_v / d s_w.
class VertexGradientResidual : public ceres::CostFunction {
 public:
  // `constant`: c_v (3 doubles). `incident`: indices into cache.elements() of
  // the elements containing v.
  static VertexGradientResidual* Create(const GradientFieldCache* cache, int v,
                                        const double* constant,
                                        const std::vector<int>& incident);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  const std::vector<int>& stencil() const { return stencil_; }

 private:
  VertexGradientResidual() = default;
  const GradientFieldCache* cache_ = nullptr;
  int vertex_ = 0;
  double constant_[3] = {0, 0, 0};
  struct Term {
    int element;
    int local_v;            // v's local index in the element
    int first_block;        // local_to_block_[first_block + a]: the stencil
                            // block of the element's local vertex a
  };
  std::vector<Term> terms_;
  std::vector<int> local_to_block_;
  std::vector<int> stencil_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_GRADIENT_FIELD_RESIDUAL_H_
