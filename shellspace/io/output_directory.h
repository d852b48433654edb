// An output directory written whole: every file of a run goes into a
// temporary sibling of the target (DIR is NormalOutputPath of the path
// given), unique to the run ("<parent>/.<name>.tmp-<pid>-<start>-<n>":
// hidden, and never named like a frame), which Commit() then moves into
// place:
//
//   1. if DIR exists, rename it aside to
//      "<parent>/.<name>.old-<pid>-<start>-<n>";
//   2. rename the staging directory to DIR;
//   3. remove the old directory (recursively).
//
// So a finished DIR holds exactly one run; a run that fails or is killed
// before step 2 leaves the previous DIR untouched (a kill between steps 1
// and 2 leaves DIR missing and the previous run whole under its .old name;
// a step 2 that fails otherwise renames it back); the staging directories
// of killed runs are removed by the next run into DIR
// (RemoveLeftoversOfEndedRuns);
// no step leaves a file under a frame's name in DIR. Two runs committing to
// one DIR at once never mix: each step is one rename, a directory is never
// renamed onto a non-empty one, so the last run to reach step 2 wins whole;
// a run whose step 2 finds DIR already re-created by the other run fails
// with an InputError (its own output discarded, the other run's kept).
//
// A DIR that exists must be replaceable (ReplaceableDirectoryProblem): the
// previous output of a run, not a directory of the user's own files.
#ifndef SHELLSPACE_IO_OUTPUT_DIRECTORY_H_
#define SHELLSPACE_IO_OUTPUT_DIRECTORY_H_

#include <optional>
#include <string>

#include "shellspace/io/atomic_file.h"

namespace shellspace {

class StagedDirectory {
 public:
  // Checks that `dir` is replaceable (throws InputError naming it, see
  // ReplaceableDirectoryProblem) and creates the staging sibling.
  explicit StagedDirectory(const std::string& dir);
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;
  // Removes the staging directory unless committed.
  ~StagedDirectory();

  // The staging directory (write the run's files here) and a file in it.
  const std::string& staging() const { return staging_; }
  std::string File(const std::string& name) const;
  // The target directory (NormalOutputPath).
  const std::string& target() const { return target_; }

  // Steps 1-3 above. Throws InputError if DIR cannot be renamed aside, or
  // another run re-created it in between (the staging directory is removed).
  void Commit();

 private:
  // `problem` with the normalised target replaced by the user's spelling.
  std::string Shown(const std::string& problem) const;

  std::string target_;  // NormalOutputPath(dir): what is renamed
  std::string shown_;   // dir as given (without trailing slashes)
  std::string staging_;
  bool committed_ = false;
};

// The outputs of one run, committed together: an output directory written
// whole (a StagedDirectory; none if `dir` is "") and files outside it (a
// film strip, a .glb: an AtomicFileSet at their NormalOutputPath). Commit
// writes the summary as summary.json into the directory, moves the
// directory into place, then renames the outside files into place.
// Destroyed without Commit, nothing is left behind. Every front end writes
// a run's directory through it (the CLI's verbs, the Python functions'
// output=DIR), so a directory holds exactly one run and its summary.json.
class StagedRun {
 public:
  explicit StagedRun(const std::string& dir);
  bool has_directory() const { return staged_.has_value(); }
  // A file in the staging directory, and the directory (has_directory()).
  std::string File(const std::string& name) const { return staged_->File(name); }
  const std::string& staging() const { return staged_->staging(); }
  void AddOutside(const std::string& path, const std::string& content);
  // `summary` (a JSON text) as summary.json (if a directory), then the
  // moves.
  void Commit(const std::string& summary);

 private:
  std::optional<StagedDirectory> staged_;
  AtomicFileSet outside_;
};

// Why `dir` may not be replaced by a run's output, or "" if it may: it
// does not exist (also when it vanishes while listed: a concurrent run
// moved it aside), or is an empty directory, or every entry is a name a run
// writes (shape_NNN.ply, summary.json, pca.json, mean.ply,
// mode_J_{minus,plus}.ply, procrustes_*.ply, u.csv, uy.png,
// interfaces.csv, pattern.png, pattern.txt, film_strip.png, and a frames/
// directory of shape_NNN.ply). Otherwise e.g. "DIR is not a directory" or
// "DIR holds notes.txt, which no run writes".
std::string ReplaceableDirectoryProblem(const std::string& dir);

// True for the names of the temporaries of this file and of atomic_file.h
// (".X.tmp-...", ".X.old-...", "X.tmp-..."): readers of a directory skip
// them.
bool IsTemporaryName(const std::string& name);

// `path` without trailing slashes ("out/" -> "out"; "/" stays).
std::string WithoutTrailingSlash(const std::string& path);

// The absolute path an output `path` is written at: its parent directory
// resolved (symbolic links, ".", ".."; std::filesystem::canonical) and its
// last name kept, not followed if it is a symbolic link; a last name "."
// or ".." (and "/") resolved whole; trailing slashes dropped. If the parent
// does not exist, the lexically normal absolute path. So "out/../out",
// "./out", "out/" and "LINK/out" (LINK -> the current directory) all name
// "$PWD/out", and a rename of "out" never makes the path unresolvable
// (the staging and the moves use it; "out/../out" used to lose "out").
std::string NormalOutputPath(const std::string& path);

// Removes what runs that have ended (ProcessEnded: killed) left beside the
// output `path`: staging directories ".<name>.tmp-TAG" and file
// temporaries "<name>.tmp-TAG" and, with `old_directories` (only once a
// new output is in place), previous outputs ".<name>.old-TAG" renamed aside
// by a run killed between steps 1 and 2. TAG is "<pid>-<start>-<n>"
// (ProcessTag) or "<pid>-<n>" (earlier names: the pid alone). A temporary
// of a process that runs (this one, a concurrent run) is never removed.
// Returns how many were removed.
int RemoveLeftoversOfEndedRuns(const std::string& path, bool old_directories);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_OUTPUT_DIRECTORY_H_
