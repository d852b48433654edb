// `shellspace view`: a sequence of shells (a path directory or a list of
// meshes) as one self-contained HTML page (render/html_viewer.h), with the
// numbers of the directory's summary.json when it has one.
#include <gflags/gflags.h>

#include <filesystem>
#include <iostream>
#include <string>

#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/input_file.h"
#include "shellspace/render/html_viewer.h"
#include "tools/run/common_flags.h"
#include "tools/run/run_paths.h"
#include "tools/verbs/verb.h"
#include "tools/run/stop_request.h"

DECLARE_string(input);

namespace shellspace {
namespace {

// A summary.json larger than this is not a run's summary.
constexpr std::int64_t kMaxSummaryBytes = std::int64_t{1} << 24;

FlagTable ViewFlags() {
  return Flags({{
      TextFlag("input",
               "a directory (all *.ply, *.obj, *.off in natural name order; "
               "its summary.json shown beside them) or a comma-separated "
               "list of mesh files")
          .Required(),
      TextFlag("output",
               "the HTML page (.html): one file that works offline")
          .Required(),
      TextFlag("quiet", "no line on stdout"),
  }});
}

// The text of DIR/summary.json if `input` is a directory holding one, else
// "". InputError if it is not a JSON object.
std::string SummaryOf(const std::string& input) {
  std::error_code error;
  const std::filesystem::path file =
      std::filesystem::path(input) / "summary.json";
  if (!std::filesystem::is_directory(input, error) ||
      !std::filesystem::exists(file, error)) {
    return "";
  }
  const std::string text =
      ReadInputFile(file.string(), "summary", kMaxSummaryBytes,
                    ReadStopToken());
  const size_t first = text.find_first_not_of(" \t\r\n");
  const size_t last = text.find_last_not_of(" \t\r\n");
  if (first == std::string::npos || text[first] != '{' || text[last] != '}') {
    throw InputError(file.string() + " is not a JSON object");
  }
  return text.substr(first, last - first + 1);
}

// Flags -> the frames and summary -> the page.
int RunView() {
  RunPaths()
      .InputFrames("input", FLAGS_input)
      .OutputHtml("output", FLAGS_output)
      .Check();
  const FrameSequence sequence =
      ReadFrameSequence(FLAGS_input, ReadStopToken());
  const std::string page = EncodeHtmlViewer(
      sequence.frames, sequence.faces, FLAGS_input, SummaryOf(FLAGS_input));
  WriteFileAtomically(FLAGS_output, page);
  if (!FLAGS_quiet) {
    std::cout << "wrote " << FLAGS_output << ": " << sequence.frames.size()
              << " frame(s) of " << sequence.frames[0].rows()
              << " vertices\n";
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "view", "view --input DIR|a.ply,b.ply --output page.html",
    shellspace::ViewFlags(), shellspace::RunView);
