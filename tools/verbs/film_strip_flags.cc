#include "tools/verbs/film_strip_flags.h"

#include <gflags/gflags.h>

#include "shellspace/render/up_axis.h"

DEFINE_string(up, "auto", "see `shellspace VERB --help`");
DEFINE_bool(labels, true, "see `shellspace VERB --help`");
DEFINE_string(color, "plain", "see `shellspace VERB --help`");

namespace shellspace {

FlagTable FilmStripFlags() {
  return {
      TextFlag("up",
               "film strip: the world axis shown upright, x, y, z, -x, -y "
               "or -z, or auto (the coordinate axis nearest the first "
               "frame's longest principal axis, its + end up; no clear long "
               "axis: y); the view then turns about it")
          .Check([](const std::string& value) { ParseUpAxis(value); }),
      TextFlag("labels",
               "film strip: the frame index k and time t = k / (n - 1) "
               "under each frame (--labels=false: none)"),
      TextFlag("color",
               "film strip: plain (outer side blue, inner side orange) or "
               "displacement (each vertex by its distance from frame 0, "
               "violet 0 to yellow the largest, with a colour bar)")
          .Check([](const std::string& value) { ParseSurfaceColor(value); }),
  };
}

RenderOptions FilmStripOptionsFromFlags() {
  RenderOptions options;
  options.up = ParseUpAxis(FLAGS_up);
  options.labels = FLAGS_labels;
  options.color = ParseSurfaceColor(FLAGS_color);
  return options;
}

}  // namespace shellspace
