#include "shellspace/solvers/space_time_ordering.h"

#include <cholmod.h>

#include <Eigen/CholmodSupport>
#include <stdexcept>

namespace shellspace {

Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>
SpaceTimeOrdering(const Eigen::SparseMatrix<double>& lower,
                  const std::vector<int>& vertex_of, int num_vertices) {
  const int n = static_cast<int>(lower.rows());
  // Compress to the vertices that carry unknowns.
  std::vector<int> node_of_vertex(num_vertices, -1);
  int nodes = 0;
  for (int i = 0; i < n; ++i) {
    int& node = node_of_vertex[vertex_of[i]];
    if (node < 0) node = nodes++;
  }
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(lower.nonZeros() / 4 + nodes);
  for (int i = 0; i < nodes; ++i) t.emplace_back(i, i, 1.0);
  for (int c = 0; c < lower.outerSize(); ++c) {
    const int nc = node_of_vertex[vertex_of[c]];
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it) {
      const int nr = node_of_vertex[vertex_of[it.row()]];
      if (nr > nc) t.emplace_back(nr, nc, 1.0);
    }
  }
  Eigen::SparseMatrix<double> graph(nodes, nodes);
  graph.setFromTriplets(t.begin(), t.end());  // duplicates summed: fine

  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  const Eigen::SparseMatrix<double>& pattern = graph;
  cholmod_sparse view =
      Eigen::viewAsCholmod(pattern.selfadjointView<Eigen::Lower>());
  cholmod_factor* symbolic = cholmod_analyze(&view, &common);
  if (symbolic == nullptr) {
    cholmod_finish(&common);
    throw std::runtime_error("CHOLMOD could not order the vertex graph");
  }
  std::vector<int> rank(nodes);  // node -> position in the ordering
  const int* perm = static_cast<const int*>(symbolic->Perm);
  for (int p = 0; p < nodes; ++p) rank[perm[p]] = p;
  cholmod_free_factor(&symbolic, &common);
  cholmod_finish(&common);

  // Counting sort of the unknowns by the rank of their vertex (stable: a
  // vertex's unknowns keep their relative order).
  std::vector<int> start(nodes + 1, 0);
  for (int i = 0; i < n; ++i) ++start[rank[node_of_vertex[vertex_of[i]]] + 1];
  for (int p = 0; p < nodes; ++p) start[p + 1] += start[p];
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation(n);
  for (int i = 0; i < n; ++i) {
    permutation.indices()[i] = start[rank[node_of_vertex[vertex_of[i]]]]++;
  }
  return permutation;
}

}  // namespace shellspace
