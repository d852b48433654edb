#include "shellspace/geometry/locality_order.h"

#include <algorithm>

namespace shellspace {

namespace {

// Breadth-first search of the unnumbered component of `start`, appending
// its vertices to *order (neighbours in increasing degree, then index) and
// marking them in `level` (>= 0 once reached).
void BreadthFirst(const std::vector<std::vector<int>>& neighbours,
                  const std::vector<int>& degree, int start,
                  std::vector<int>* level, std::vector<int>* order) {
  const size_t begin = order->size();
  (*level)[start] = 0;
  order->push_back(start);
  std::vector<int> next;
  for (size_t head = begin; head < order->size(); ++head) {
    const int v = (*order)[head];
    next.clear();
    for (int w : neighbours[v]) {
      if (w != v && (*level)[w] < 0) {
        (*level)[w] = (*level)[v] + 1;
        next.push_back(w);
      }
    }
    std::sort(next.begin(), next.end(), [&](int a, int b) {
      return degree[a] != degree[b] ? degree[a] < degree[b] : a < b;
    });
    order->insert(order->end(), next.begin(), next.end());
  }
}

}  // namespace

std::vector<int> CuthillMcKeeRanks(
    const std::vector<std::vector<int>>& neighbours) {
  const int n = static_cast<int>(neighbours.size());
  std::vector<int> degree(n, 0);
  for (int v = 0; v < n; ++v) {
    for (int w : neighbours[v]) degree[v] += w != v;
  }
  // Vertices by increasing degree (then index): each component starts from
  // its first one.
  std::vector<int> by_degree(n);
  for (int v = 0; v < n; ++v) by_degree[v] = v;
  std::stable_sort(by_degree.begin(), by_degree.end(),
                   [&](int a, int b) { return degree[a] < degree[b]; });
  std::vector<int> level(n, -1), probe_level(n, -1), order, probe;
  order.reserve(n);
  for (int seed : by_degree) {
    if (level[seed] >= 0) continue;
    // The last vertex of a search from the seed: far from it, near the
    // component's boundary.
    probe.clear();
    BreadthFirst(neighbours, degree, seed, &probe_level, &probe);
    BreadthFirst(neighbours, degree, probe.back(), &level, &order);
  }
  std::vector<int> rank(n);
  for (int r = 0; r < n; ++r) rank[order[r]] = r;
  return rank;
}

}  // namespace shellspace
