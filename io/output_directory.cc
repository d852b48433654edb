#include "shellspace/io/output_directory.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>
#include <system_error>

#include "shellspace/geometry/mesh.h"

namespace shellspace {
namespace {

namespace fs = std::filesystem;

// "<parent>/.<name>.<kind>-<pid>-<n>".
std::string Sibling(const std::string& dir, const std::string& kind) {
  static std::atomic<unsigned long> counter{0};
  const fs::path path(dir);
  const fs::path parent = path.parent_path();
  const std::string name = "." + path.filename().string() + "." + kind + "-" +
                           std::to_string(static_cast<long>(::getpid())) +
                           "-" + std::to_string(counter++);
  return (parent.empty() ? fs::path(name) : parent / name).string();
}

bool IsFrameName(const std::string& name) {
  static const std::regex frame(R"(shape_[0-9]+\.ply)");
  return std::regex_match(name, frame);
}

bool IsRunFileName(const std::string& name) {
  static const std::regex known(
      R"(shape_[0-9]+\.ply|summary\.json|pca\.json|mean\.ply|)"
      R"(mode_[0-9]+_(minus|plus)\.ply|procrustes_mean\.ply|)"
      R"(procrustes_mode_[0-9]+_(minus|plus)\.ply|u\.csv|uy\.png|)"
      R"(interfaces\.csv|pattern\.png|pattern\.txt|film_strip\.png)");
  return std::regex_match(name, known) || IsTemporaryName(name);
}

void RemoveAll(const std::string& path) {
  std::error_code error;
  fs::remove_all(path, error);
}

}  // namespace

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
    : target_(WithoutTrailingSlash(dir)) {
  const std::string problem = ReplaceableDirectoryProblem(target_);
  if (!problem.empty()) throw InputError(problem);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string candidate = Sibling(target_, "tmp");
    std::error_code error;
    if (fs::create_directory(candidate, error)) {
      staging_ = candidate;
      return;
    }
    if (error && error != std::errc::file_exists) break;
  }
  throw InputError("cannot create a directory beside " + target_);
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
    if (!problem.empty()) throw InputError(problem);
    aside = Sibling(target_, "old");
    if (std::rename(target_.c_str(), aside.c_str()) != 0) {
      if (errno != ENOENT) {
        throw InputError("cannot replace " + target_ + ": " +
                         std::strerror(errno));
      }
      aside.clear();
    }
  }
  // 2. The new one in. rename() onto an existing non-empty directory fails:
  // another run committed between steps 1 and 2.
  if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
    const int code = errno;
    if (!aside.empty()) RemoveAll(aside);  // its place is taken either way
    if (code == ENOTEMPTY || code == EEXIST) {
      throw InputError("another run wrote " + target_ +
                       " at the same time; it holds that run's output, this "
                       "run's was discarded");
    }
    throw InputError("cannot write " + target_ + ": " + std::strerror(code));
  }
  committed_ = true;
  // 3. The old one removed.
  if (!aside.empty()) RemoveAll(aside);
}

}  // namespace shellspace
