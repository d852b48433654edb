// Named example sets made procedurally (no data files): poses of one shell,
// a vertex mask and a variation, for trying the calculus from a bare
// checkout.
#ifndef SHELLSPACE_GEOMETRY_EXAMPLE_POSES_H_
#define SHELLSPACE_GEOMETRY_EXAMPLE_POSES_H_

#include <string>
#include <utility>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// Shapes sharing `faces`, each with the name of its file ("finger0"), the
// vertices a mask holds, and what the set is.
struct ExampleSet {
  std::string name;
  std::string description;
  Faces faces;
  std::vector<std::pair<std::string, Positions>> shapes;
  std::vector<int> mask;  // 0-based vertex indices; may be empty
};

// The names MakeExampleSet knows, each with its description, in the order
// they are listed.
std::vector<std::pair<std::string, std::string>> ExampleSetNames();

// The set `name`:
//   finger      the demo's finger (MakeFinger, 721 vertices) straight
//               (finger0) and bent by 90 degrees (finger1), its two base
//               rings as the mask, and finger_var: finger0 with a bump on
//               its side;
//   plate       a flat plate of equilateral triangles (plate0, 323
//               vertices), rolled onto a cylinder about its y axis (plate1)
//               and about its x axis (plate2), the vertices near its centre
//               as the mask, and plate_var: plate0 with a bump;
//   cylinder    an open tube (cylinder0, 576 vertices), twisted by 90
//               degrees from bottom to top (cylinder1), its bottom ring as
//               the mask, and cylinder_var: cylinder0 with a bump;
//   collection  seven poses of a smaller finger (pose0 ... pose6, 321
//               vertices) bent by 0, 15, ..., 90 degrees alternately to
//               either side of the x-y plane, for the mean, PCA and
//               regression; its two base rings as the mask.
// Throws InputError for another name.
ExampleSet MakeExampleSet(const std::string& name);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_EXAMPLE_POSES_H_
