// Lighting model of the renderer: two-sided Lambert shading with ambient.
#ifndef SHELLSPACE_RENDER_SHADING_H_
#define SHELLSPACE_RENDER_SHADING_H_

#include <string>

#include <Eigen/Core>

namespace shellspace {

// Flat: one intensity per triangle, from its face normal. Gouraud: intensities
// at the vertices, from area-weighted vertex normals, interpolated linearly
// across the triangle.
enum class Shading { kFlat, kGouraud };

// Parses "flat" or "gouraud" (case-insensitive); throws InputError otherwise.
Shading ParseShading(const std::string& text);

// "flat" or "gouraud".
std::string ShadingName(Shading shading);

// Colours (RGB in [0, 1]) and light of the renderer. Shells are open
// surfaces, so lighting is two-sided: a triangle whose normal points away from
// the viewer shows its back side, lit with the flipped normal and coloured
// with back_color. A surface point with unit normal n (flipped to face the
// viewer) gets the colour
//   color * (ambient + diffuse * max(0, n . light))
// where light is the unit direction towards the light.
struct Lighting {
  Eigen::Vector3d front_color{0.58, 0.72, 0.92};  // outer side (CCW faces)
  Eigen::Vector3d back_color{0.92, 0.74, 0.58};   // inner side
  Eigen::Vector3d background{0.97, 0.97, 0.97};
  double ambient = 0.22;
  double diffuse = 0.78;
  // Towards the light in camera coordinates (right, up, towards the viewer):
  // a light over the viewer's left shoulder. Normalized when used.
  Eigen::Vector3d light_in_camera{-0.35, 0.45, 1.0};
};

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_SHADING_H_
