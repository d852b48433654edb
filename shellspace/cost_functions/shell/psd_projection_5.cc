// The projections of psd_projection.h for stencils of 5 vertices and the
// reduced matrices of size 15 and 24, compiled once (one file per stencil
// size, compiled in parallel).
#include "shellspace/cost_functions/shell/psd_projection.h"

namespace shellspace {

SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(template, 5);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(template, 15);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(template, 24);

}  // namespace shellspace
