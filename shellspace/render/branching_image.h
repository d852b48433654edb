// Pictures of the branching problem (docs/math.md, "Branching: the Kohn–Müller
// model"): the slope u_y of a sharp self-similar construction and of a relaxed
// (diffuse-interface) field. x runs to the right (the austenite at x = 0 is the
// left edge), y upward; u_y = +1 orange, -1 blue. The *Figure functions frame
// these pictures with axes and a legend (plot_axes.h) for the files the CLI
// writes.
#ifndef SHELLSPACE_RENDER_BRANCHING_IMAGE_H_
#define SHELLSPACE_RENDER_BRANCHING_IMAGE_H_

#include "shellspace/io/png_writer.h"
#include "shellspace/render/plot_axes.h"
#include "shellspace/models/branching/construction.h"
#include "shellspace/models/branching/relaxed_grid.h"

namespace shellspace::branching {

// u_y of the construction over (0, L) x [0, height), width_px x height_px
// pixels; interfaces (pixels closer than 0.6 pixel to one) dark.
RgbImage RenderConstruction(const Construction& construction, double height,
                            int width_px, int height_px);

// u_y of a relaxed field over (0, L) x [0, H) in physical proportions of x
// (graded grids are resampled to the nearest node row), blended to white as
// |u_y| -> 0 so the diffuse interfaces show as light lines.
RgbImage RenderSlope(const RelaxedField& field, int width_px, int height_px);

// RenderConstruction framed by FramePlot: x from 0 to L along the bottom
// (named "x  (austenite at x = 0)"), y from 0 to `height` up the left side,
// and the legend u_y = +1 (orange), u_y = -1 (blue), interface (dark); text
// scale clamp(round(width_px / 450), 1, 3).
RgbImage ConstructionFigure(const Construction& construction, double height,
                            int width_px, int height_px);

// RenderSlope framed the same way over (0, L) x [0, H), with the legend
// u_y = +1, u_y = 0 (white: a diffuse interface), u_y = -1.
RgbImage SlopeFigure(const RelaxedField& field, int width_px, int height_px);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_RENDER_BRANCHING_IMAGE_H_
