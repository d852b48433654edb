// The edge-angle variant of the shape-operator bending energy (docs/math.md,
// "Bending energy: two models"): the per-edge angles phi that make the rotated
// mid-edge second forms (geometry/edge_angle_second_form.h) fit a shape best,
// and the bending energy of a (reference, deformed) pair with them.
//
// The variant is not wired into the calculus (no problem differentiates
// through the inner minimisation); `shellspace energy --bending
// shape-operator-edge-angles` and bench/curvature_study use it.
#ifndef SHELLSPACE_COST_FUNCTIONS_EDGE_ANGLE_BENDING_H_
#define SHELLSPACE_COST_FUNCTIONS_EDGE_ANGLE_BENDING_H_

#include <string>
#include <vector>

#include "shellspace/cost_functions/edge_angle_bending_cost_function.h"
#include "shellspace/geometry/edge_angle_second_form.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// The #F reference faces of `metric` (#V x 3): area and Cholesky factor of
// each face's first fundamental form, with second forms `target` (#F; all
// zero if empty). Throws InputError for a degenerate face.
std::vector<EdgeAngleReferenceFace> EdgeAngleReferenceFaces(
    const Mesh& mesh, const Positions& metric,
    const std::vector<SecondForm2>& target = {});

// The second forms H_T(angles) of all faces (#F).
std::vector<SecondForm2> EdgeAngleSecondForms(
    const std::vector<EdgeAngleFace>& faces, const std::vector<double>& angles);

struct EdgeAngleFitOptions {
  double alpha = 0, beta = 1;  // docs/math.md, "Bending energy: two models"
  int max_iterations = 200;    // Levenberg-Marquardt iterations
  // Converged when Ceres' function, gradient or parameter tolerance is met.
  double function_tolerance = 1e-14;
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
};

struct EdgeAngleFit {
  std::vector<double> angles;       // phi_e, one per interior edge
  std::vector<double> face_energy;  // #F, abar (alpha (tr M)^2 + beta tr M^2)
  double energy = 0;                // sum of face_energy at `angles`
  std::vector<double> face_energy_at_zero;  // #F, the same at phi = 0
  double energy_at_zero = 0;        // sum of face_energy_at_zero
  int iterations = 0;               // Levenberg-Marquardt iterations
  bool converged = false;           // a Ceres tolerance was met
  std::string message;              // Ceres' report when not converged
};

// argmin over phi (#interior edges) of
//   sum_T abar_T (alpha (tr M_T)^2 + beta tr(M_T^2)),
//   M_T = Gbar_T^-1 (H_T(phi) - Hbar_T),
// `shape` the deformed faces (EdgeAngleFaces), `reference` the metric and
// targets Hbar_T (EdgeAngleReferenceFaces), by Ceres' sparse
// Levenberg-Marquardt from phi = 0 on one thread (deterministic).
EdgeAngleFit FitEdgeAngles(const std::vector<EdgeAngleFace>& shape,
                           const std::vector<EdgeAngleReferenceFace>& reference,
                           int num_interior_edges,
                           const EdgeAngleFitOptions& options = {});

// W_bend^SO,phi[Sbar, S]: the reference's angles phibar minimise the
// reference's own curvature functional (metric Sbar, target 0: sum abar
// (alpha (tr Bbar)^2 + beta tr Bbar^2)); the deformed angles phi then
// minimise W_bend^SO with Hbar = H(Sbar, phibar). Zero at rest (phi =
// phibar), invariant under rigid motions of either shell; at phi = phibar =
// 0 it is the plain shape-operator energy. reference, deformed: #V x 3.
struct EdgeAngleBending {
  EdgeAngleFit reference;  // phibar and the reference's curvature functional
  EdgeAngleFit deformed;   // phi and W_bend (deformed.energy)
  double energy = 0;       // = deformed.energy (without eta)
  bool converged = false;  // both fits converged
};
EdgeAngleBending EvaluateEdgeAngleBending(const Mesh& mesh,
                                          const Topology& topology,
                                          const Positions& reference,
                                          const Positions& deformed,
                                          const EdgeAngleFitOptions& options = {});

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_EDGE_ANGLE_BENDING_H_
