// Comparing two shells or two paths of one connectivity: the check a
// downstream test suite runs against a pinned reference solution
// (`shellspace compare`, Python `shellspace.compare`).
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_SHAPE_COMPARISON_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_SHAPE_COMPARISON_H_

#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {

// One frame: b_k rigidly aligned onto a_k (AlignRigidly, Kabsch; the
// identity instead if it leaves no larger sum of squared distances, so
// equal frames compare exactly 0), then |a_k,i - b_k,i| over the vertices
// i.
struct FrameDifference {
  double max_distance = 0;   // max_i
  double mean_distance = 0;  // mean_i
};

struct ShapeComparison {
  std::vector<FrameDifference> frames;  // one per frame (K + 1)
  double max_distance = 0;   // max over frames
  double mean_distance = 0;  // mean over frames and vertices
  double diameter = 0;       // bounding-box diagonal of a_0 (the scale)
  double relative_max_distance = 0;  // max_distance / diameter
  // Two single shells (one frame each): W[a_0, b_0] (zero iff equal up to a
  // rigid motion) in `energy_a_to_b`; energy_a = energy_b = 0. Paths
  // (K + 1 >= 2 frames each): E_K of each path and
  // |E_K(a) - E_K(b)| / max(E_K(a), E_K(b)) (0 if both are 0).
  double energy_a_to_b = 0;
  double energy_a = 0, energy_b = 0;
  double relative_energy_difference = 0;
};

// The verdict against tolerances: the shapes agree if relative_max_distance
// <= tolerance, the energies if the sides are single shells or
// relative_energy_difference <= energy_tolerance.
struct ComparisonVerdict {
  bool shapes_agree = false;
  bool energies_agree = false;
  bool agree() const { return shapes_agree && energies_agree; }
};
ComparisonVerdict JudgeComparison(const ShapeComparison& comparison,
                                  double tolerance, double energy_tolerance);

// Compares a and b (each K + 1 >= 1 frames of #V x 3, the connectivity of
// `space`; W and E_K with its material). Throws InputError if the frame
// counts or vertex counts differ, naming both.
ShapeComparison CompareShapes(const ShellSpace& space, const ShellPath& a,
                              const ShellPath& b);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_SHAPE_COMPARISON_H_
