// The initial path of a geodesic solve (docs/math.md, "Path energy and discrete
// geodesics"; thesis §6.3.1-6.3.2): the linear interpolation of the end shapes
// with the rigid motion between them removed, or, where that path passes
// through collapsed or turned-over triangles, the LΘA path -- shells whose edge
// lengths, areas and dihedral angles interpolate those of the ends.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_GEODESIC_INITIAL_PATH_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_GEODESIC_INITIAL_PATH_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/shell_path.h"
#include "shellspace/geometry/named_values.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// How the initial path is made:
//  - kLinear: LinearPathWithoutRigidMotion;
//  - kLTheta: LThetaPath;
//  - kRotations: RotationBlendPath (rotation_blend_path.h);
//  - kAuto: kLinear unless that path degenerates (FindPathDegeneracy),
//    then kRotations unless that path degenerates too, then kLTheta (its
//    frames at most kAutoLThetaFrameIterations LM iterations each).
enum class GeodesicInit { kAuto, kLinear, kLTheta, kRotations };

// The names "auto", "linear", "ltheta", "rotations"
// (geometry/named_values.h).
inline constexpr NamedValue<GeodesicInit> kGeodesicInitNames[] = {
    {GeodesicInit::kAuto, "auto"},
    {GeodesicInit::kLinear, "linear"},
    {GeodesicInit::kLTheta, "ltheta"},
    {GeodesicInit::kRotations, "rotations"}};
const char* GeodesicInitName(GeodesicInit init);

// The LM iterations of each LΘA frame when kAuto chose the LΘA path (a
// start, not a solution: the geodesic solve that follows corrects it; an
// explicit kLTheta keeps the settings' iterations). On meshes where the
// reconstruction converges it does so in about 20 (the triceratops of the
// stress corpus, 2.8k vertices bent by 75 degrees: 18 to 24 per frame);
// where it does not, each of the K - 1 frames would spend the whole
// budget (a 13k-vertex mannequin of many tiny triangles, bent by 120
// degrees: 30 to 200 iterations per frame, 0.6 s each, the 300 s time
// limit spent before the geodesic's first iteration).
inline constexpr int kAutoLThetaFrameIterations = 25;

// Below this rotation between the end shapes (the Kabsch rotation of the
// end onto the start, in degrees) the linear path interpolates the
// positions as they are: the rigid motion is not worth a different path
// (and a pair that is already aligned keeps the plain linear path to the
// bit).
inline constexpr double kRigidBlendMinDegrees = 1.0;

// The linear path degenerates where a triangle of an inner shape keeps less
// than this fraction of the smaller of its two end areas (a triangle passes
// near a point or a segment) or where a triangle's normal turns by more
// than 90 degrees between two consecutive shapes (it turns over).
inline constexpr double kDegenerateAreaRatio = 0.1;

// The K + 1 shapes s_k = BlendRigidly(start, end, k / K) (ltheta_
// reconstruction.h): positions blended after the rigid motion from end to
// start is removed, and the blend moved by the fraction k / K of that
// motion. Without a mask and with a rotation of at least
// kRigidBlendMinDegrees; otherwise (a mask anchors the shapes, whose
// vertices stay at their linear positions, or the ends are aligned) the
// plain linear path LinearPath(start, end, steps). *rotation_degrees gets
// the rotation angle if given.
ShellPath LinearPathWithoutRigidMotion(const Positions& start,
                                       const Positions& end, int steps,
                                       const std::vector<int>& fixed_vertices,
                                       double* rotation_degrees = nullptr);

// Where a path degenerates (kDegenerateAreaRatio): the smallest area ratio
// |f(s_k)| / min(|f(s_0)|, |f(s_K)|) over the inner shapes and where, and
// the number of faces that turn over between consecutive shapes (normals
// with a negative dot product) and the first of them.
struct PathDegeneracy {
  double smallest_area_ratio = 1;
  int area_shape = -1, area_face = -1;
  int turned_faces = 0;
  int turned_shape = -1, turned_face = -1;
  bool degenerate() const {
    return smallest_area_ratio < kDegenerateAreaRatio || turned_faces > 0;
  }
  // "triangle 12 of shape 4 keeps 0.03 of its area" / "... turns over
  // between shapes 3 and 4" / "no degenerate triangle".
  std::string Describe() const;
};
// Faces listed in `ignored` (face ids, e.g. the slivers of the start,
// whose normals a tiny move flips) are not counted.
PathDegeneracy FindPathDegeneracy(const Faces& faces, const ShellPath& path,
                                  const std::vector<int>& ignored = {});

// The LΘA path: every inner shape s_k (t = k / K) reconstructed
// (ReconstructFromLTheta) from the edge lengths, areas and dihedral angles
// interpolated linearly between the ends ((1 - t) q_0 + t q_K; dihedral
// angles unwrapped, each within pi of the start's), from the guess
// LinearPathWithoutRigidMotion's s_k, with the mask's vertices held there
// (their linear positions), or without a mask, pinned at three vertices and
// finally rigidly aligned to the guess. This is the two-keyframe LΘA spline
// (problems/splines/ltheta_spline.h): the natural cubic spline through two
// values is the straight line. The frames are independent and solved in
// parallel (settings.num_threads threads, each solve on one thread: the
// result does not depend on the thread count); each at most
// settings.max_iterations LM iterations to settings' tolerances.
// `iterations` (if given) gets the LM iterations summed over the frames,
// `unconverged` the frames that stopped short of Ceres' convergence.
// settings.stop is asked by each frame's LM: a stopped frame keeps its
// last iterate.
ShellPath LThetaPath(const ShellSpace& space, const Positions& start,
                     const Positions& end, int steps,
                     const std::vector<int>& fixed_vertices,
                     const SolverSettings& settings, int* iterations = nullptr,
                     std::vector<int>* unconverged = nullptr);

// What MakeGeodesicInitialPath did.
struct InitialPathReport {
  GeodesicInit requested = GeodesicInit::kAuto;
  GeodesicInit used = GeodesicInit::kLinear;  // kLinear, kLTheta, kRotations
  double rotation_degrees = 0;  // between the ends (Kabsch)
  bool rigid_motion_removed = false;
  // The linear path's degeneracy (found for kAuto and kLinear).
  PathDegeneracy linear;
  int ltheta_iterations = 0;              // kLTheta: LM iterations, summed
  std::vector<int> ltheta_unconverged;    // kLTheta: frames short of it
  // One line: why this path, e.g. "linear (no degenerate triangle)" or
  // "ltheta (the linear path degenerates: triangle 12 of shape 4 keeps
  // 0.03 of its area)".
  std::string reason;
  double seconds = 0;  // wall clock, information only
};

// The initial path of a geodesic from `start` to `end` with `steps` steps
// by `init` (see GeodesicInit; kAuto: linear unless it degenerates).
// `settings` are those of the LΘA reconstructions (iterations, tolerances,
// threads, stop).
ShellPath MakeGeodesicInitialPath(const ShellSpace& space,
                                  const Positions& start, const Positions& end,
                                  int steps,
                                  const std::vector<int>& fixed_vertices,
                                  GeodesicInit init,
                                  const SolverSettings& settings,
                                  InitialPathReport* report = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_GEODESIC_INITIAL_PATH_H_
