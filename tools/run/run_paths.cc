#include "tools/run/run_paths.h"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/output_directory.h"

namespace shellspace {
namespace {

namespace fs = std::filesystem;

// The absolute path with symbolic links and ".." resolved as far as it
// exists.
fs::path Canonical(const std::string& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(WithoutTrailingSlash(path), error);
  if (error) return fs::path(path).lexically_normal();
  fs::path canonical = fs::weakly_canonical(absolute, error);
  if (error) return absolute.lexically_normal();
  return canonical;
}

bool Exists(const std::string& path) {
  std::error_code error;
  return fs::exists(path, error);
}

// The same file: the same resolved path, or (both existing) the same inode.
bool Same(const std::string& a, const std::string& b) {
  if (Canonical(a) == Canonical(b)) return true;
  std::error_code error;
  return Exists(a) && Exists(b) && fs::equivalent(a, b, error) && !error;
}

// `child` lies strictly inside directory `dir`.
bool Inside(const std::string& child, const std::string& dir) {
  const fs::path c = Canonical(child), d = Canonical(dir);
  auto ci = c.begin();
  for (auto di = d.begin(); di != d.end(); ++di, ++ci) {
    if (di->empty()) continue;  // a trailing separator
    if (ci == c.end() || *ci != *di) return false;
  }
  return ci != c.end();
}

std::string Flag(const std::string& name) { return "--" + name; }

// The parent directory of `path` (as written: NormalOutputPath) exists and
// can be written.
void CheckParentWritable(const std::string& flag, const std::string& path) {
  const fs::path parent = fs::path(NormalOutputPath(path)).parent_path();
  std::error_code error;
  if (!fs::exists(parent, error)) {
    throw InputError(Flag(flag) + " " + path + ": directory " +
                     parent.string() + " does not exist");
  }
  if (!fs::is_directory(parent, error)) {
    throw InputError(Flag(flag) + " " + path + ": " + parent.string() +
                     " is not a directory");
  }
  struct statvfs volume;
  if (::access(parent.c_str(), W_OK | X_OK) != 0 ||
      (::statvfs(parent.c_str(), &volume) == 0 &&
       (volume.f_flag & ST_RDONLY))) {
    throw InputError(Flag(flag) + " " + path + ": directory " +
                     parent.string() + " is not writable");
  }
}

}  // namespace

RunPaths& RunPaths::Add(std::vector<Entry>* entries, const std::string& flag,
                        const std::string& path) {
  if (!path.empty()) entries->push_back({flag, path});
  return *this;
}

RunPaths& RunPaths::InputFile(const std::string& flag,
                              const std::string& path) {
  return Add(&input_files_, flag, path);
}

RunPaths& RunPaths::InputList(const std::string& flag,
                              const std::string& list) {
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ',')) InputFile(flag, item);
  return *this;
}

RunPaths& RunPaths::InputFrames(const std::string& flag,
                                const std::string& input) {
  if (input.empty()) return *this;
  std::error_code error;
  if (input.find(',') == std::string::npos && fs::is_directory(input, error)) {
    input_dirs_.push_back({flag, input});
    try {
      for (const std::string& file : ListFrameFiles(input)) {
        InputFile(flag, file);
      }
    } catch (const InputError&) {
      // An empty or unreadable directory: the verb's reader says so.
    }
    return *this;
  }
  return InputList(flag, input);
}

RunPaths& RunPaths::OutputFile(const std::string& flag,
                               const std::string& path) {
  return Add(&output_files_, flag, path);
}

RunPaths& RunPaths::OutputDirectory(const std::string& flag,
                                    const std::string& path) {
  return Add(&output_dirs_, flag, path);
}

void RunPaths::Check() const {
  for (size_t i = 0; i < output_files_.size(); ++i) {
    const Entry& out = output_files_[i];
    for (const Entry& in : input_files_) {
      if (Same(out.path, in.path)) {
        throw InputError(Flag(out.flag) + " " + out.path +
                         " is also the input " + Flag(in.flag) +
                         ": not overwriting it");
      }
    }
    for (const Entry& in : input_dirs_) {
      if (Same(out.path, in.path)) {
        throw InputError(Flag(out.flag) + " " + out.path +
                         " is the input directory " + Flag(in.flag));
      }
    }
    for (const Entry& dir : output_dirs_) {
      if (Same(out.path, dir.path) || Inside(out.path, dir.path)) {
        throw InputError(Flag(out.flag) + " " + out.path + " is inside " +
                         Flag(dir.flag) + " " + dir.path +
                         ", which is replaced as a whole: write it elsewhere");
      }
    }
    for (size_t j = 0; j < i; ++j) {
      if (Same(out.path, output_files_[j].path)) {
        throw InputError(Flag(out.flag) + " and " +
                         Flag(output_files_[j].flag) + " are the same file " +
                         out.path);
      }
    }
    std::error_code error;
    if (fs::is_directory(out.path, error)) {
      throw InputError(Flag(out.flag) + " " + out.path + " is a directory");
    }
    CheckParentWritable(out.flag, out.path);
    if (Exists(out.path) && ::access(out.path.c_str(), W_OK) != 0) {
      throw InputError(Flag(out.flag) + " " + out.path + " is not writable");
    }
  }
  for (size_t i = 0; i < output_dirs_.size(); ++i) {
    const Entry& out = output_dirs_[i];
    for (const Entry& in : input_files_) {
      if (Same(out.path, in.path) || Inside(in.path, out.path)) {
        throw InputError(Flag(out.flag) + " " + out.path +
                         " holds the input " + Flag(in.flag) + " " + in.path +
                         " (the directory is replaced as a whole)");
      }
    }
    for (const Entry& in : input_dirs_) {
      if (Same(out.path, in.path)) {
        throw InputError(Flag(out.flag) + " " + out.path +
                         " is the input directory " + Flag(in.flag));
      }
      if (Inside(in.path, out.path)) {
        throw InputError(Flag(out.flag) + " " + out.path +
                         " holds the input directory " + Flag(in.flag) + " " +
                         in.path);
      }
    }
    for (size_t j = 0; j < i; ++j) {
      const Entry& other = output_dirs_[j];
      if (Same(out.path, other.path) || Inside(out.path, other.path) ||
          Inside(other.path, out.path)) {
        throw InputError(Flag(out.flag) + " " + out.path + " and " +
                         Flag(other.flag) + " " + other.path + " overlap");
      }
    }
    const std::string problem = ReplaceableDirectoryProblem(
        WithoutTrailingSlash(out.path));
    if (!problem.empty()) throw InputError(Flag(out.flag) + ": " + problem);
    CheckParentWritable(out.flag, out.path);
    if (Exists(out.path) &&
        ::access(out.path.c_str(), W_OK | X_OK) != 0) {
      throw InputError(Flag(out.flag) + " " + out.path + " is not writable");
    }
  }
  // Every output can be written: what killed runs left beside it goes
  // before the solves (a staging directory can be large).
  for (const std::vector<Entry>* outputs : {&output_files_, &output_dirs_}) {
    for (const Entry& out : *outputs) RemoveLeftoversOfEndedRuns(out.path, false);
  }
}

}  // namespace shellspace
