// `shellspace export`: a sequence of shells (a path directory or a list of
// meshes) as one glTF 2.0 morph animation (.glb).
#include <gflags/gflags.h>

#include <iostream>
#include <string>

#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/json_writer.h"
#include "tools/run/common_flags.h"
#include "tools/run/run_paths.h"
#include "tools/verbs/verb.h"
#include "tools/run/stop_request.h"

DECLARE_string(input);
DEFINE_double(fps, 4.0, "export: frames per second");
DEFINE_string(interpolation, "linear", "export: linear or step");

namespace shellspace {
namespace {

FlagTable ExportFlags() {
  return Flags(
      {{
           TextFlag("input",
                    "a directory (all *.ply, *.obj, *.off in natural name "
                    "order) or a comma-separated list of mesh files")
               .Required(),
           TextFlag("output",
                    "the glTF 2.0 binary file (.glb): the first mesh the base, "
                    "the others morph targets, one animation key per frame")
               .Required(),
           RealFlag("fps", "frames per second of the animation", 0,
                    End::kOpen),
           TextFlag("interpolation",
                    "linear (frames blended between keys) or step"),
           TextFlag("quiet", "no line on stdout"),
       },
       JsonFlag()});
}

int RunExport() {
  GltfAnimationOptions options;
  options.frames_per_second = FLAGS_fps;
  options.interpolation =
      ParseGltfInterpolation(FLAGS_interpolation, "--interpolation");
  RunPaths()
      .InputFrames("input", FLAGS_input)
      .OutputGlb("output", FLAGS_output)
      .Check();
  const FrameSequence sequence =
      ReadFrameSequence(FLAGS_input, ReadStopToken());
  WriteGltfMorphAnimation(FLAGS_output, sequence.frames, sequence.faces,
                          options);
  if (FLAGS_json) {
    std::cout << JsonObject()
                     .Add("output", FLAGS_output)
                     .Add("frames", static_cast<int>(sequence.frames.size()))
                     .Add("morph_targets",
                          static_cast<int>(sequence.frames.size()) - 1)
                     .Add("vertices",
                          static_cast<int>(sequence.frames[0].rows()))
                     .Add("faces", static_cast<int>(sequence.faces.rows()))
                     .Add("fps", FLAGS_fps)
                     .Add("interpolation", FLAGS_interpolation)
                     .Add("inputs", sequence.paths)
                     .str()
              << "\n";
  } else if (!FLAGS_quiet) {
    std::cout << "wrote " << FLAGS_output << ": " << sequence.frames.size()
              << " frame(s) as a glTF morph animation\n";
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "export",
    "export --input DIR|a.ply,b.ply --output path.glb [--fps 4] "
    "[--interpolation linear|step]",
    shellspace::ExportFlags(), shellspace::RunExport);
