// The projections of psd_projection.h for stencils of 4 vertices and the
// reduced matrices of size 12 and 18, compiled once (one file per stencil
// size, compiled in parallel).
#include "shellspace/cost_functions/shell/psd_projection.h"

namespace shellspace {

SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(template, 4);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(template, 12);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(template, 18);

}  // namespace shellspace
