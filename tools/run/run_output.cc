#include "tools/run/run_output.h"

#include <unistd.h>

#include <chrono>
#include <ctime>

#include "tools/run/shell_inputs.h"
#include "tools/run/stop_request.h"

namespace shellspace {
namespace {

std::string& CommandLineStorage() {
  static std::string line;
  return line;
}

}  // namespace

void SetRunCommandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool quote = arg.find_first_of(" \t\"'") != std::string::npos;
    line += (i ? " " : "") + (quote ? "'" + arg + "'" : arg);
  }
  CommandLineStorage() = line;
}

const std::string& RunCommandLine() { return CommandLineStorage(); }

const std::string& RunId() {
  static const std::string id = [] {
    const std::time_t now = std::chrono::system_clock::to_time_t(
        std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof(text), "%Y%m%dT%H%M%SZ", &utc);
    return std::string(text) + "-" +
           std::to_string(static_cast<long>(::getpid()));
  }();
  return id;
}

JsonObject& AddRunFields(JsonObject& json) {
  const StopCause stop = ObservedStopCause();
  return json.Add("partial", stop != StopCause::kNone)
      .Add("stop_reason", StopCauseText(stop))
      .Add("run_id", RunId())
      .Add("command_line", RunCommandLine());
}

std::string RunDirectory::Commit(JsonObject summary) {
  AddRunFields(summary);
  const std::string text = summary.str();
  CommitSummary(text);
  return text;
}

void RunDirectory::CommitSummary(const std::string& text) {
  for (const auto& [path, make] : outside_of_summary_) {
    AddOutside(path, make(text));
  }
  for (const auto& [name, make] : inside_of_summary_) {
    WriteFileAtomically(File(name), make(text));
  }
  StagedRun::Commit(text);
}

}  // namespace shellspace
