// Multiresolution geodesic interpolation (docs/math.md, "Multiresolution";
// thesis §6.3.3): decimate the end shapes with one shared connectivity, solve
// the geodesic on the coarse level, prolongate its inner shapes by deformation
// transfer, finish on the fine level.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_MULTIRESOLUTION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_MULTIRESOLUTION_H_

#include <string>
#include <vector>

#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {

struct MultiresolutionSettings {
  // Coarse levels below the input mesh; 0 solves on the input mesh alone.
  int levels = 1;
  // Each level keeps this fraction of the vertices of the one above it.
  double reduction = 0.25;
  // No level is coarser than this many vertices (fewer levels are used).
  int min_vertices = 200;
  // The coarse levels stop at this relative gradient (the fine finish
  // reaches the caller's tolerance): their solutions only seed the next
  // level.
  double coarse_gradient_tolerance = 1e-6;
};

// Multiresolution below this many vertices per level is not used by the
// automatic choice.
inline constexpr int kAutoMinVertices = 2500;

// How many coarse levels a caller asks for: a number, or automatic (as
// many as keep the coarsest at kAutoMinVertices or more; none for meshes
// below 4 kAutoMinVertices).
struct MultiresolutionChoice {
  bool automatic = true;
  int levels = 0;  // when not automatic, 0 .. 8
  static MultiresolutionChoice Automatic() { return {true, 0}; }
  static MultiresolutionChoice Levels(int levels) { return {false, levels}; }
};

// The settings of `choice` for a mesh of `num_vertices`: automatic as
// above; a number of levels with coarse levels down to 20 vertices.
MultiresolutionSettings ResolveMultiresolution(
    const MultiresolutionChoice& choice, int num_vertices);

// What each level did, coarsest first; the last entry is the input mesh.
struct MultiresolutionLevel {
  int vertices = 0;
  int faces = 0;
  int iterations = 0;         // LM iterations + Newton steps on this level
  double path_energy = 0;     // E_K of the level's solution
  double final_gradient = 0;  // max |grad E_K| at the end
  bool converged = false;
  double seconds = 0;         // prolongation onto this level + its solve
};

// The check of a prolongated path before the fine solve: it is used only if
// its E_K is below that of the fine level's own initial path
// (MakeGeodesicInitialPath) and no triangle of an inner shape turned over
// against that path's shape (normals with a negative dot product) or kept
// less than kCollapsingFaceAreaRatio of its start area. A coarse solution
// can be a worse start than the linear path: a thin part (a finger, a horn)
// that the decimation thinned out is prolongated through its neighbours.
struct ProlongationCheck {
  bool checked = false;        // a coarse level ran
  bool used = false;           // the fine solve started from the prolongation
  // The prolongation used is RotationGuidedPath's, not the deformation
  // transfer's (the one of lower E_K where both pass the check).
  bool rotation_guided = false;
  double prolongated_energy = 0;  // E_K (+inf: a degenerate element)
  double initial_energy = 0;      // E_K of the fine level's initial path
  // Triangles that turn over between consecutive shapes of the
  // prolongation and of the initial path (FindPathDegeneracy).
  int turned_faces = 0, initial_turned_faces = 0;
  FaceAreaRatio smallest_face_area;  // of the prolongated inner shapes
  std::string reason;          // one line: why it was used or rejected
};

// The ProlongationCheck of `prolongated` against `initial` (K + 1 shapes
// each, the same ends), whose path `init` made. Used unless an element of
// it is degenerate, more triangles turn over between its shapes than
// between the initial path's (the slivers of the start, FindSliverFaces,
// not counted), a triangle keeps less than
// kCollapsingFaceAreaRatio of its area and less than on the initial path,
// or its E_K is not below the initial path's.
ProlongationCheck CheckProlongation(const ShellSpace& space,
                                    const ShellPath& prolongated,
                                    const ShellPath& initial,
                                    const InitialPathReport& init);

struct MultiresolutionResult {
  GeodesicResult geodesic;  // the fine solution (as SolveGeodesic's)
  std::vector<MultiresolutionLevel> levels;
  ProlongationCheck prolongation;  // onto the fine level
};

// The geodesic of `input` on `space` through `settings.levels` coarse levels
// (fewer if a level would fall below min_vertices). Each level decimates the
// one above with DecimateShared over {start, end} (masked vertices locked,
// so the coarse mask is the mask itself), solves its geodesic (recursively),
// and prolongates each inner shape s_k by deformation transfer from the
// coarse end shape nearer in time (s_0 for k <= K/2, else s_K); masked
// vertices are then put back at their linear positions. The fine level is
// solved from that path if it passes ProlongationCheck, else from its own
// initial path (MakeGeodesicInitialPath of input.init), to the caller's
// tolerance relative to the gradient at that initial path
// (GeodesicInput::reference_gradient), so the result is a solution of the
// same problem as SolveGeodesic's. Throws InputError
// as SolveGeodesic does.
MultiresolutionResult SolveGeodesicMultiresolution(
    const ShellSpace& space, const GeodesicInput& input,
    const SolverSettings& settings, const MultiresolutionSettings& multires);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_MULTIRESOLUTION_H_
