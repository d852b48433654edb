#include "shellspace/render/plot_axes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shellspace/render/bitmap_font.h"

namespace shellspace {
namespace {

constexpr std::array<std::uint8_t, 3> kInk = {40, 40, 40};

void FillRect(int left, int top, int width, int height,
              const std::array<std::uint8_t, 3>& color, RgbImage* image) {
  for (int y = std::max(0, top); y < std::min(image->height, top + height);
       ++y) {
    for (int x = std::max(0, left); x < std::min(image->width, left + width);
         ++x) {
      std::uint8_t* pixel = image->at(x, y);
      for (int c = 0; c < 3; ++c) pixel[c] = color[c];
    }
  }
}

// The step of NiceTicks before halving.
double NiceStep(double range, int target) {
  const double raw = range / std::max(1, target);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double normalized = raw / magnitude;
  const double factor = normalized < 1.5 ? 1 : normalized < 3 ? 2
                        : normalized < 7 ? 5 : 10;
  return factor * magnitude;
}

std::vector<double> TicksWithStep(double lo, double hi, double step) {
  std::vector<double> ticks;
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  for (double i = first; i <= last; ++i) ticks.push_back(i == 0 ? 0.0 : i * step);
  return ticks;
}

double TickStep(const std::vector<double>& ticks, double lo, double hi) {
  return ticks.size() >= 2 ? ticks[1] - ticks[0] : std::max(hi - lo, 1e-300);
}

// The ticks of one axis and their labels.
struct AxisTicks {
  std::vector<double> ticks;
  std::vector<std::string> labels;
};

// NiceTicks of [lo, hi], labelled by TickLabel with their step.
AxisTicks TicksOf(double lo, double hi) {
  AxisTicks axis;
  axis.ticks = NiceTicks(lo, hi);
  const double step = TickStep(axis.ticks, lo, hi);
  for (double v : axis.ticks) axis.labels.push_back(TickLabel(v, step));
  return axis;
}

// The sizes of a framed plot in pixels: the text scale s, the frame's line
// width, the tick length, the text height and the padding; the picture
// (w x h) at (left, top) of the framed image (width x height).
struct PlotLayout {
  int s = 1;
  int line = 1;
  int tick = 0;
  int text_height = 0;
  int pad = 0;
  int w = 0;
  int h = 0;
  int left = 0;
  int top = 0;
  int width = 0;
  int height = 0;
};

// The layout of `picture` framed with `axes`: room for the y labels and
// the title on the left and top, the x labels and name below, the legend
// on the right.
PlotLayout LayOutPlot(const RgbImage& picture, const PlotAxes& axes,
                      const AxisTicks& x_axis, const AxisTicks& y_axis) {
  const int s = std::max(1, axes.text_scale);
  const int line = std::max(1, s / 2);
  const int tick = 3 * s;
  const int text_height = TextHeight(s);
  const int pad = 4 * s;
  const int w = picture.width;
  const int h = picture.height;

  const std::vector<std::string>& x_labels = x_axis.labels;
  int y_label_width = 0;
  for (const std::string& label : y_axis.labels) {
    y_label_width = std::max(y_label_width, TextWidth(label, s));
  }
  int legend_width = 0;
  for (const LegendEntry& entry : axes.legend) {
    legend_width = std::max(legend_width, 9 * s + TextWidth(entry.text, s));
  }
  const int legend_height = static_cast<int>(axes.legend.size()) * 9 * s;

  // Half a tick label may stick out on either side of the x axis.
  const int x_overhang =
      x_labels.empty() ? 0
                       : std::max(TextWidth(x_labels.front(), s),
                                  TextWidth(x_labels.back(), s)) / 2;
  const int left = std::max(pad + y_label_width + s + tick + line,
                            pad + x_overhang);
  const int top = pad + text_height + 3 * s + line;
  const int right_margin =
      line + std::max(x_overhang, legend_width > 0 ? 4 * s + legend_width : 0) +
      pad;
  const int bottom_margin =
      line + tick + s + text_height + s + text_height + pad;
  const int width = left + w + right_margin;
  const int height = std::max(top + h + bottom_margin,
                              top + legend_height + pad);
  return PlotLayout{s, line, tick, text_height, pad,   w,
                    h, left, top,  width,       height};
}

// The frame's lines around the picture.
void DrawFrame(const PlotLayout& layout, RgbImage* image) {
  const int line = layout.line;
  const int left = layout.left;
  const int top = layout.top;
  const int w = layout.w;
  const int h = layout.h;
  FillRect(left - line, top - line, w + 2 * line, line, kInk, image);
  FillRect(left - line, top + h, w + 2 * line, line, kInk, image);
  FillRect(left - line, top, line, h, kInk, image);
  FillRect(left + w, top, line, h, kInk, image);
}

// The x ticks and labels below the frame, and the x axis' name under them.
void DrawXAxis(const PlotLayout& layout, const PlotAxes& axes,
               const AxisTicks& x_axis, RgbImage* image) {
  const int s = layout.s;
  const int line = layout.line;
  const int tick = layout.tick;
  const int left = layout.left;
  const int top = layout.top;
  const int w = layout.w;
  const int h = layout.h;
  const std::vector<double>& x_ticks = x_axis.ticks;
  const std::vector<std::string>& x_labels = x_axis.labels;
  const double x_range = axes.x_max - axes.x_min;
  for (size_t k = 0; k < x_ticks.size(); ++k) {
    const double f = x_range > 0 ? (x_ticks[k] - axes.x_min) / x_range : 0;
    const int column =
        left + std::clamp(static_cast<int>(std::floor(f * w + 1e-9)), 0, w - 1);
    FillRect(column, top + h + line, 1, tick, kInk, image);
    DrawText(x_labels[k], column - TextWidth(x_labels[k], s) / 2,
             top + h + line + tick + s, s, kInk, image);
  }
  DrawText(axes.x_name, left + (w - TextWidth(axes.x_name, s)) / 2,
           top + h + line + tick + s + layout.text_height + s, s, kInk, image);
}

// The y ticks and labels left of the frame, and the y axis' name above
// them.
void DrawYAxis(const PlotLayout& layout, const PlotAxes& axes,
               const AxisTicks& y_axis, RgbImage* image) {
  const int s = layout.s;
  const int line = layout.line;
  const int tick = layout.tick;
  const int left = layout.left;
  const int top = layout.top;
  const int h = layout.h;
  const std::vector<double>& y_ticks = y_axis.ticks;
  const std::vector<std::string>& y_labels = y_axis.labels;
  const double y_range = axes.y_max - axes.y_min;
  for (size_t k = 0; k < y_ticks.size(); ++k) {
    const double f = y_range > 0 ? (axes.y_max - y_ticks[k]) / y_range : 0;
    const int row =
        top + std::clamp(static_cast<int>(std::floor(f * h + 1e-9)), 0, h - 1);
    FillRect(left - line - tick, row, tick, 1, kInk, image);
    // Digits sit on rows 0..6 of the cell: centre those on the tick.
    DrawText(y_labels[k],
             left - line - tick - s - TextWidth(y_labels[k], s),
             row - (kGlyphHeight - 1) * s / 2, s, kInk, image);
  }
  DrawText(axes.y_name, left - line, layout.pad, s, kInk, image);
}

// The legend right of the frame: a swatch of each entry's colour and its
// text.
void DrawLegend(const PlotLayout& layout, const PlotAxes& axes,
                RgbImage* image) {
  const int s = layout.s;
  const int legend_left = layout.left + layout.w + layout.line + 4 * s;
  for (size_t k = 0; k < axes.legend.size(); ++k) {
    const int y = layout.top + static_cast<int>(k) * 9 * s;
    FillRect(legend_left, y, 7 * s, 7 * s, kInk, image);
    FillRect(legend_left + 1, y + 1, 7 * s - 2, 7 * s - 2,
             axes.legend[k].color, image);
    DrawText(axes.legend[k].text, legend_left + 9 * s, y, s, kInk, image);
  }
}

}  // namespace

std::vector<double> NiceTicks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(hi - lo)) return {lo};
  double step = NiceStep(hi - lo, target);
  std::vector<double> ticks = TicksWithStep(lo, hi, step);
  for (int k = 0; ticks.size() < 2 && k < 8; ++k) {
    step /= 2;
    ticks = TicksWithStep(lo, hi, step);
  }
  return ticks;
}

