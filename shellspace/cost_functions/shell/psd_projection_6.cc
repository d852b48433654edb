// The projections of psd_projection.h for stencils of 6 vertices and the
// reduced matrices of size 30, compiled once (one file per stencil size,
// compiled in parallel).
#include "shellspace/cost_functions/shell/psd_projection.h"

namespace shellspace {

SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(template, 6);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(template, 30);

}  // namespace shellspace
