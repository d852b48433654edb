// The two r = 2 cells with straight interfaces (docs/math.md, "Branching: the
// Kohn–Müller model"): the Kohn–Müller psi-junction cell ("km") and the needle
// cell ("needle", the T2 topology that the code formerly called km).
// Units: period h; coordinates s, eta of cell_pattern.h. Both start from the
// laminate -1 on [0, 1/4), +1 on [1/4, 3/4), -1 on [3/4, 1) and end (s = 1)
// in the laminate of period 1/2.
//
// Series (self_similar_series.h) with r = 2, S1 = 4 theta / (4 theta - 1),
// S2 = 1 / (1 - 2 theta):
//   C(theta) = 3 2^(-2/3) (A B^2)^(1/3) f(theta)^(1/3),
//   f(theta) = 4 theta (1 - theta) / ((4 theta - 1) (1 - 2 theta)^2).
// d log f / d theta = 0  <=>  8 theta^3 - 12 theta^2 + 1 = 0; with
// theta = 1/2 + t this is 4 t^3 - 3 t = 1/2 = cos(3 phi), t = cos(phi), and the
// root in (1/4, 1/2) is t = cos(5 pi / 9):
//   theta_2 = 1/2 + cos(5 pi / 9) = 1/2 - sin(pi / 18) = 0.326351822...,
//   f(theta_2) = (1 - 4 t^2) / (4 t^2 (1 + 4 t)) = (1 + 2 cos(pi / 9))^3
//   (= 23.872578108145; checked to 1e-13 in the tests), so
//   C = 3 2^(-2/3) (A B^2)^(1/3) (1 + 2 cos(pi/9)).
//
// NEEDLE (T2) cell: a -1 needle nucleates at eta = 1/2, in the middle of the
// +1 lamella, and the four interfaces move straight:
//   g1 = 1/4 - s/8 (+2),  g2 = 1/2 - s/8 (-2),  g3 = 1/2 + s/8 (+2),
//   g4 = 3/4 + s/8 (-2);  next generation at eta = 0.
// F = -sum_{g_i < eta} jump_i g_i' is 0, 1/4, 0, -1/4, 0 on the five pieces
// (widths 1/4 - s/8, s/4, ..), mean 0:  A = 2 (1/4)(1/4)^2 = 1/32 (with or
// without the optimal shift), B = 2 * 4 = 8, A B^2 = 2:
//   C_needle = 3 2^(-1/3) (1 + 2 cos(pi/9)) = 6.856108742239...
//
// KM (psi-junction) cell: the twin boundary g = 3/4 (+1 below, -1 above)
// splits into three, a lamella of each variant appearing on the twin plane:
//   g1 = 1/4 (+2, straight),  g2 = 3/4 - s/4 (-2),  g3 = 3/4 (+2, straight),
//   g4 = 3/4 + s/4 (-2);
// at s = 1: -1 [0, 1/4), +1 [1/4, 1/2), -1 [1/2, 3/4), +1 [3/4, 1): the
// coarse laminate scaled by 1/2 and shifted by 1/8 (next_offset = 1/4).
// F = -2 w' = -1/2 on (g2, g4) (width 2w = s/2, w = s/4) and 0 elsewhere, so
//   mean F^2 = s/8,  (mean F)^2 = s^2/16,
//   u = 0 on the cell edges (the lines g1, g3: F measured from a fixed
//     interface, no shift):  A_0 = int_0^1 s/8 ds = 1/16,
//   optimal per-column shift:  A = int_0^1 (s/8 - s^2/16) ds = 1/24,
//   B = 2 * 4 = 8;  A_0 B^2 = 4, A B^2 = 8/3:
//   C_KM (u = 0 on cell edges) = 3 (1 + 2 cos(pi/9)) = 8.638155724715...,
//   C_KM (optimal shift)       = 3 (2/3)^(1/3) (1 + 2 cos(pi/9))
//   = 7.546124092461...
// The needle value is C_KM(u = 0) / 2^(1/3).
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_KM_FAMILY_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_KM_FAMILY_H_

#include "shellspace/models/branching/cell_pattern.h"

namespace shellspace::branching {

// The cells as curves (evaluated by EvaluateCell, not by the closed forms).
CellPattern KmCellPattern();      // psi-junction
CellPattern NeedleCellPattern();  // T2

// The KM cell's fixed interface g1 = 1/4: u = 0 there in the "u = 0 on the
// cell edges" evaluation (EvaluateCell with anchor).
constexpr double kKmAnchor = 0.25;

// Closed forms derived above.
constexpr double kKmA = 1.0 / 24.0;        // optimal shift
constexpr double kKmAZeroEdge = 1.0 / 16.0;  // u = 0 on the cell edges
constexpr double kKmB = 8.0;
constexpr double kNeedleA = 1.0 / 32.0;
constexpr double kNeedleB = 8.0;

// theta_2 = 1/2 - sin(pi/18), optimal for every r = 2 cell.
double KmOptimalTheta();
// C(theta) for r = 2 and a given A B^2 (closed form above).
double R2ConstantAt(double AB2, double theta);
double KmClosedFormConstant();          // 3 (1 + 2 cos(pi/9)), u = 0 edges
double KmShiftedClosedFormConstant();   // 3 (2/3)^(1/3) (1 + 2 cos(pi/9))
double NeedleClosedFormConstant();      // 3 2^(-1/3) (1 + 2 cos(pi/9))

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_KM_FAMILY_H_
