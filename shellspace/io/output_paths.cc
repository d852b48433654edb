#include "shellspace/io/output_paths.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cctype>
#include <climits>
#include <filesystem>
#include <system_error>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/gltf_writer.h"
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

bool Equivalent(const fs::path& a, const fs::path& b) {
  std::error_code error;
  return fs::exists(a, error) && fs::exists(b, error) &&
         fs::equivalent(a, b, error) && !error;
}

// The same file: the same resolved path, or (both existing) the same device
// and inode (a hard link, a symbolic link, a case-folded spelling).
bool Same(const std::string& a, const std::string& b) {
  return Canonical(a) == Canonical(b) || Equivalent(a, b);
}

// Two names of files not yet written that a case-folding file system takes
// for one: the same parent directory, names equal but for ASCII case.
bool FoldedTogether(const std::string& a, const std::string& b) {
  const fs::path pa(NormalOutputPath(a)), pb(NormalOutputPath(b));
  const std::string na = pa.filename().string(), nb = pb.filename().string();
  if (na == nb || AsciiLowercase(na) != AsciiLowercase(nb)) return false;
  if (!(pa.parent_path() == pb.parent_path() ||
        Equivalent(pa.parent_path(), pb.parent_path()))) {
    return false;
  }
  return FoldsCase(pa.parent_path().string());
}

// `child` lies strictly inside directory `dir`: by the resolved paths, or
// (`dir` existing) one of `child`'s existing ancestors is `dir`'s inode.
bool Inside(const std::string& child, const std::string& dir) {
  const fs::path c = Canonical(child), d = Canonical(dir);
  auto ci = c.begin();
  bool prefix = true;
  for (auto di = d.begin(); di != d.end(); ++di, ++ci) {
    if (di->empty()) continue;  // a trailing separator
    if (ci == c.end() || *ci != *di) {
      prefix = false;
      break;
    }
  }
  if (prefix && ci != c.end()) return true;
  if (!Exists(dir)) return false;
  for (fs::path up = c.parent_path(); !up.empty() && up != up.root_path();
       up = up.parent_path()) {
    if (Equivalent(up, d)) return true;
  }
  return false;
}

// The parent directory of `path` (as written: NormalOutputPath) exists and
// can be written.
void CheckParentWritable(const std::string& name, const std::string& path) {
  const fs::path parent = fs::path(NormalOutputPath(path)).parent_path();
  std::error_code error;
  if (!fs::exists(parent, error)) {
    throw InputError(name + " " + path + ": directory " + parent.string() +
                     " does not exist");
  }
  if (!fs::is_directory(parent, error)) {
    throw InputError(name + " " + path + ": " + parent.string() +
                     " is not a directory");
  }
  struct statvfs volume;
  if (::access(parent.c_str(), W_OK | X_OK) != 0 ||
      (::statvfs(parent.c_str(), &volume) == 0 &&
       (volume.f_flag & ST_RDONLY))) {
    throw InputError(name + " " + path + ": directory " + parent.string() +
                     " is not writable");
  }
}

void CheckLength(const std::string& name, const std::string& path) {
  const std::string problem = OutputNameLengthProblem(name, path);
  if (!problem.empty()) throw InputError(problem);
}

}  // namespace

bool FoldsCase(const std::string& dir) {
  const std::string lower = "/.shellspace-case-probe-" + ProcessTag();
  std::string upper = lower;
  for (char& c : upper) c = static_cast<char>(std::toupper(c));
  const std::string probe = dir + lower;
  const int fd = ::open(probe.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC,
                        0600);
  if (fd < 0) return false;
  ::close(fd);
  struct stat a {}, b {};
  const bool folds = ::stat(probe.c_str(), &a) == 0 &&
                     ::stat((dir + upper).c_str(), &b) == 0 &&
                     a.st_dev == b.st_dev && a.st_ino == b.st_ino;
  ::unlink(probe.c_str());
  return folds;
}

