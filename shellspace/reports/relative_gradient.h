// The gradient norm of a solve relative to its start's, as the summaries
// report it (relative_gradient_norm, mean_relative_gradient_norm).
#ifndef SHELLSPACE_REPORTS_RELATIVE_GRADIENT_H_
#define SHELLSPACE_REPORTS_RELATIVE_GRADIENT_H_

namespace shellspace {

// |grad| / |grad_0|; 0 when |grad_0| = 0 (the start was already
// stationary, so there is nothing to be relative to).
inline double RelativeGradientNorm(double gradient_norm,
                                   double initial_gradient_norm) {
  return initial_gradient_norm > 0 ? gradient_norm / initial_gradient_norm
                                   : 0.0;
}

}  // namespace shellspace

#endif  // SHELLSPACE_REPORTS_RELATIVE_GRADIENT_H_
