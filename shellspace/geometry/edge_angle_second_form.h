// The mid-edge second fundamental form with rotated edge normals: the
// edge-angle variant of the shape-operator bending model (docs/math.md,
// "Bending energy: two models"; after Grinspun, Gingold, Reisman, Zorin 2006).
//
// One angle phi_e per interior edge e. In face T the normal of its edge i
// (opposite X_i) makes the angle
//   alpha_i = theta_i / 2 + s_{T,i} phi_e
// with the face normal N, theta_i the signed dihedral angle of the edge
// (theta_i / 2 = 1/2 atan2(N_i . t_i, N . N_i), t_i the unit in-plane vector
// from X_i's side towards the edge, perpendicular to it, N_i the normal of
// the face across), and s_{T,i} = +1 if T runs through e as the first face
// of its flap (i -> j, geometry/topology.h), -1 for the second face: the
// normal is turned about the edge, towards one face and away from the other.
// Then
//   c_i = 2 h_i sin(alpha_i)            (h_i the altitude on edge i),
//   H_T(phi) = [[c_0 + c_1, c_0], [c_0, c_0 + c_2]]   (basis E_1, E_2),
// c_i = 0 on a boundary edge. At phi = 0 this is the mid-edge form
// (mid_edge_second_form.h): 2 h_i sin(theta_i / 2) = (X_{i+1} + X_{i+2} -
// 2 X_i) . n_i. The angles enter through sin only, so H_T is smooth in phi;
// dc_i / dphi_e = 2 h_i s_{T,i} cos(alpha_i).
#ifndef SHELLSPACE_GEOMETRY_EDGE_ANGLE_SECOND_FORM_H_
#define SHELLSPACE_GEOMETRY_EDGE_ANGLE_SECOND_FORM_H_

#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// What H_T(phi) of one face needs of its shape: per edge slot i (edge
// opposite X_i, X = the face's vertices in the mesh's order).
struct EdgeAngleFace {
  double altitude[3] = {0, 0, 0};       // h_i = 2 a_T / l_i
  double half_dihedral[3] = {0, 0, 0};  // theta_i / 2 (0 on the boundary)
  int edge[3] = {-1, -1, -1};  // index into Topology::interior_edges, -1 boundary
  double sign[3] = {0, 0, 0};  // s_{T,i} (0 on the boundary)

  bool interior(int i) const { return edge[i] >= 0; }
  // c_i at the angles phi_i of the face's three edge slots (a boundary
  // slot's angle is ignored).
  double Coefficient(int i, double phi_i) const;
  // dc_i / dphi_i.
  double CoefficientDerivative(int i, double phi_i) const;
};

// The #F faces' data of `shape` (#V x 3, the mesh's connectivity). Throws
// InputError if a face is degenerate (zero area).
std::vector<EdgeAngleFace> EdgeAngleFaces(const Mesh& mesh,
                                          const Topology& topology,
                                          const Positions& shape);

// The second form (h11, h12, h22) of one face at its slots' angles phi[3].
struct SecondForm2 {
  double h11 = 0, h12 = 0, h22 = 0;
};
SecondForm2 EdgeAngleSecondForm(const EdgeAngleFace& face, const double* phi);

// The three slot angles of `face` from the per-edge angles (#interior edges;
// 0 on boundary slots).
void FaceEdgeAngles(const EdgeAngleFace& face, const std::vector<double>& angles,
                    double* phi);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_EDGE_ANGLE_SECOND_FORM_H_