std::string OutputNameLengthProblem(const std::string& name,
                                    const std::string& path) {
  const fs::path normal(NormalOutputPath(path));
  const std::string last = normal.filename().string();
  // The longest temporary: ".<last>.old-<tag>-<n>" of a directory
  // (io/output_directory.h), "<last>.tmp-<tag>-<n>" of a file; n up to 20
  // digits.
  const size_t suffix = std::string(".." "old-").size() + ProcessTag().size() +
                        1 + 20;
  long name_max = ::pathconf(normal.parent_path().c_str(), _PC_NAME_MAX);
  if (name_max <= 0) name_max = NAME_MAX;
  if (last.size() + suffix > static_cast<size_t>(name_max)) {
    return name + " " + path.substr(0, 40) + "...: its name is " +
           std::to_string(last.size()) + " bytes; the file system takes " +
           std::to_string(name_max) + ", and " + std::to_string(suffix) +
           " go to the temporary it is written under: give a name of at most " +
           std::to_string(name_max - static_cast<long>(suffix)) + " bytes";
  }
  long path_max = ::pathconf(normal.parent_path().c_str(), _PC_PATH_MAX);
  if (path_max <= 0) path_max = PATH_MAX;
  // A directory's files (shape_NNN.ply, summary.json) and their temporaries
  // lie one level below.
  const size_t longest = normal.string().size() + suffix + 32;
  if (longest > static_cast<size_t>(path_max)) {
    return name + " " + path.substr(0, 40) + "...: the path is " +
           std::to_string(normal.string().size()) +
           " bytes, too long for the file system (" +
           std::to_string(path_max) + " with the files written under it)";
  }
  return "";
}

OutputPaths& OutputPaths::Add(std::vector<Entry>* entries,
                              const std::string& name,
                              const std::string& path) {
  if (!path.empty()) entries->push_back({name, path});
  return *this;
}

OutputPaths& OutputPaths::InputFile(const std::string& name,
                                    const std::string& path) {
  return Add(&input_files_, name, path);
}

