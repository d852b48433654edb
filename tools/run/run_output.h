// What a verb run writes: its identity (run id, command line), the fields
// every --json report and summary.json carry, and an output directory
// written whole (io/output_directory.h) with its summary.json.
#ifndef SHELLSPACE_TOOLS_RUN_RUN_OUTPUT_H_
#define SHELLSPACE_TOOLS_RUN_RUN_OUTPUT_H_

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "shellspace/io/atomic_file.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/io/output_directory.h"

namespace shellspace {

// Set once by main: the command line of this run.
void SetRunCommandLine(int argc, char** argv);
// "YYYYMMDDTHHMMSSZ-PID" (UTC start time and process id: unique per run on
// one machine); information only.
const std::string& RunId();
// The command line, arguments separated by spaces (quoted if they hold
// spaces).
const std::string& RunCommandLine();

// Adds run_id, command_line, partial (a time limit or a signal cut a solve
// short, tools/run/stop_request.h) and stop_reason ("" or e.g. "SIGTERM",
// "time limit 10 s") to `json`.
JsonObject& AddRunFields(JsonObject& json);

// An output directory of one run (io/output_directory.h StagedRun: the
// staging directory is created by the constructor, so construct it after
// the solves), committed with the run fields in its summary.json. Files
// that show the summary (an --html page) are made from its text at Commit:
// outside the directory by AddOutsideOfSummary, inside by AddFileOfSummary.
class RunDirectory : public StagedRun {
 public:
  using SummaryPage = std::function<std::string(const std::string& summary)>;
  explicit RunDirectory(const std::string& dir) : StagedRun(dir) {}
  // The file at `path` is make(the summary's text), made at Commit.
  void AddOutsideOfSummary(const std::string& path, SummaryPage make) {
    outside_of_summary_.emplace_back(path, std::move(make));
  }
  // The file `name` in the directory is make(the summary's text), made at
  // Commit.
  void AddFileOfSummary(const std::string& name, SummaryPage make) {
    inside_of_summary_.emplace_back(name, std::move(make));
  }
  // AddRunFields(summary), then CommitSummary. Returns the summary's text.
  std::string Commit(JsonObject summary);
  // `text` (a JSON object with the run fields) as summary.json, then the
  // moves.
  void CommitSummary(const std::string& text);

 private:
  std::vector<std::pair<std::string, SummaryPage>> outside_of_summary_;
  std::vector<std::pair<std::string, SummaryPage>> inside_of_summary_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_RUN_OUTPUT_H_
