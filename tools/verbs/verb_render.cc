// `shellspace render`: a PNG film strip of a sequence of shells.
#include <gflags/gflags.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/render/view.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "tools/run/run_paths.h"
#include "tools/verbs/verb.h"
#include "tools/run/stop_request.h"

DEFINE_string(input, "", "render: the meshes");
DEFINE_string(view, "front", "render: the view direction");
DEFINE_string(shading, "gouraud", "render: flat or gouraud");

namespace shellspace {
namespace {

bool IsWholeOrZero(double value, double max) {
  return value == 0 ||
         (value >= 1 && value <= max && value == std::floor(value));
}

FlagTable RenderFlags() {
  return Flags(
      {{
           TextFlag("input",
                    "a directory (all *.ply, *.obj, *.off in natural name "
                    "order) or a comma-separated list of mesh files")
               .Required(),
           TextFlag("output", "the PNG film strip").Required(),
           CheckedFlag("width",
                       "width of the whole image in pixels (0: 320 per "
                       "column); with C columns (up to 6 frames per row) "
                       "each frame is floor(W / C) wide, the remainder "
                       "background at the sides",
                       "0 (the default) or a whole number in [1, 65536], "
                       "at most 8192 per column" +
                           FilmStripBoundText(),
                       [](double v) { return IsWholeOrZero(v, 65536); }),
           CheckedFlag("height",
                       "height of each frame's picture in pixels, not "
                       "counting its label (0: the frame's width)",
                       "0 (the default) or a whole number in [1, 8192]" +
                           FilmStripBoundText(),
                       [](double v) { return IsWholeOrZero(v, 8192); }),
           TextFlag("view",
                    "front (along -z, +y up, for --up y), back, side "
                    "(along -x), left, top (along -y), bottom, iso, or "
                    "AZIMUTH,ELEVATION in degrees (e.g. --view=30,20; "
                    "azimuth about the up axis from the front view, "
                    "elevation towards it); other --up values turn the "
                    "world first (--up z: front looks along +y, x right)")
               .Check([](const std::string& value) { ParseView(value); }),
           TextFlag("shading", "flat or gouraud")
               .Check([](const std::string& value) { ParseShading(value); }),
           TextFlag("quiet", "no line on stdout"),
       },
       FilmStripFlags(), JsonFlag()});
}

std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

int RunRender() {
  RenderOptions options = FilmStripOptionsFromFlags();
  options.width = static_cast<int>(FLAGS_width);
  options.height = static_cast<int>(FLAGS_height);
  options.view = ParseView(FLAGS_view);
  options.shading = ParseShading(FLAGS_shading);
  RunPaths()
      .InputFrames("input", FLAGS_input)
      .OutputPng("output", FLAGS_output)
      .Check();
  // The pixels' memory against the bound before any mesh is read.
  CheckFilmStripMemory(static_cast<int>(ListFrameFiles(FLAGS_input).size()),
                       options, "--width " + std::to_string(options.width) +
                                    " --height " +
                                    std::to_string(options.height));
  const FrameSequence sequence =
      ReadFrameSequence(FLAGS_input, ReadStopToken());
  const RgbImage image =
      RenderFilmStrip(sequence.frames, sequence.faces, options);
  WritePng(image, FLAGS_output);

  if (FLAGS_json) {
    const FilmStripLayout layout =
        LayoutFilmStrip(static_cast<int>(sequence.frames.size()), options);
    std::cout << "{\"output\": " << JsonString(FLAGS_output)
              << ", \"frames\": " << sequence.frames.size()
              << ", \"columns\": " << layout.columns
              << ", \"rows\": " << layout.rows
              << ", \"frame_width\": " << layout.frame_width
              << ", \"frame_height\": " << layout.frame_height
              << ", \"label_height\": " << layout.label_height
              << ", \"width\": " << image.width
              << ", \"height\": " << image.height
              << ", \"view\": {\"azimuth\": " << options.view.azimuth
              << ", \"elevation\": " << options.view.elevation << "}"
              << ", \"up\": "
              << JsonString(UpAxisName(
                     ResolveUpAxis(options.up, sequence.frames[0], &sequence.faces)))
              << ", \"color\": " << JsonString(SurfaceColorName(options.color))
              << ", \"labels\": " << (options.labels ? "true" : "false")
              << ", \"shading\": " << JsonString(ShadingName(options.shading))
              << ", \"inputs\": [";
    for (size_t k = 0; k < sequence.paths.size(); ++k) {
      std::cout << (k ? ", " : "") << JsonString(sequence.paths[k]);
    }
    std::cout << "]}\n";
  } else if (!FLAGS_quiet) {
    std::cout << "wrote " << FLAGS_output << ": " << sequence.frames.size()
              << " frame(s), " << image.width << "x" << image.height
              << " pixels\n";
  }
  return 0;
}

}  // namespace

SHELLSPACE_REGISTER_VERB(
    "render",
    "render --input DIR|a.ply,b.ply --output strip.png [--width W --height H "
    "--view V --up auto|x|y|z|-x|-y|-z --labels=false --color displacement]",
    RenderFlags(), RunRender);

}  // namespace shellspace
