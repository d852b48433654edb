// Pictures of the Kohn–Müller branching problem (spec branching.md): the
// slope u_y of a sharp self-similar construction and of a relaxed
// (diffuse-interface) field. x runs to the right (the austenite at x = 0 is
// the left edge), y upward; u_y = +1 orange, -1 blue.
#ifndef SHELLSPACE_RENDER_BRANCHING_IMAGE_H_
#define SHELLSPACE_RENDER_BRANCHING_IMAGE_H_

#include "shellspace/io/png_writer.h"
#include "shellspace/problems/branching/construction.h"
#include "shellspace/problems/branching/relaxed_grid.h"

namespace shellspace::branching {

// u_y of the construction over (0, L) x [0, height), width_px x height_px
// pixels; interfaces (pixels closer than 0.6 pixel to one) dark.
RgbImage RenderConstruction(const Construction& construction, double height,
                            int width_px, int height_px);

// u_y of a relaxed field over (0, L) x [0, H) in physical proportions of x
// (graded grids are resampled to the nearest node row), blended to white as
// |u_y| -> 0 so the diffuse interfaces show as light lines.
RgbImage RenderSlope(const RelaxedField& field, int width_px, int height_px);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_RENDER_BRANCHING_IMAGE_H_