OutputPaths& OutputPaths::InputList(const std::string& name,
                                    const std::string& list) {
  if (list.empty()) return *this;
  std::vector<std::string> items;
  for (size_t start = 0;;) {
    const size_t comma = list.find(',', start);
    items.push_back(list.substr(
        start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  const std::string count = std::to_string(items.size());
  for (size_t k = 0; k < items.size(); ++k) {
    const std::string& item = items[k];
    const std::string position =
        "item " + std::to_string(k + 1) + " of " + count;
    const std::string empty =
        name + " '" + list + "' has an empty item: " + position;
    if (item.empty()) {
      const char* why = k + 1 == items.size() ? " (a trailing comma)"
                        : k == 0              ? " (a leading comma)"
                                              : " (two commas in a row)";
      throw InputError(empty + why);
    }
    if (item.find_first_not_of(" \t") == std::string::npos) {
      throw InputError(empty + " (only white space between commas)");
    }
    const auto space = [](char c) {
      return std::isspace(static_cast<unsigned char>(c)) != 0;
    };
    struct stat info {};
    const bool padded = space(item.front()) || space(item.back());
    if (padded && ::stat(item.c_str(), &info) != 0) {
      throw InputError(name + " '" + list + "': " + position + ", '" + item +
                       "', begins or ends with white space and names no "
                       "file (items are split at the commas only: no space "
                       "after a comma)");
    }
    InputFile(name, item);
  }
  return *this;
}

OutputPaths& OutputPaths::InputFrames(const std::string& name,
                                      const std::string& input) {
  if (input.empty()) return *this;
  std::error_code error;
  if (input.find(',') == std::string::npos && fs::is_directory(input, error)) {
    input_dirs_.push_back({name, input});
    try {
      for (const std::string& file : ListFrameFiles(input)) {
        InputFile(name, file);
      }
    } catch (const InputError&) {
      // An empty or unreadable directory: the verb's reader says so.
    }
    return *this;
  }
  return InputList(name, input);
}

OutputPaths& OutputPaths::OutputFile(const std::string& name,
                                     const std::string& path) {
  return Add(&output_files_, name, path);
}

OutputPaths& OutputPaths::OutputGlb(const std::string& name,
                                    const std::string& path) {
  Add(&glb_files_, name, path);
  return Add(&output_files_, name, path);
}

OutputPaths& OutputPaths::AddNamed(const std::string& name,
                                   const std::string& path,
                                   std::vector<std::string> extensions,
                                   const std::string& container) {
  if (!path.empty()) {
    named_files_.push_back({{name, path}, std::move(extensions), container});
  }
  return Add(&output_files_, name, path);
}

OutputPaths& OutputPaths::OutputPng(const std::string& name,
                                    const std::string& path) {
  return AddNamed(name, path, {".png"}, "a PNG image");
}

OutputPaths& OutputPaths::OutputHtml(const std::string& name,
                                     const std::string& path) {
  return AddNamed(name, path, {".html", ".htm"}, "an HTML page");
}

OutputPaths& OutputPaths::OutputMesh(const std::string& name,
                                     const std::string& path) {
  return AddNamed(name, path, {".ply", ".obj", ".off"}, "a mesh");
}

OutputPaths& OutputPaths::OutputDirectory(const std::string& name,
                                          const std::string& path) {
  return Add(&output_dirs_, name, path);
}

void OutputPaths::CheckOutputFile(size_t i) const {
  const Entry& out = output_files_[i];
  for (const Entry& in : input_files_) {
    if (Same(out.path, in.path)) {
      throw InputError(out.name + " " + out.path + " is also the input " +
                       in.name + ": not overwriting it");
    }
  }
  for (const Entry& in : input_dirs_) {
    if (Same(out.path, in.path)) {
      throw InputError(out.name + " " + out.path + " is the input directory " +
                       in.name);
    }
  }
  for (const Entry& dir : output_dirs_) {
    if (Same(out.path, dir.path) || Inside(out.path, dir.path)) {
      throw InputError(out.name + " " + out.path + " is inside " + dir.name +
                       " " + dir.path +
                       ", which is replaced as a whole: write it elsewhere");
    }
  }
  for (size_t j = 0; j < i; ++j) {
    if (Same(out.path, output_files_[j].path) ||
        FoldedTogether(out.path, output_files_[j].path)) {
      throw InputError(out.name + " and " + output_files_[j].name +
                       " are the same file " + out.path);
    }
  }
  std::error_code error;
  if (fs::is_directory(out.path, error)) {
    throw InputError(out.name + " " + out.path + " is a directory");
  }
  // A FIFO, socket or device: reading (a cache) would block and the
  // staged rename would replace the node itself.
  if (fs::exists(out.path, error) && !fs::is_regular_file(out.path, error)) {
    throw InputError(out.name + " " + out.path +
                     " is not a regular file (a FIFO, socket or device)");
  }
  CheckParentWritable(out.name, out.path);
  if (Exists(out.path) && ::access(out.path.c_str(), W_OK) != 0) {
    throw InputError(out.name + " " + out.path + " is not writable");
  }
  CheckLength(out.name, out.path);
}

void OutputPaths::CheckOutputDirectory(size_t i) const {
  const Entry& out = output_dirs_[i];
  for (const Entry& in : input_files_) {
    if (Same(out.path, in.path) || Inside(in.path, out.path)) {
      throw InputError(out.name + " " + out.path + " holds the input " +
                       in.name + " " + in.path +
                       " (the directory is replaced as a whole)");
    }
  }
  for (const Entry& in : input_dirs_) {
    if (Same(out.path, in.path)) {
      throw InputError(out.name + " " + out.path + " is the input directory " +
                       in.name);
    }
    if (Inside(in.path, out.path)) {
      throw InputError(out.name + " " + out.path +
                       " holds the input directory " + in.name + " " + in.path);
    }
  }
  for (size_t j = 0; j < i; ++j) {
    const Entry& other = output_dirs_[j];
    if (Same(out.path, other.path) || Inside(out.path, other.path) ||
        Inside(other.path, out.path) || FoldedTogether(out.path, other.path)) {
      throw InputError(out.name + " " + out.path + " and " + other.name + " " +
                       other.path + " overlap");
    }
  }
  for (const Entry& file : output_files_) {
    if (FoldedTogether(out.path, file.path)) {
      throw InputError(file.name + " and " + out.name + " are the same file " +
                       file.path);
    }
  }
  const std::string problem =
      ReplaceableDirectoryProblem(WithoutTrailingSlash(out.path));
  if (!problem.empty()) throw InputError(out.name + ": " + problem);
  CheckParentWritable(out.name, out.path);
  if (Exists(out.path) && ::access(out.path.c_str(), W_OK | X_OK) != 0) {
    throw InputError(out.name + " " + out.path + " is not writable");
  }
  CheckLength(out.name, out.path);
}

void OutputPaths::CheckContainerNames() const {
  for (const NamedContainer& named : named_files_) {
    const std::string lower = AsciiLowercase(named.entry.path);
    bool matches = false;
    std::string names;
    for (const std::string& ext : named.extensions) {
      matches = matches || (lower.size() > ext.size() &&
                            lower.compare(lower.size() - ext.size(), ext.size(),
                                          ext) == 0);
      names += (names.empty() ? "" : ", ") + ext;
    }
    if (!matches) {
      throw InputError(named.entry.name + " " + named.entry.path +
                       ": the file written is " + named.container +
                       "; name it " + names);
    }
  }
}

void OutputPaths::Check() const {
  for (size_t i = 0; i < output_files_.size(); ++i) CheckOutputFile(i);
  for (size_t i = 0; i < output_dirs_.size(); ++i) CheckOutputDirectory(i);
  for (const Entry& glb : glb_files_) CheckGltfFileName(glb.path, glb.name);
  CheckContainerNames();
  // Every output can be written: what killed runs left beside it goes
  // before the solves (a staging directory can be large).
  for (const std::vector<Entry>* outputs : {&output_files_, &output_dirs_}) {
    for (const Entry& out : *outputs) {
      RemoveLeftoversOfEndedRuns(out.path, false);
    }
  }
}

}  // namespace shellspace
