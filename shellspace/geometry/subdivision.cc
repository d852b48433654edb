#include "shellspace/geometry/subdivision.h"

#include <algorithm>
#include <map>
#include <string>

namespace shellspace {

MidpointSubdivision::MidpointSubdivision(const Faces& coarse, int num_vertices)
    : num_coarse_vertices(num_vertices) {
  std::map<std::pair<int, int>, int> midpoint;
  const auto mid = [&](int i, int j) {
    const std::pair<int, int> key(std::min(i, j), std::max(i, j));
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    const int index = num_vertices + static_cast<int>(parents.size());
    parents.push_back({key.first, key.second});
    midpoint.emplace(key, index);
    return index;
  };
  faces.resize(4 * coarse.rows(), 3);
  for (int f = 0; f < coarse.rows(); ++f) {
    const int a = coarse(f, 0), b = coarse(f, 1), c = coarse(f, 2);
    if (a < 0 || b < 0 || c < 0 || a >= num_vertices || b >= num_vertices ||
        c >= num_vertices) {
      throw InputError("subdivision: face " + std::to_string(f) +
                       " has a vertex index out of range");
    }
    const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    faces.row(4 * f + 0) << a, ab, ca;
    faces.row(4 * f + 1) << ab, b, bc;
    faces.row(4 * f + 2) << ca, bc, c;
    faces.row(4 * f + 3) << ab, bc, ca;
  }
}

Positions MidpointSubdivision::Apply(const Positions& coarse) const {
  if (coarse.rows() != num_coarse_vertices) {
    throw InputError("subdivision: the shape has " +
                     std::to_string(coarse.rows()) + " vertices, expected " +
                     std::to_string(num_coarse_vertices));
  }
  Positions fine(num_vertices(), 3);
  fine.topRows(num_coarse_vertices) = coarse;
  for (size_t e = 0; e < parents.size(); ++e) {
    fine.row(num_coarse_vertices + e) =
        0.5 * (coarse.row(parents[e][0]) + coarse.row(parents[e][1]));
  }
  return fine;
}

std::vector<int> MidpointSubdivision::CarryMask(
    const std::vector<int>& mask) const {
  std::vector<char> in(num_coarse_vertices, 0);
  for (int v : mask) {
    if (v >= 0 && v < num_coarse_vertices) in[v] = 1;
  }
  std::vector<int> out;
  for (int v = 0; v < num_coarse_vertices; ++v) {
    if (in[v]) out.push_back(v);
  }
  for (size_t e = 0; e < parents.size(); ++e) {
    if (in[parents[e][0]] && in[parents[e][1]]) {
      out.push_back(num_coarse_vertices + static_cast<int>(e));
    }
  }
  return out;
}

std::vector<int> VertexRing(const Faces& faces, int num_vertices, int seed,
                            int rings) {
  if (seed < 0 || seed >= num_vertices) {
    throw InputError("vertex ring: seed vertex " + std::to_string(seed) +
                     " out of range");
  }
  std::vector<std::vector<int>> neighbours(num_vertices);
  for (int f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      neighbours[faces(f, c)].push_back(faces(f, (c + 1) % 3));
      neighbours[faces(f, (c + 1) % 3)].push_back(faces(f, c));
    }
  }
  std::vector<int> distance(num_vertices, -1);
  std::vector<int> frontier = {seed};
  distance[seed] = 0;
  for (int r = 1; r <= rings; ++r) {
    std::vector<int> next;
    for (int v : frontier) {
      for (int w : neighbours[v]) {
        if (distance[w] < 0) {
          distance[w] = r;
          next.push_back(w);
        }
      }
    }
    frontier = std::move(next);
  }
  std::vector<int> out;
  for (int v = 0; v < num_vertices; ++v) {
    if (distance[v] >= 0) out.push_back(v);
  }
  return out;
}

}  // namespace shellspace
