// CuthillMcKeeRanks on procedural graphs: a permutation; on a grid whose
// vertices are numbered at random, a bandwidth of the order of the grid's
// side (the twin: the random numbering's own bandwidth, measured by the same
// helper, is far above it); one contiguous block per connected component;
// the same ranks for the same graph.
#include "shellspace/geometry/locality_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace shellspace {
namespace {

using Graph = std::vector<std::vector<int>>;

// A side x side grid (4-neighbours), vertex (x, y) numbered label[y side +
// x], in a graph of `size` vertices (default: the grid's).
Graph Grid(int side, const std::vector<int>& label, int size = 0) {
  Graph g(size > 0 ? size : side * side);
  const auto link = [&](int a, int b) {
    g[label[a]].push_back(label[b]);
    g[label[b]].push_back(label[a]);
  };
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      if (x + 1 < side) link(y * side + x, y * side + x + 1);
      if (y + 1 < side) link(y * side + x, (y + 1) * side + x);
    }
  }
  return g;
}

// max |rank[v] - rank[w]| over the edges.
int Bandwidth(const Graph& g, const std::vector<int>& rank) {
  int width = 0;
  for (int v = 0; v < static_cast<int>(g.size()); ++v) {
    for (int w : g[v]) width = std::max(width, std::abs(rank[v] - rank[w]));
  }
  return width;
}

std::vector<int> Shuffled(int n, unsigned seed) {
  std::vector<int> label(n);
  std::iota(label.begin(), label.end(), 0);
  std::shuffle(label.begin(), label.end(), std::mt19937(seed));
  return label;
}

TEST(LocalityOrderTest, ShuffledGridGetsTheBandwidthOfItsSide) {
  const int side = 30;
  const Graph g = Grid(side, Shuffled(side * side, 7));
  const std::vector<int> rank = CuthillMcKeeRanks(g);
  std::vector<int> sorted = rank;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(side * side);
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(sorted, identity);  // a permutation
  // Breadth-first levels of a grid from a corner are its anti-diagonals
  // (at most `side` vertices): an edge spans at most two levels.
  EXPECT_LE(Bandwidth(g, rank), 2 * side);
  // Twin: the shuffled numbering itself, through the same helper.
  EXPECT_GT(Bandwidth(g, identity), 10 * side);
  // Deterministic.
  EXPECT_EQ(CuthillMcKeeRanks(g), rank);
}

TEST(LocalityOrderTest, EachComponentIsOneBlock) {
  // Two shuffled grids side by side, interleaved in the numbering, and an
  // isolated vertex.
  const int side = 8, n = side * side;
  const std::vector<int> shuffled = Shuffled(2 * n, 3);
  std::vector<int> first(shuffled.begin(), shuffled.begin() + n);
  std::vector<int> second(shuffled.begin() + n, shuffled.end());
  Graph g = Grid(side, first, 2 * n + 1);
  const Graph other = Grid(side, second, 2 * n + 1);
  for (int v = 0; v < 2 * n + 1; ++v) {
    g[v].insert(g[v].end(), other[v].begin(), other[v].end());
  }
  const std::vector<int> rank = CuthillMcKeeRanks(g);
  for (const std::vector<int>& labels : {first, second}) {
    int low = 2 * n + 1, high = -1;
    for (int v : labels) {
      low = std::min(low, rank[v]);
      high = std::max(high, rank[v]);
    }
    EXPECT_EQ(high - low, n - 1);
  }
  EXPECT_TRUE(rank[2 * n] == 0 || rank[2 * n] == 2 * n);
}

}  // namespace
}  // namespace shellspace
