// Transfer of a relaxed field onto another grid of the same domain: the
// continuation of the delta -> 0 extrapolation (simulation.h) starts the
// solve at each narrower width from the converged field of the previous
// width, interpolated onto the finer grid, so that every width keeps the
// same pattern (periods, nucleation sites) instead of restarting from a
// fresh initial guess.
//
// Bilinear interpolation of the nodal values (relaxed_grid.h):
//   u'(x, y) = (1 - a)(1 - b) u_{i,j} + a (1 - b) u_{i+1,j}
//              + (1 - a) b u_{i,j+1} + a b u_{i+1,j+1},
//   x_i <= x <= x_{i+1}, a = (x - x_i) / (x_{i+1} - x_i)   (graded rows),
//   y = (j + b) dy, 0 <= b < 1, j + 1 taken modulo ny       (periodic).
// Row 0 of the target is the austenite row of the source (u = 0), so the
// boundary condition is kept; the slopes u_y of the target are the source
// slopes (piecewise constant in y), i.e. the interfaces keep their position
// and their width delta_old, which the next solve sharpens.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_FIELD_TRANSFER_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_FIELD_TRANSFER_H_

#include "shellspace/models/branching/relaxed_grid.h"

namespace shellspace::branching {

// `from` interpolated onto `to` (same length and height; InputError if not).
RelaxedField TransferField(const RelaxedField& from, const RelaxedGrid& to);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_FIELD_TRANSFER_H_
