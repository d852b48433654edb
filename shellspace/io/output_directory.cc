#include "shellspace/io/output_directory.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <system_error>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/atomic_file.h"

namespace shellspace {
namespace {

namespace fs = std::filesystem;

// "<parent>/.<name>.<kind>-<pid>-<start>-<n>" (ProcessTag).
std::string Sibling(const std::string& dir, const std::string& kind) {
  static std::atomic<unsigned long> counter{0};
  const fs::path path(dir);
  const fs::path parent = path.parent_path();
  const std::string name = "." + path.filename().string() + "." + kind + "-" +
                           ProcessTag() + "-" + std::to_string(counter++);
  return (parent.empty() ? fs::path(name) : parent / name).string();
}

// True if `text` is all decimal digits, 1 to max_length of them.
bool IsDigits(const std::string& text, std::size_t max_length) {
  if (text.empty() || text.size() > max_length) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// The owner of a temporary's tag "<pid>-<start>-<n>" (or "<pid>-<n>", the
// names before the start time was added: start 0, unknown); false if
// `tag` is not one (pid at most 18 digits, start at most 19).
bool ParseTag(const std::string& tag, long* pid, unsigned long long* start) {
  std::vector<std::string> parts(1);
  for (char c : tag) {
    if (c == '-') {
      parts.emplace_back();
    } else {
      parts.back() += c;
    }
  }
  const std::size_t unlimited = std::string::npos;
  if (parts.size() == 3 && IsDigits(parts[0], 18) && IsDigits(parts[1], 19) &&
      IsDigits(parts[2], unlimited)) {
    *pid = std::stol(parts[0]);
    *start = std::stoull(parts[1]);
    return true;
  }
  if (parts.size() == 2 && IsDigits(parts[0], 18) &&
      IsDigits(parts[1], unlimited)) {
    *pid = std::stol(parts[0]);
    *start = 0;
    return true;
  }
  return false;
}

// True if `name` matches `pattern`, where '#' stands for one or more decimal
// digits, '*' for zero or more, and every other character for itself.
bool MatchesNamePattern(const std::string& name, const char* pattern) {
  std::size_t i = 0;
  for (const char* p = pattern; *p != '\0'; ++p) {
    if (*p == '#' || *p == '*') {
      const std::size_t first = i;
      while (i < name.size() && name[i] >= '0' && name[i] <= '9') ++i;
      if (*p == '#' && i == first) return false;
    } else if (i < name.size() && name[i] == *p) {
      ++i;
    } else {
      return false;
    }
  }
  return i == name.size();
}

// The tag of `entry` if it is a temporary of `name` of one of `kinds`
// (".<name>.tmp-TAG", ...; "<name>.tmp-TAG" for kind "file"), else "".
std::string TagOf(const std::string& entry, const std::string& name,
                  std::initializer_list<const char*> kinds) {
  for (const char* kind : kinds) {
    const std::string prefix = std::string(kind) == "file"
                                   ? name + ".tmp-"
                                   : "." + name + "." + kind + "-";
    if (entry.size() > prefix.size() && entry.compare(0, prefix.size(), prefix) == 0) {
      return entry.substr(prefix.size());
    }
  }
  return "";
}

bool IsFrameName(const std::string& name) {
  return MatchesNamePattern(name, "shape_#.ply");
}

bool IsRunFileName(const std::string& name) {
  static const char* const kKnown[] = {
      "shape_#.ply", "summary.json", "pca.json", "mean.ply", "mode_#_minus.ply",
      "mode_#_plus.ply", "procrustes_mean.ply", "procrustes_mode_#_minus.ply",
      "procrustes_mode_#_plus.ply", "u.csv", "uy.png", "interfaces.csv",
      "pattern.png", "pattern.txt", "film_strip.png", "viewer.html",
      // The example sets (geometry/example_poses.h).
      "finger*.ply", "plate*.ply", "cylinder*.ply", "pose*.ply",
      "finger*_var.ply", "plate*_var.ply", "cylinder*_var.ply", "pose*_var.ply",
      "finger_mask.txt", "plate_mask.txt", "cylinder_mask.txt",
      "collection_mask.txt"};
  for (const char* pattern : kKnown) {
    if (MatchesNamePattern(name, pattern)) return true;
  }
  return IsTemporaryName(name);
}

void RemoveAll(const std::string& path) {
  std::error_code error;
  fs::remove_all(path, error);
}

}  // namespace

std::string NormalOutputPath(const std::string& path) {
  if (path.empty()) return path;
  std::error_code error;
  const fs::path absolute = fs::absolute(WithoutTrailingSlash(path), error);
  if (error) return WithoutTrailingSlash(path);
  const std::string name = absolute.filename().string();
  if (name.empty() || name == "." || name == "..") {
    // "DIR/.." or "/": the directory it names, resolved whole.
    const fs::path whole = fs::canonical(absolute, error);
    return (error ? absolute.lexically_normal() : whole).string();
  }
  const fs::path parent = fs::canonical(absolute.parent_path(), error);
  if (error) return absolute.lexically_normal().string();
  return (parent / name).string();
}

int RemoveLeftoversOfEndedRuns(const std::string& path, bool old_directories) {
  const fs::path target(NormalOutputPath(path));
  const std::string name = target.filename().string();
  if (name.empty()) return 0;
  int removed = 0;
  std::error_code error;
  for (fs::directory_iterator it(target.parent_path(), error), end;
       !error && it != end; it.increment(error)) {
    const std::string entry = it->path().filename().string();
    const std::string tag =
        old_directories ? TagOf(entry, name, {"tmp", "old", "file"})
                        : TagOf(entry, name, {"tmp", "file"});
    long pid = 0;
    unsigned long long start = 0;
    if (tag.empty() || !ParseTag(tag, &pid, &start) ||
        !ProcessEnded(pid, start)) {
      continue;
    }
    std::error_code gone;
    if (fs::remove_all(it->path(), gone) > 0 && !gone) ++removed;
  }
  return removed;
}

std::string WithoutTrailingSlash(const std::string& path) {
  std::string out = path;
  while (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

bool IsTemporaryName(const std::string& name) {
  if (!name.empty() && name[0] == '.' &&
      (name.find(".tmp-") != std::string::npos ||
       name.find(".old-") != std::string::npos)) {
    return true;
  }
  return name.find(".tmp-") != std::string::npos;
}

std::string ReplaceableDirectoryProblem(const std::string& dir) {
  std::error_code error;
  const fs::file_status status = fs::symlink_status(dir, error);
  if (error || !fs::exists(status)) return "";
  if (fs::is_symlink(status)) {
    return dir + " is a symbolic link (give the directory it points to)";
  }
  if (!fs::is_directory(status)) return dir + " is not a directory";
  for (fs::directory_iterator it(dir, error), end; !error && it != end;
       it.increment(error)) {
    const std::string name = it->path().filename().string();
    std::error_code type_error;
    if (it->is_directory(type_error) && name == "frames") {
      for (fs::directory_iterator f(it->path(), error), fend;
           !error && f != fend; f.increment(error)) {
        const std::string frame = f->path().filename().string();
        if (!IsFrameName(frame) && !IsTemporaryName(frame)) {
          return dir + " holds frames/" + frame +
                 ", which no run writes: not replacing it";
        }
      }
      continue;
    }
    if (it->is_directory(type_error) || !IsRunFileName(name)) {
      return dir + " holds " + name + ", which no run writes: not replacing it";
    }
  }
  if (error) {
    // Gone while listed: a concurrent run moved it aside (Commit, step 1),
    // so there is nothing left here to protect.
    std::error_code gone;
    const fs::file_status now = fs::symlink_status(dir, gone);
    if (!fs::exists(now) &&
        (!gone || gone == std::errc::no_such_file_or_directory)) {
      return "";
    }
    return "cannot list directory " + dir;
  }
  return "";
}

StagedDirectory::StagedDirectory(const std::string& dir)
    : target_(NormalOutputPath(dir)), shown_(WithoutTrailingSlash(dir)) {
  const std::string problem = ReplaceableDirectoryProblem(target_);
  if (!problem.empty()) throw InputError(Shown(problem));
  RemoveLeftoversOfEndedRuns(target_, false);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string candidate = Sibling(target_, "tmp");
    std::error_code error;
    if (fs::create_directory(candidate, error)) {
      staging_ = candidate;
      return;
    }
    if (error && error != std::errc::file_exists) break;
  }
  throw InputError("cannot create a directory beside " + shown_);
}

std::string StagedDirectory::Shown(const std::string& problem) const {
  // The problem names the normalised path; the user knows their spelling.
  if (problem.compare(0, target_.size(), target_) == 0) {
    return shown_ + problem.substr(target_.size());
  }
  return problem;
}

StagedDirectory::~StagedDirectory() {
  if (!committed_ && !staging_.empty()) RemoveAll(staging_);
}

std::string StagedDirectory::File(const std::string& name) const {
  return staging_ + "/" + name;
}

void StagedDirectory::Commit() {
  // 1. The previous output aside (none, or another run has just moved it).
  std::string aside;
  std::error_code error;
  if (fs::exists(fs::symlink_status(target_, error))) {
    const std::string problem = ReplaceableDirectoryProblem(target_);
    if (!problem.empty()) throw InputError(Shown(problem));
    aside = Sibling(target_, "old");
    if (std::rename(target_.c_str(), aside.c_str()) != 0) {
      if (errno != ENOENT) {
        throw InputError("cannot replace " + shown_ + ": " +
                         std::strerror(errno));
      }
      aside.clear();
    }
  }
  // 2. The new one in. rename() onto an existing non-empty directory fails:
  // another run committed between steps 1 and 2.
  if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
    const int code = errno;
    if (code == ENOTEMPTY || code == EEXIST) {
      if (!aside.empty()) RemoveAll(aside);  // its place is taken
      throw InputError("another run wrote " + shown_ +
                       " at the same time; it holds that run's output, this "
                       "run's was discarded");
    }
    // The previous output back in its place (never lost for a failure of
    // this run's rename); if that fails too, it stays whole under `aside`.
    if (!aside.empty()) std::rename(aside.c_str(), target_.c_str());
    throw InputError("cannot write " + shown_ + ": " + std::strerror(code));
  }
  committed_ = true;
  // 3. The old one removed, and the previous outputs left aside by runs
  // killed between steps 1 and 2 (this run's output replaces them).
  if (!aside.empty()) RemoveAll(aside);
  RemoveLeftoversOfEndedRuns(target_, true);
}

StagedRun::StagedRun(const std::string& dir) {
  if (!dir.empty()) staged_.emplace(dir);
}

void StagedRun::AddOutside(const std::string& path,
                           const std::string& content) {
  outside_.Add(NormalOutputPath(path), content);
}

void StagedRun::Commit(const std::string& summary) {
  if (staged_) {
    WriteFileAtomically(staged_->File("summary.json"), summary + "\n");
    staged_->Commit();
  }
  outside_.Commit();
}

}  // namespace shellspace
