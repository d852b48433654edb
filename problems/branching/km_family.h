// The Kohn–Müller (KM) branching cell: straight interfaces, every +1 lamella
// splits into two (spec branching.md, "KM family"), r = 2.
//
// Cell (units: period h, coordinates s, eta of cell_pattern.h). At the coarse
// end (s = 0) the laminate -1 on [0, 1/4), +1 on [1/4, 3/4), -1 on [3/4, 1);
// a -1 wedge nucleates at eta = 1/2 and the four interfaces move straight:
//   g1 = 1/4 - s/8 (jump +2),  g2 = 1/2 - s/8 (jump -2),
//   g3 = 1/2 + s/8 (jump +2),  g4 = 3/4 + s/8 (jump -2),
// so that at s = 1 the laminate of period 1/2 (interfaces 1/8, 3/8, 5/8, 7/8)
// is reached with the same phase: the next generation starts at eta = 0. The
// +1 fraction (g2 - g1) + (g4 - g3) = 1/2 in every column.
//
// Closed form. F = -sum_{g_i < eta} jump_i g_i' takes the values 0 on
// [0, g1), 1/4 on (g1, g2), 0 on (g2, g3), -1/4 on (g3, g4), 0 on (g4, 1);
// the pieces (g1, g2), (g3, g4) have width 1/4 each, so the mean is 0 and
//   A = Var F = 2 (1/4) (1/4)^2 = 1/32.
// Four interfaces span the whole cell: B = 2 * 4 = 8 (per period h, per unit
// height: E_cell = h^2 / (32 l) + 8 eps l / h).
// Series (self_similar_series.h) with r = 2, S1 = 4 theta / (4 theta - 1),
// S2 = 1 / (1 - 2 theta); since (A)^(1/3) (B)^(2/3) = 2^(1/3),
//   C(theta) = 3 2^(-1/3) [4 theta (1 - theta) /
//                         ((4 theta - 1) (1 - 2 theta)^2)]^(1/3).
// d log C / d theta = 0  <=>  8 theta^3 - 12 theta^2 + 1 = 0; with
// theta = 1/2 + t this is 4 t^3 - 3 t = 1/2 = cos(3 phi), t = cos(phi), and the
// root in (1/4, 1/2) is t = cos(5 pi / 9):
//   theta_KM = 1/2 + cos(5 pi / 9) = 1/2 - sin(pi / 18) = 0.326351822...
//   C_KM = C(theta_KM) = 6.856108742239...
// and h0 = (8 eps l0^2 S2 / (2 S1 / 32))^(1/3) = (128 eps l0^2 S2 / S1)^(1/3).
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_KM_FAMILY_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_KM_FAMILY_H_

#include "shellspace/cost_functions/branching/cell_pattern.h"

namespace shellspace::branching {

// The KM cell as curves (evaluated by EvaluateCell, not by the closed form).
CellPattern KmCellPattern();

// Closed forms derived above.
constexpr double kKmA = 1.0 / 32.0;
constexpr double kKmB = 8.0;
double KmOptimalTheta();         // 1/2 - sin(pi/18)
double KmClosedFormConstant();   // C(theta_KM)
double KmConstantAt(double theta);  // C(theta), closed form

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_KM_FAMILY_H_
