// Axes around a picture of a field on a rectangle: a frame line, ticks with
// labels along the bottom (x) and the left (y) edge, the axis names and a
// legend of the picture's colours, in the bitmap font (bitmap_font.h).
#ifndef SHELLSPACE_RENDER_PLOT_AXES_H_
#define SHELLSPACE_RENDER_PLOT_AXES_H_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "shellspace/io/png_writer.h"

namespace shellspace {

// One line of a legend: a square swatch of `color` (with a dark outline, so
// a white swatch shows too) and its text.
struct LegendEntry {
  std::array<std::uint8_t, 3> color = {0, 0, 0};
  std::string text;
};

struct PlotAxes {
  // The values at the picture's left and right edges (x) and at its bottom
  // and top edges (y); min < max.
  double x_min = 0, x_max = 1;
  double y_min = 0, y_max = 1;
  std::string x_name = "x";  // centred under the x tick labels
  std::string y_name = "y";  // above the top-left corner of the frame
  std::vector<LegendEntry> legend;  // top to bottom, right of the picture
  int text_scale = 2;               // glyph scale, >= 1
};

// Where the picture went in the framed image: its top-left pixel.
struct PlotPlacement {
  int left = 0;
  int top = 0;
};

// Tick values for [lo, hi]: the multiples i * step inside it (to 1e-9 of a
// step), step = 1, 2 or 5 times a power of ten chosen so that there are
// about `target` of them (never fewer than two for lo < hi: the step is
// halved until there are); {lo} when hi <= lo.
std::vector<double> NiceTicks(double lo, double hi, int target = 5);

// The label of a tick value v of NiceTicks with step `step`: fixed point with
// as many decimals as the step needs (0.25 with step 0.05 gives "0.25", 2
// with step 1 gives "2"); %g form ("1e-05") for steps below 1e-4 or
// |v| >= 1e6.
std::string TickLabel(double value, double step);

// The picture on a white canvas with the axes of `axes`:
//  - a frame line of thickness t = max(1, text_scale / 2) around the picture
//    (just outside it);
//  - ticks 3 text_scale long, pointing outwards from the frame, at the
//    NiceTicks(x_min, x_max) below the picture and the
//    NiceTicks(y_min, y_max) left of it; the tick of value v sits on picture
//    column min(W - 1, floor((v - x_min) / (x_max - x_min) W + 1e-9)) and
//    on row min(H - 1, floor((y_max - v) / (y_max - y_min) H + 1e-9)) for a
//    W x H picture;
//  - each tick's TickLabel centred under it (x) or right-aligned left of it
//    (y); the axis names; the legend right of the frame, top-aligned with
//    the picture (entries 9 text_scale apart, swatches 7 text_scale square).
// The picture's pixels are copied unchanged; `placement` (if given) receives
// where. Deterministic.
RgbImage FramePlot(const RgbImage& picture, const PlotAxes& axes,
                   PlotPlacement* placement = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_PLOT_AXES_H_
