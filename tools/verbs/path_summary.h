// The frame output of the path verbs and their verdicts; their --json
// reports are built by reports/path_reports.h (shared with the Python
// module).
#ifndef SHELLSPACE_TOOLS_VERBS_PATH_SUMMARY_H_
#define SHELLSPACE_TOOLS_VERBS_PATH_SUMMARY_H_

#include <string>

#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/workflows/solve_status.h"
#include "tools/run/run_output.h"
#include "tools/run/run_status.h"
#include "tools/verbs/verb_flags.h"

namespace shellspace {

// The --png flag of the verbs that write frames: a film strip of `what`
// ("the frames") at the default size, with its memory bound.
FlagSpec PngFlag(const std::string& what = "the frames");
// The --gltf flag of the verbs that write frames.
FlagSpec GltfFlag();
// The --html flag of the verbs that write frames: the viewer page
// (render/html_viewer.h) of the frames with the run's summary.
FlagSpec HtmlFlag();

// With --html, adds the viewer page of `frames` and the run's summary to
// `out`'s outside files (written at Commit with the rest, or not at all).
void AddViewerPage(RunDirectory* out, const Faces& faces,
                   const std::vector<Positions>& frames);

// Records in `status` what a workflow's solves missed (its SolveStatus
// failures, each already naming its solve) and warns with each of
// `warnings`, prefixed "WHAT: ".
void RecordWorkflow(const workflows::SolveStatus& solve,
                    const std::vector<std::string>& warnings,
                    const std::string& what, RunStatus* status);

// The end of a run whose workflow could not solve (status kFailed): one
// line "shellspace VERB: MESSAGE" on stderr and kExitNotConverged, nothing
// written.
int FailedSolveExit(const std::string& verb,
                    const workflows::SolveStatus& solve);

// Records each unsolved EXP step of the shot in `status`.
void CheckShoot(const ShootResult& result, RunStatus* status);

// With --png, the film strip of `frames` frames (--up, --labels, --color)
// against the memory bound (render/film_strip.h
// CheckFilmStripMemory): called before the solve with the frames it will
// write, so that a strip too large fails in one line before any work.
void CheckPngMemory(int frames);

// Writes shape_000.ply ... into the run's output directory and adds, if
// --png is set, the film strip, if --gltf is set, the frames as one
// glTF 2.0 morph animation (io/gltf_writer.h) and, if --html is set, their
// viewer page (AddViewerPage) to its outside files
// (tools/run/run_output.h): all appear together at Commit or none.
void WritePathOutputs(RunDirectory* out, const Faces& faces,
                      const ShellPath& path);

// Ends the report `summary` of a path verb with the keys they all end with
// -- energy_split (PathEnergySplitJson of `path` in `space`), bending_model
// (--bending), seconds, output (--output) -- commits the run directory with
// it (RunDirectory::Commit) and, with --json, prints it on stdout. Returns
// the report's text.
std::string CommitPathRun(RunDirectory* out, JsonObject summary,
                          const ShellSpace& space, const ShellPath& path,
                          double seconds);
// The same for a summary that has its energy_split (a workflow's ToJson).
std::string CommitPathRun(RunDirectory* out, JsonObject summary,
                          double seconds);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERBS_PATH_SUMMARY_H_
