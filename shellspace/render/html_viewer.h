// A sequence of shells as one self-contained HTML page: the frames drawn by
// WebGL (plain WebGL 1, the script inlined, nothing fetched: it works
// offline), a frame slider, play/pause, mouse orbit and zoom, each vertex
// coloured by its distance from frame 0, and the numbers of a run's summary
// beside it.
#ifndef SHELLSPACE_RENDER_HTML_VIEWER_H_
#define SHELLSPACE_RENDER_HTML_VIEWER_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The page of `frames` (each #V x 3, sharing `faces`, #F x 3), titled
// `title`. `summary_json` is "" or a JSON object (a run's summary.json):
// the page shows its path_energy (E_K), spline_energy, regression_energy,
// converged and material (mu, lambda, eta) when present, and keeps the whole
// object in a <script type="application/json" id="summary"> element.
// Positions are float32 and faces uint32, base64-encoded in the page. The
// page sets data-status="ready" and data-load-ms (the milliseconds from the
// start of its script to the first frame drawn) on <body> once it has
// drawn, or data-status="error" with the message shown; "#frame=K" in the
// address (K a number or "last") opens frame K. Throws InputError for no
// frames, frames of different vertex counts, a face index out of range or
// a non-finite coordinate.
std::string EncodeHtmlViewer(const std::vector<Positions>& frames,
                             const Faces& faces, const std::string& title,
                             const std::string& summary_json = "");

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_HTML_VIEWER_H_
