// How a film strip is drawn, from the command line: --up, --labels and
// --color, shared by `render` and every verb that writes a strip (--png of
// geodesic, shoot, transport, spline, regress, pca; demo's film_strip.png).
#ifndef SHELLSPACE_TOOLS_VERBS_FILM_STRIP_FLAGS_H_
#define SHELLSPACE_TOOLS_VERBS_FILM_STRIP_FLAGS_H_

#include "shellspace/render/film_strip.h"
#include "tools/verbs/verb_flags.h"

namespace shellspace {

// --up auto|x|y|z|-x|-y|-z (default auto), --labels (default true; turn
// off with --labels=false) and --color plain|displacement (default plain).
// A bad --up or --color fails in main, before the verb runs (one line,
// exit 1).
FlagTable FilmStripFlags();

// Default RenderOptions with --up, --labels and --color applied.
RenderOptions FilmStripOptionsFromFlags();

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERBS_FILM_STRIP_FLAGS_H_
