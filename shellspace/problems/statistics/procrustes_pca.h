// The Procrustes PCA baseline of shell PCA (docs/math.md, "Elastic mean and
// shell PCA"): rigidly align the shapes (generalised Procrustes, no scaling),
// then Euclidean PCA on the vertex positions.
#ifndef SHELLSPACE_PROBLEMS_STATISTICS_PROCRUSTES_PCA_H_
#define SHELLSPACE_PROBLEMS_STATISTICS_PROCRUSTES_PCA_H_

#include <vector>

#include <Eigen/Core>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

struct ProcrustesPcaModel {
  Positions mean;                       // x_bar = (1/n) sum_i A_i(S_i)
  std::vector<Positions> displacements; // d_i = A_i(S_i) - x_bar
  Eigen::VectorXd eigenvalues;          // of Gamma_ij = <d_i, d_j> / n
  std::vector<Positions> modes;         // Euclidean-orthonormal w_j
  int iterations = 0;                   // Procrustes alignment sweeps
};

// Generalised Procrustes alignment: start from the average of the shapes
// aligned to S_1, then repeat A_i = AlignRigidly(., x_bar), x_bar = (1/n)
// sum_i A_i(S_i) (x_bar re-aligned to S_1 to fix its pose) until x_bar moves
// by less than 1e-12 of its size or `max_iterations` sweeps. Then Euclidean
// PCA of d_i = A_i(S_i) - x_bar: Gamma_ij = <d_i, d_j> / n, modes w_j =
// sum_i a^j_i d_i / sqrt(n lambda_j) with |w_j| = 1. Throws InputError on an
// empty or inconsistent set.
ProcrustesPcaModel ComputeProcrustesPca(const std::vector<Positions>& shapes,
                                        int max_iterations = 50);

// x_bar + t sqrt(lambda_j) w_j (mode j 0-based).
Positions ProcrustesModeShape(const ProcrustesPcaModel& model, int j, double t);

// Reconstruction of `shape` from the first m modes: with x = AlignRigidly(
// shape, x_bar), x_bar + sum_{j<m} <x - x_bar, w_j> w_j.
Positions ProcrustesReconstruct(const ProcrustesPcaModel& model,
                                const Positions& shape, int m);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_STATISTICS_PROCRUSTES_PCA_H_
