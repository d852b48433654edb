// The consumers' mesh, built in code (no data files): a flat
// kGridSize x kGridSize grid on [0, 1]^2 in the plane z = 0, each cell split
// into two counter-clockwise triangles.
#ifndef SHELLSPACE_CONSUMER_GRID_H_
#define SHELLSPACE_CONSUMER_GRID_H_

#include <shellspace/geometry/mesh.h>

namespace consumer {

constexpr int kGridSize = 4;  // vertices per side
constexpr double kSpacing = 1.0 / (kGridSize - 1);

inline int VertexIndex(int i, int j) { return j * kGridSize + i; }

inline shellspace::Mesh MakeFlatGrid() {
  shellspace::Mesh mesh;
  mesh.positions.resize(kGridSize * kGridSize, 3);
  for (int j = 0; j < kGridSize; ++j) {
    for (int i = 0; i < kGridSize; ++i) {
      mesh.positions.row(VertexIndex(i, j)) << i * kSpacing, j * kSpacing, 0.0;
    }
  }
  const int num_cells = (kGridSize - 1) * (kGridSize - 1);
  mesh.faces.resize(2 * num_cells, 3);
  int face = 0;
  for (int j = 0; j + 1 < kGridSize; ++j) {
    for (int i = 0; i + 1 < kGridSize; ++i) {
      const int v00 = VertexIndex(i, j);
      const int v10 = VertexIndex(i + 1, j);
      const int v01 = VertexIndex(i, j + 1);
      const int v11 = VertexIndex(i + 1, j + 1);
      mesh.faces.row(face++) << v00, v10, v11;
      mesh.faces.row(face++) << v00, v11, v01;
    }
  }
  return mesh;
}

}  // namespace consumer

#endif  // SHELLSPACE_CONSUMER_GRID_H_
