#include "shellspace/geometry/connected_components.h"

#include <algorithm>
#include <numeric>

namespace shellspace {
namespace {

int Root(std::vector<int>& parent, int v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];  // path halving
    v = parent[v];
  }
  return v;
}

}  // namespace

std::vector<std::vector<int>> ConnectedComponents(const Faces& faces,
                                                  int vertex_count) {
  std::vector<int> parent(vertex_count);
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 1; c < 3; ++c) {
      const int a = Root(parent, faces(f, 0));
      const int b = Root(parent, faces(f, c));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  // Each root is its component's least vertex, so numbering the roots in
  // vertex order orders the groups by their least vertex.
  std::vector<int> group_of_root(vertex_count, -1);
  std::vector<std::vector<int>> groups;
  for (int v = 0; v < vertex_count; ++v) {
    const int root = Root(parent, v);
    if (group_of_root[root] < 0) {
      group_of_root[root] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[group_of_root[root]].push_back(v);
  }
  return groups;
}

}  // namespace shellspace
