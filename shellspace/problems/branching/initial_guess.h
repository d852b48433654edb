// Initial fields of the relaxed simulation (docs/math.md, "Branching: the
// Kohn–Müller model"): never u = 0; transitions smoothed to the width delta.
//
// Every initialisation prescribes a smoothed slope field
//   u_y(x, y) = v(x, y) tanh(d(x, y) / delta),
// v = +-1 the variant of a sharp pattern and d the y-distance to its nearest
// interface (the optimal 1D profile of the double well is tanh(y / delta)).
// Column by column u is then integrated in y: u_{j+1} - u_j = the Simpson
// mean of u_y over the edge times dy, minus the column mean of these
// increments (so u is periodic), and shifted to zero column mean (the
// optimal per-column shift of the sharp model, which vanishes at x = 0).
// Row 0 stays 0.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_INITIAL_GUESS_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_INITIAL_GUESS_H_

#include <functional>
#include <string>

#include "shellspace/models/branching/construction.h"
#include "shellspace/models/branching/relaxed_grid.h"

namespace shellspace::branching {

// Fills rows i >= 1 of `field` from a slope function u_y(x, y) (see above);
// `ramp(x)` (in [0, 1]) multiplies the result, e.g. a boundary layer.
void FillFromSlope(RelaxedField* field,
                   const std::function<double(double, double)>& slope,
                   const std::function<double(double)>& ramp = nullptr);

// Laminate of `periods` periods in H (-1 on [0, p/4), +1 on [p/4, 3p/4),
// -1 on [3p/4, p)), ramped linearly to 0 over x < p / 2 (a boundary layer of
// the width of the period).
void InitLaminate(RelaxedField* field, int periods, double delta);

// u_y = tanh(phi / delta), phi a random trigonometric polynomial in y with
// x-dependent phases (fixed `seed`), projected to zero column mean.
void InitRandom(RelaxedField* field, unsigned seed, double delta);

// A sampled sharp construction (km, needle or lens, construction.h).
void InitConstruction(RelaxedField* field, const Construction& construction,
                      double delta);

// Number of first-generation periods fitting H for the needle (T2)
// construction with the optimal h0 of (epsilon, L): max(1, round(H / h0*))
// (the default period count of every --init).
int KmPeriodsFor(double epsilon, double length, double height);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_INITIAL_GUESS_H_
