// The grid of the relaxed (diffuse-interface) simulation and the nodal field u
// on it (docs/math.md, "Branching: the Kohn–Müller model", relaxed model).
#ifndef SHELLSPACE_MODELS_BRANCHING_RELAXED_GRID_H_
#define SHELLSPACE_MODELS_BRANCHING_RELAXED_GRID_H_

#include <cstddef>
#include <vector>

namespace shellspace::branching {

// Domain (0, L) x [0, H), x = distance from the austenite, y periodic.
// Nodes: x_i = L (i / nx)^grading, i = 0..nx (grading >= 1 refines toward the
// austenite at x = 0; grading = 1 is uniform), y_j = j dy, dy = H / ny,
// j = 0..ny-1 (periodic). Row i = 0 is the austenite, u = 0 there.
//
// Quadrature (documented choice; the spec only asks for cell weights):
//  - x-edges (i-1 -> i) carry the elastic term with weight dx_i dy / H;
//  - node row i >= 1 carries the y-terms (gradient at nodes, double well at
//    the staggered y-edges) with x-weight wx_i = x_{i+1/2} - x_{i-1/2},
//    x_{i+1/2} = (x_i + x_{i+1}) / 2, where x_{1/2} := 0 and
//    x_{nx+1/2} := L. The austenite row (u_y = 0, a constant) is thus not
//    counted; the y-weights of the rows i >= 1 sum to L.
struct RelaxedGrid {
  double length = 1.0;  // L
  double height = 1.0;  // H
  int nx = 0;           // number of x-cells (nx + 1 node rows)
  int ny = 0;           // number of nodes per column (periodic)
  double grading = 1.0;

  RelaxedGrid() = default;
  RelaxedGrid(double length, double height, int nx, int ny, double grading);

  double x(int i) const { return x_[i]; }
  double dx(int i) const { return x_[i] - x_[i - 1]; }  // i >= 1
  double dy() const { return height / ny; }
  double y(int j) const { return j * dy(); }
  // x-weight of node row i >= 1 (see above).
  double wx(int i) const;
  int index(int i, int j) const { return i * ny + j; }
  int num_nodes() const { return (nx + 1) * ny; }
  const std::vector<double>& xs() const { return x_; }

 private:
  std::vector<double> x_;
};

// Nodal values u_{ij} = u[grid.index(i, j)]; row 0 is zero.
struct RelaxedField {
  RelaxedGrid grid;
  std::vector<double> u;

  explicit RelaxedField(const RelaxedGrid& g)
      : grid(g), u(static_cast<size_t>(g.num_nodes()), 0.0) {}
  double& at(int i, int j) { return u[grid.index(i, j)]; }
  double at(int i, int j) const { return u[grid.index(i, j)]; }
  // Staggered slope (u_{i,j+1} - u_{ij}) / dy, periodic in j.
  double uy(int i, int j) const {
    return (at(i, (j + 1) % grid.ny) - at(i, j)) / grid.dy();
  }
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_MODELS_BRANCHING_RELAXED_GRID_H_
