// The failure line of an unconverged geodesic says where its gradient is
// largest and, when that vertex is on a triangle the solve crushed, names
// the triangle and how far it was crushed.
#include <gtest/gtest.h>

#include <string>

#include "shellspace/workflows/geodesic.h"

namespace shellspace {
namespace {

// Two faces; the gradient peaks at vertex 2 of shape 3; face 1 (vertices
// 1, 2, 3) kept 2e-4 of its start area in shape 2.
GeodesicResult PeakOnACrushedFace(Faces* faces) {
  faces->resize(2, 3);
  *faces << 0, 1, 2,  //
      1, 3, 2;
  GeodesicResult result;
  result.gradient_peak.value = 5e4;
  result.gradient_peak.shape = 3;
  result.gradient_peak.vertex = 2;
  result.smallest_face_area.ratio = 2e-4;
  result.smallest_face_area.shape = 2;
  result.smallest_face_area.face = 1;
  result.collapsing_faces = true;
  return result;
}

TEST(GradientPeakTextTest, APeakOnACrushedFaceNamesTheFace) {
  Faces faces;
  const GeodesicResult result = PeakOnACrushedFace(&faces);
  EXPECT_EQ(workflows::GradientPeakText(result, faces),
            ", largest at vertex 2 of shape 3, a vertex of face 1, which the "
            "solve crushed to 0.0002 of its start area while lowering E_K "
            "(a sliver or cap of the mesh: remesh it)");
}

TEST(GradientPeakTextTest, APeakAwayFromTheCrushedFaceNamesOnlyTheVertex) {
  Faces faces;
  GeodesicResult result = PeakOnACrushedFace(&faces);
  result.gradient_peak.vertex = 0;  // on face 0 only
  EXPECT_EQ(workflows::GradientPeakText(result, faces),
            ", largest at vertex 0 of shape 3");
}

TEST(GradientPeakTextTest, AFaceAboveTheCollapseRatioIsNotNamed) {
  Faces faces;
  GeodesicResult result = PeakOnACrushedFace(&faces);
  result.smallest_face_area.ratio = 0.2;
  result.collapsing_faces = false;
  EXPECT_EQ(workflows::GradientPeakText(result, faces),
            ", largest at vertex 2 of shape 3");
  // Without the faces no face is named.
  EXPECT_EQ(workflows::GradientPeakText(PeakOnACrushedFace(&faces), Faces()),
            ", largest at vertex 2 of shape 3");
}

TEST(GradientPeakTextTest, AnUnknownPeakSaysNothing) {
  EXPECT_EQ(workflows::GradientPeakText(GeodesicResult(), Faces()), "");
}

}  // namespace
}  // namespace shellspace
