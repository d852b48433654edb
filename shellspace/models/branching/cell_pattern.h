// Room note: this header (the cell evaluator and its quadrature) and
// lens_family.h live in cost_functions/branching/ because the lens cost
// function needs the lens profile and the Gauss–Legendre rule; the r = 2
// families (km_family.h) and the general search stay in problems/branching/.
//
// One cell of a self-similar branching construction in the sharp-interface
// model (docs/math.md, "Branching: the Kohn–Müller model"), and the exact
// evaluation of its energy coefficients A (elastic) and B (interfacial).
#ifndef SHELLSPACE_MODELS_BRANCHING_CELL_PATTERN_H_
#define SHELLSPACE_MODELS_BRANCHING_CELL_PATTERN_H_

#include <functional>
#include <string>
#include <vector>

namespace shellspace::branching {

// Cell coordinates: s = (x_k - x) / l_k in [0, 1] runs from the coarse end of
// the cell (s = 0, far from the austenite) to the fine end (s = 1), and
// eta = (y - offset_k) / h_k in [0, 1) is the position in one period h_k.
//
// An interface is a curve eta = g(s) (taken mod 1) on [s_begin, s_end]; its
// `jump` is the jump of u_y when eta crosses it upward: +2 (variant -1 below,
// +1 above) or -2. `position(s)` returns g, `velocity(s)` returns dg/ds.
struct InterfaceCurve {
  int jump = 2;
  double s_begin = 0.0;
  double s_end = 1.0;
  std::function<double(double)> position;
  std::function<double(double)> velocity;
};

// A cell: its interfaces, the period ratio r (the period at s = 1 is 1/r),
// and the offset of the next generation: the next cell's eta = 0 sits at
// eta = next_offset / r of this one (0 for KM; 1/2 for the variant-swapping
// lens cell).
struct CellPattern {
  std::string family;
  int r = 2;
  double next_offset = 0.0;
  // The next generation is the variant-swapped copy (u -> -u, same energy):
  // generation k draws (-1)^k u_y (general cells with an odd label offset).
  bool swap_variants = false;
  std::vector<InterfaceCurve> interfaces;
  // Breakpoints of the s-integration besides 0 and 1 (tips of interfaces).
  std::vector<double> breakpoints;
};

// The interfaces crossing the column s, sorted by position in [0, 1).
struct ColumnState {
  std::vector<double> position;  // in [0, 1), ascending
  std::vector<double> velocity;  // d position / ds
  std::vector<int> jump;         // +-2
};
ColumnState StateAt(const CellPattern& pattern, double s);

// u_y (+1 or -1) at (s, eta), and the distance (in units of the period) from
// eta to the nearest interface of the column.
int VariantAt(const ColumnState& column, double eta, double* distance = nullptr);

// Elastic energy density of the column, scaled: with u_y fixed by the
// interfaces, u_x = c'(x) - sum_{g_i < y} jump_i g_i'(x); the per-column
// shift c' removes the mean over one period, so the density per unit height
// is (h / l)^2 Var_eta(F), F(eta) = -sum_{g_i < eta} jump_i dg_i/ds. Returns
// Var_eta(F) (piecewise-constant F, exact).
double ColumnVariance(const ColumnState& column);

// Energy coefficients of a cell: one period h, length l, per unit height
//   E_cell = A h^2 / l + B eps l / h,
//   A = \int_0^1 Var_eta(F)(s) ds  (Gauss–Legendre on the pieces between
//       breakpoints, `points` nodes each; exact for polynomial integrands of
//       degree < 2 points),
//   B = 2 sum_i (s_end,i - s_begin,i)  (each interface adds 2 to TV_y over
//       the projected x-extent it spans; one period).
struct CellCoefficients {
  double A = 0.0;
  double B = 0.0;
};
CellCoefficients EvaluateCell(const CellPattern& pattern, int points = 16);

// The same with u = 0 on the line eta = anchor in every column instead of
// the optimal per-column shift (cells glued with u = 0 on their edges, as in
// Kohn–Müller's construction): A = \int_0^1 mean_eta (F - F(anchor))^2 ds.
// `anchor` must not lie on a moving interface.
double ColumnMeanSquare(const ColumnState& column, double anchor);
CellCoefficients EvaluateCellZeroAt(const CellPattern& pattern, double anchor,
                                    int points = 16);

// Gauss–Legendre nodes and weights on [0, 1].
void GaussLegendre01(int points, std::vector<double>* nodes,
                     std::vector<double>* weights);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_MODELS_BRANCHING_CELL_PATTERN_H_
