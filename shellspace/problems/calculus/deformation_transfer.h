// Prolongation of a coarse deformation to the fine mesh by deformation
// transfer (docs/math.md, "Multiresolution").
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_DEFORMATION_TRANSFER_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_DEFORMATION_TRANSFER_H_

#include <memory>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/calculus/shared_decimation.h"

namespace shellspace {

// Carries a deformation of the coarse level (coarse reference -> coarse
// deformed) to the fine level. For each coarse face T the deformation
// gradient
//   D_T = [e1' e2' n'] [e1 e2 n]^-1
// (edges e1 = x1 - x0, e2 = x2 - x0 and unit normal n of T in the coarse
// reference, primed in the coarse deformed shape) maps the fine reference's
// edges of the fine faces nearest to T (by distance of the fine face's
// centroid to the coarse triangle, in the reference); then
//   x = argmin sum_{fine faces f} a_f sum_{edges (i, j) of f}
//           |x_j - x_i - D_T(f) (X_j - X_i)|^2
// with the survivors anchored at their coarse deformed positions (a sparse
// SPD system, the weighted graph Laplacian of the fine mesh on the
// non-survivors, factorised once per Prolongation). A rigid motion of the
// coarse level gives exactly the same rigid motion of the fine reference.
class Prolongation {
 public:
  // `fine_reference`: #V x 3, on `fine_faces`; `level`: a decimation of the
  // fine mesh (its survivors index fine vertices). `coarse_reference` is the
  // coarse shape the deformations passed to Apply start from (usually
  // level.shapes[s] for the fine reference's own shape s). Throws InputError
  // if a non-survivor has no path to a survivor (the system is singular).
  Prolongation(const Faces& fine_faces, const Positions& fine_reference,
               const SharedDecimation& level,
               const Positions& coarse_reference);
  ~Prolongation();

  // The fine shape whose deformation from the fine reference follows the
  // coarse one; `coarse_deformed` is #survivors x 3.
  Positions Apply(const Positions& coarse_deformed) const;

  // Per fine face, the coarse face whose deformation gradient it follows
  // (the nearest to its centroid in the references).
  const std::vector<int>& coarse_face_of() const { return coarse_face_of_; }

 private:
  struct Solver;
  Faces fine_faces_;
  Positions fine_reference_;
  Faces coarse_faces_;
  Positions coarse_reference_;
  std::vector<int> survivors_;
  std::vector<int> coarse_face_of_;  // per fine face
  std::vector<int> free_index_;      // per fine vertex: index among the free, or -1
  std::unique_ptr<Solver> solver_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_DEFORMATION_TRANSFER_H_
