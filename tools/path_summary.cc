#include "shellspace/tools/path_summary.h"

#include "shellspace/io/atomic_file.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/png_writer.h"
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
  // One set: the frames, the film strip and the .glb appear together or
  // not at all (a .glb in a missing directory leaves no frames behind).
  // The single files first, so that a failure creates no directory.
  AtomicFileSet files;
  if (!FLAGS_gltf.empty()) {
    files.Add(FLAGS_gltf, EncodeGltfMorphAnimation(path, faces));
  }
  if (!FLAGS_png.empty()) {
    files.Add(FLAGS_png, EncodePng(RenderFilmStrip(path, faces, options)));
  }
  AddFrames(dir, faces, path, &files);
  files.Commit();
}

}  // namespace shellspace
