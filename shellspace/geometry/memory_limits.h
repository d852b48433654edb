// Memory estimates of the solves whose size the user picks (the steps of a
// path, the branching grid), checked before anything is allocated: above
// the limit, one line naming the input, the estimate and the limit. Both
// front ends (the CLI's verbs, the Python module) refuse the same sizes
// through these. The estimates are fits of the peak resident memory
// measured with /usr/bin/time (docs/cli-behaviour.md, "Limits"); they are
// rough, on the safe side for the meshes measured. The film strip's check,
// which needs its layout, is render/film_strip.h's CheckFilmStripMemory.
// (In geometry/, the room of InputError, not in runtime/: runtime/ sits
// below geometry/ and links nothing of the project.)
#ifndef SHELLSPACE_GEOMETRY_MEMORY_LIMITS_H_
#define SHELLSPACE_GEOMETRY_MEMORY_LIMITS_H_

#include <string>

namespace shellspace {

// The largest number of steps of any solve (the CLI's --steps; also
// bounded by the estimates below).
constexpr int kMaxSteps = 100000;

// Half the physical memory of the machine.
double MemoryLimitBytes();

// A geodesic solve (geodesic, log) of K steps on V vertices:
// 64 MB + 1500 B x V x K^2 (LM and the Newton finish on the whole path;
// measured 79 MB at V = 121, K = 16 and 749 MB at K = 64; 481 MB at V = 5,
// K = 1000).
double GeodesicBytes(int vertices, int steps);

// A path of `frames` shapes kept and written (shoot, transport, spline):
// 64 MB + 200 B x V x frames.
double PathBytes(int vertices, int frames);

// A spline or regression of K steps on V vertices (spline, regress):
// 64 MB + 24 B x (K + 1)^2 + 20 KB x V x (K + 1): the preconditioner's
// dense (K + 1) x (K + 1) time matrix, its Cholesky factor and the
// factorisation's copy (`--steps 100000` asked for 80 GB of it and ended in
// std::bad_alloc), and per shape the path, its gradient, midpoints and
// one-shape factors (measured 27, 123, 420 MB at V = 5, K = 500, 2000,
// 4000; 146 MB at V = 121, K = 200; 1.27 GB at V = 5261, K = 16).
double SplineBytes(int vertices, int steps);

// The branching simulation on `nodes` grid nodes: 16 MB + 3 KB x nodes
// (measured 18 MB at 2,112 nodes, 101 MB at 33,024).
double BranchingBytes(double nodes);

// A film strip (render; --png of the verbs that write frames): FilmStripBytes
// of render/film_strip.h, 6 B x W x H + 32 B x s^2 x frame pixels, s the
// supersampling (2): the 49152 x 8192 strip of 6 square frames needs about
// 11 GB. Checked by render/film_strip.h's CheckFilmStripMemory.
inline constexpr const char* kFilmStripModel =
    "6 B x width x height + 128 B x frame width x frame height";

// Throws InputError "<what> needs about X GB (<model>), above the limit
// Y GB (half the physical memory)" if estimate > MemoryLimitBytes().
void CheckMemory(double estimate, const std::string& what,
                 const std::string& model);

// The --help text of the bound of a film strip's size: "; the strip's
// estimated memory, kFilmStripModel, within half the physical memory (X GB
// here)".
std::string FilmStripBoundText();

// The --help text of the bound of the steps (the CLI's --steps) of a solve
// whose estimate is `model`.
std::string StepsBoundText(const std::string& model);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_MEMORY_LIMITS_H_
