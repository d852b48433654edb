#include "shellspace/tools/path_summary.h"

#include "shellspace/io/atomic_file.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/shell_inputs.h"

namespace shellspace {

FlagSpec GltfFlag() {
  return TextFlag("gltf",
                  "also write the frames as one glTF 2.0 file (.glb): the "
                  "first frame the base mesh, the others morph targets, "
                  "animated at 4 frames per second");
}

void WritePathOutputs(const std::string& dir, const Faces& faces,
                      const ShellPath& path) {
  RenderOptions options;
  if (!FLAGS_png.empty()) ValidateRenderOptions(options);
  // Encoded before anything is written: a bad path writes no file.
  const std::string glb =
      FLAGS_gltf.empty() ? "" : EncodeGltfMorphAnimation(path, faces);
  WriteFrames(dir, faces, path);
  if (!FLAGS_png.empty()) WriteFilmStrip(path, faces, options, FLAGS_png);
  if (!FLAGS_gltf.empty()) WriteFileAtomically(FLAGS_gltf, glb);
}

}  // namespace shellspace
