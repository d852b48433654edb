// The time-discrete spline energy and the regression functional as a
// ceres::FirstOrderFunction with the adjoint gradient (calculus.md,
// "Riemannian splines" and "Regression").
#ifndef SHELLSPACE_PROBLEMS_SPLINE_ENERGY_H_
#define SHELLSPACE_PROBLEMS_SPLINE_ENERGY_H_

#include <ceres/first_order_function.h>

#include <vector>

#include "problems/geodesic.h"

namespace shellspace {

// One observation of the regression data term W[shape, s_index].
struct SplineDatum {
  Positions shape;
  int index = 0;
};

// The path and which of its shapes are unknowns.
//  - Non-periodic: shapes s_0 .. s_K, midpoint terms k = 1 .. K-1.
//  - Periodic: shapes s_0 .. s_{K-1}, midpoint terms k = 0 .. K-1 with
//    neighbours taken mod K.
struct SplineSpec {
  int steps = 0;  // K
  bool periodic = false;
  ShellPath initial;          // K + 1 (or K if periodic) shapes
  std::vector<char> is_free;  // one flag per shape; fixed shapes are data
  std::vector<SplineDatum> data;
  double sigma = 1.0;  // weight of F_K
};

// R[s] = sum_j W[S_j, s_{k_j}] + sigma F_K[s], F_K = 4 K^3 sum_k W[s_k,
// m_k], m_k = argmin_m W[s_{k-1}, m] + W[m, s_{k+1}] (geodesic midpoint,
// solved by sparse LM, warm-started from the previous evaluation's midpoint).
// Gradient by the adjoint: with H_k = D_2^2 W[s_{k-1}, m_k] + D_1^2 W[m_k,
// s_{k+1}] and H_k p_k = -D_2 W[s_k, m_k] (solved modulo rigid motions),
//   dF/ds_k     += 4K^3 D_1 W[s_k, m_k],
//   dF/ds_{k-1} += 4K^3 (d_{s_{k-1}} d_m W[s_{k-1}, m_k]) p_k,
//   dF/ds_{k+1} += 4K^3 (d_{s_{k+1}} d_m W[m_k, s_{k+1}]) p_k,
// the mixed blocks mapping a vector on m to one on the neighbour. The
// parameters are the free shapes' coordinates, concatenated in index order.
class SplineObjective : public ceres::FirstOrderFunction {
 public:
  SplineObjective(const ShellSpace& space, SplineSpec spec,
                  const SolverSettings& inner_settings);

  int NumParameters() const override { return num_parameters_; }
  bool Evaluate(const double* parameters, double* cost,
                double* gradient) const override;

  std::vector<double> InitialParameters() const;
  ShellPath PathFrom(const double* parameters) const;
  // F_K alone (without sigma and data) of a path, solving the midpoints.
  double SplineEnergyOf(const ShellPath& path) const;
  int num_shapes() const { return static_cast<int>(spec_.initial.size()); }

 private:
  struct Term {
    int previous, center, next;
  };
  const ShellSpace& space_;
  SplineSpec spec_;
  SolverSettings inner_settings_;
  std::vector<Term> terms_;
  std::vector<int> free_shapes_;
  int num_parameters_ = 0;
  mutable std::vector<Positions> midpoints_;  // warm starts, one per term
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINE_ENERGY_H_
