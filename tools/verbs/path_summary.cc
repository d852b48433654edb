#include "tools/verbs/path_summary.h"

#include <algorithm>
#include <iostream>
#include <utility>

#include "shellspace/geometry/memory_limits.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_set_check.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/render/html_viewer.h"
#include "shellspace/workflows/geodesic.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "tools/run/shell_inputs.h"

namespace shellspace {

FlagSpec PngFlag(const std::string& what) {
  return TextFlag("png", "also write a PNG film strip of " + what +
                             " here (frames of 320 pixels, 6 a row)" +
                             FilmStripBoundText());
}

FlagSpec GltfFlag() {
  return TextFlag("gltf",
                  "also write the frames as one glTF 2.0 file (.glb): the "
                  "first frame the base mesh, the others morph targets, "
                  "animated at 4 frames per second");
}

FlagSpec HtmlFlag() {
  return TextFlag("html",
                  "also write the frames as one self-contained HTML page "
                  "(.html, works offline): WebGL view with a frame slider, "
                  "play, orbit, colour by distance from frame 0 and the "
                  "summary's numbers");
}

void AddViewerPage(RunDirectory* out, const Faces& faces,
                   const std::vector<Positions>& frames) {
  if (FLAGS_html.empty()) return;
  // Checked now, written at Commit.
  CheckFrameSet(frames, faces, "--html");
  out->AddOutsideOfSummary(
      FLAGS_html, [faces, frames](const std::string& summary) {
        return EncodeHtmlViewer(frames, faces, FLAGS_output, summary);
      });
}

void RecordWorkflow(const workflows::SolveStatus& solve,
                    const std::vector<std::string>& warnings,
                    const std::string& what, RunStatus* status) {
  for (const std::string& failure : solve.failures) {
    status->Require(false, failure);
  }
  for (const std::string& warning : warnings) {
    status->Warn(what + ": " + warning);
  }
}

int FailedSolveExit(const std::string& verb,
                    const workflows::SolveStatus& solve) {
  std::cerr << "shellspace " << verb << ": " << solve.message << "\n";
  return kExitNotConverged;
}

void CheckShoot(const ShootResult& result, RunStatus* status) {
  for (size_t i = 0; i < result.exp_steps.size(); ++i) {
    const ExpStepResult& step = result.exp_steps[i];
    status->Require(step.solved,
                    "EXP step " + std::to_string(i + 1) +
                        " not solved: relative residual " +
                        Short(step.relative_residual) + " > " +
                        Short(kExpStepAcceptance) + " (" +
                        ExpMethodName(step.method) + ")");
  }
}

void CheckPngMemory(int frames) {
  if (FLAGS_png.empty()) return;
  CheckFilmStripMemory(frames, FilmStripOptionsFromFlags(), "--png");
}

void WritePathOutputs(RunDirectory* out, const Faces& faces,
                      const ShellPath& path) {
  const RenderOptions options = FilmStripOptionsFromFlags();
  // Checked before the solve with the frames it was to write; a stopped
  // run writes fewer.
  CheckPngMemory(static_cast<int>(path.size()));
  // The film strip and the .glb are files outside the directory: they are
  // renamed into place with it at Commit (or not at all).
  if (!FLAGS_gltf.empty()) {
    out->AddOutside(FLAGS_gltf, EncodeGltfMorphAnimation(path, faces));
  }
  if (!FLAGS_png.empty()) {
    out->AddOutside(FLAGS_png,
                    EncodePng(RenderFilmStrip(path, faces, options)));
  }
  AddViewerPage(out, faces, path);
  WriteFrames(out->staging(), faces, path);
}

std::string CommitPathRun(RunDirectory* out, JsonObject summary,
                          const ShellSpace& space, const ShellPath& path,
                          double seconds) {
  summary.Add("energy_split", PathEnergySplitJson(space, path));
  return CommitPathRun(out, std::move(summary), seconds);
}

std::string CommitPathRun(RunDirectory* out, JsonObject summary,
                          double seconds) {
  summary.Add("bending_model", FLAGS_bending)
      .Add("seconds", seconds)
      .Add("output", FLAGS_output);
  const std::string text = out->Commit(std::move(summary));
  if (FLAGS_json) std::cout << text << "\n";
  return text;
}

}  // namespace shellspace
