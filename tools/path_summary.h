// The frame output of the path verbs; their --json reports are built by
// reports/path_reports.h (shared with the Python module).
#ifndef SHELLSPACE_TOOLS_PATH_SUMMARY_H_
#define SHELLSPACE_TOOLS_PATH_SUMMARY_H_

#include <string>

#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/tools/verb_flags.h"

namespace shellspace {

// The --gltf flag of the verbs that write frames.
FlagSpec GltfFlag();

// Writes DIR/shape_000.ply ..., if --png is set a film strip, and if --gltf
// is set the frames as one glTF 2.0 morph animation (io/gltf_writer.h), all
// together or none.
void WritePathOutputs(const std::string& dir, const Faces& faces,
                      const ShellPath& path);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_PATH_SUMMARY_H_
