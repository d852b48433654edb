// Viewing directions of the renderer: named views and azimuth/elevation.
#ifndef SHELLSPACE_RENDER_VIEW_H_
#define SHELLSPACE_RENDER_VIEW_H_

#include <string>

namespace shellspace {

// A viewing direction given by two angles in degrees. The camera sits on the
// unit direction
//   c = (cos(elevation) sin(azimuth), sin(elevation), cos(elevation) cos(azimuth))
// as seen from the object and looks along -c. Azimuth 0, elevation 0 is the
// front view (camera on +z looking along -z, +x right, +y up); azimuth 90 puts
// the camera on +x, elevation 90 puts it on +y (looking down). These are the
// directions for the up axis +y; another up axis (up_axis.h) turns the world
// first, so that the azimuth turns about that axis (camera.h ViewFrame).
struct ViewAngles {
  double azimuth = 0;    // degrees, any finite value, about the +y axis
  double elevation = 0;  // degrees, in [-90, 90]
};

// Parses a --view value: one of the names
//   front  (0, 0)    look along -z, +y up, +x right
//   back   (180, 0)  look along +z
//   side   (90, 0)   look along -x, +y up, -z right (alias: right)
//   left   (-90, 0)  look along +x
//   top    (0, 90)   look along -y, +x right, -z up
//   bottom (0, -90)  look along +y
//   iso    (45, 35.26)  along -(1, 1, 1)
// or "AZIMUTH,ELEVATION" in degrees (e.g. "30,20"). Names are
// case-insensitive. Throws InputError with a one-line message for anything
// else, or for a non-finite angle or an elevation outside [-90, 90].
ViewAngles ParseView(const std::string& text);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_VIEW_H_
