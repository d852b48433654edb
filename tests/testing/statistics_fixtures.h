// The shapes and settings shared by the statistics tests
// (tests/problems/statistics/): the four spheres of ../shared/data, the
// solver settings of their solves, Gaussian noise on positions.
#ifndef SHELLSPACE_TESTS_TESTING_STATISTICS_FIXTURES_H_
#define SHELLSPACE_TESTS_TESTING_STATISTICS_FIXTURES_H_

#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace::testing {

// The unit sphere (162 vertices) and its deformations along x, y and z.
inline constexpr const char* kSpheres[] = {
    "sphere/unitSphere1.ply", "sphere/unitSphere1_defX.ply",
    "sphere/unitSphere1_defY.ply", "sphere/unitSphere1_defZ.ply"};

// The positions of the kSpheres, in order.
std::vector<Positions> LoadSpheres();

// The settings of the statistics solves: gradient tolerance 1e-10,
// function tolerance 1e-14, the rest the defaults.
SolverSettings StatisticsSettings();

// rows x 3 positions with independent normal entries of standard deviation
// `scale` (fixed seed).
Positions GaussianNoise(int rows, double scale, unsigned seed);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_STATISTICS_FIXTURES_H_