std::string TickLabel(double value, double step) {
  char text[40];
  if (step < 1e-4 || std::fabs(value) >= 1e6) {
    std::snprintf(text, sizeof(text), "%g", value);
  } else {
    const int decimals =
        std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
    // A halved step (0.25, 0.125, ...) needs its own digits too.
    int digits = decimals;
    while (digits < 12 &&
           std::fabs(std::round(step * std::pow(10.0, digits)) -
                     step * std::pow(10.0, digits)) > 1e-6) {
      ++digits;
    }
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
  }
  return text;
}

RgbImage FramePlot(const RgbImage& picture, const PlotAxes& axes,
                   PlotPlacement* placement) {
  const AxisTicks x_axis = TicksOf(axes.x_min, axes.x_max);
  const AxisTicks y_axis = TicksOf(axes.y_min, axes.y_max);
  const PlotLayout layout = LayOutPlot(picture, axes, x_axis, y_axis);
  const int w = layout.w;
  const int h = layout.h;

  RgbImage image(layout.width, layout.height, 255);
  for (int y = 0; y < h; ++y) {
    std::copy(picture.at(0, y), picture.at(0, y) + 3 * w,
              image.at(layout.left, y + layout.top));
  }
  DrawFrame(layout, &image);
  DrawXAxis(layout, axes, x_axis, &image);
  DrawYAxis(layout, axes, y_axis, &image);
  DrawLegend(layout, axes, &image);
  if (placement) {
    placement->left = layout.left;
    placement->top = layout.top;
  }
  return image;
}

}  // namespace shellspace
