// The Kronecker model of a path Hessian, for the linear-solver tests:
// K T (x) G with T = tridiag(-1, 2, -1) (size K - 1) and an SPD metric G.
#ifndef SHELLSPACE_TESTS_TESTING_KRONECKER_MODEL_H_
#define SHELLSPACE_TESTS_TESTING_KRONECKER_MODEL_H_

#include <Eigen/SparseCore>
#include <vector>

namespace shellspace::testing {

// G = the edge-graph Laplacian of plate/plate121 + shift I, 3 unknowns per
// vertex (vertex-major): SPD for shift > 0.
Eigen::SparseMatrix<double> PlateLaplacianMetric(double shift);

// The lower triangle of K T (x) G, the diagonal blocks scaled by
// diagonal_scale (> 1/2 keeps it SPD).
Eigen::SparseMatrix<double> KroneckerPathModel(
    const Eigen::SparseMatrix<double>& g, int K, double diagonal_scale = 1.0);

// {0, m, 2 m, ..., blocks m}: the offsets of `blocks` slices of size m.
std::vector<int> SliceOffsets(int blocks, int m);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_KRONECKER_MODEL_H_
