#include "shellspace/io/frame_sequence.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/output_directory.h"

namespace shellspace {
namespace {

namespace fs = std::filesystem;

bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)); }

bool HasMeshExtension(const fs::path& path) {
  const std::string ext = AsciiLowercase(path.extension().string());
  return ext == ".ply" || ext == ".obj" || ext == ".off";
}

std::string Trim(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
}

// The number of a frame name "shape_NNN.ply" (at least three digits, as
// the runs write them), or -1.
long FrameNumber(const std::string& name) {
  static const std::string prefix = "shape_";
  const size_t dot = name.rfind('.');
  if (name.compare(0, prefix.size(), prefix) != 0 || dot == std::string::npos ||
      dot < prefix.size() + 3 || dot - prefix.size() > 9 ||
      name.substr(dot) != ".ply") {
    return -1;
  }
  const std::string digits = name.substr(prefix.size(), dot - prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stol(digits);
}

std::vector<std::string> ListDirectory(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code error;
  for (fs::directory_iterator it(dir, error), end; !error && it != end;
       it.increment(error)) {
    std::error_code type_error;
    const std::string name = it->path().filename().string();
    if (!HasMeshExtension(it->path()) || name[0] == '.' ||
        IsTemporaryName(name)) {
      continue;
    }
    if (it->is_symlink(type_error) && !it->exists(type_error)) {
      // A frame that is not there: refused, not skipped.
      throw InputError(it->path().string() +
                       " is a broken symbolic link (its target " +
                       fs::read_symlink(it->path(), type_error).string() +
                       " does not exist)");
    }
    if (!it->is_regular_file(type_error)) {
      // A directory, FIFO or socket named like a numbered frame
      // (shape_003.ply) is refused, not skipped: the last frame would
      // vanish unnoticed. Others (a folder sub.ply) are not frames.
      if (FrameNumber(name) >= 0) {
        throw InputError(it->path().string() +
                         " is named like a mesh but is not a regular file");
      }
      continue;
    }
    files.push_back(it->path().string());
  }
  if (error) throw InputError("cannot list directory " + dir);
  if (files.empty()) {
    throw InputError("no .ply, .obj or .off meshes in directory " + dir);
  }
  std::sort(files.begin(), files.end(), NaturalLess);
  // A directory of numbered frames (shape_000.ply ...: a path a run wrote)
  // is read whole or not at all: a gap is a missing frame.
  std::vector<long> numbers;
  for (const std::string& file : files) {
    numbers.push_back(FrameNumber(fs::path(file).filename().string()));
  }
  if (std::all_of(numbers.begin(), numbers.end(),
                  [](long n) { return n >= 0; })) {
    for (size_t k = 0; k < numbers.size(); ++k) {
      if (k > 0 && numbers[k] == numbers[k - 1]) {
        throw InputError(dir + " holds frame " + std::to_string(numbers[k]) +
                         " twice (" + files[k - 1] + ", " + files[k] + ")");
      }
      if (numbers[k] != static_cast<long>(k)) {
        char name[32];
        std::snprintf(name, sizeof(name), "shape_%03zu", k);
        throw InputError(dir + ": frame " + name +
                         " is missing (the frames are numbered from 0 "
                         "without gaps)");
      }
    }
  }
  return files;
}

}  // namespace

bool NaturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (IsDigit(a[i]) && IsDigit(b[j])) {
      size_t i_end = i, j_end = j;
      while (i_end < a.size() && IsDigit(a[i_end])) ++i_end;
      while (j_end < b.size() && IsDigit(b[j_end])) ++j_end;
      // Compare the runs as numbers: skip leading zeros, then by length,
      // then digit by digit.
      size_t i_start = i, j_start = j;
      while (i_start + 1 < i_end && a[i_start] == '0') ++i_start;
      while (j_start + 1 < j_end && b[j_start] == '0') ++j_start;
      const size_t i_len = i_end - i_start, j_len = j_end - j_start;
      if (i_len != j_len) return i_len < j_len;
      const int order = a.compare(i_start, i_len, b, j_start, j_len);
      if (order != 0) return order < 0;
      i = i_end;
      j = j_end;
    } else {
      if (a[i] != b[j]) {
        return static_cast<unsigned char>(a[i]) <
               static_cast<unsigned char>(b[j]);
      }
      ++i;
      ++j;
    }
  }
  if ((a.size() - i) != (b.size() - j)) return a.size() - i < b.size() - j;
  return a < b;  // equal up to leading zeros: keep a total order
}

std::vector<std::string> ListFrameFiles(const std::string& input) {
  const std::string trimmed = Trim(input);
  if (trimmed.empty()) throw InputError("no input meshes given");
  if (trimmed.find(',') == std::string::npos) {
    std::error_code error;
    if (fs::is_directory(trimmed, error)) return ListDirectory(trimmed);
    if (!fs::exists(trimmed, error)) {
      throw InputError("input " + trimmed + " does not exist");
    }
    return {trimmed};
  }
  std::vector<std::string> files;
  size_t start = 0;
  while (true) {
    const size_t comma = trimmed.find(',', start);
    const std::string item = Trim(trimmed.substr(
        start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty()) {
      throw InputError("empty entry in the input list '" + trimmed + "'");
    }
    files.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return files;
}

FrameSequence ReadFrameSequence(const std::string& input,
                                const StopToken& stop) {
  FrameSequence sequence;
  sequence.paths = ListFrameFiles(input);
  for (const std::string& path : sequence.paths) {
    Mesh mesh = ReadMesh(path, stop);
    if (sequence.frames.empty()) {
      sequence.faces = mesh.faces;
    } else if (mesh.num_vertices() != sequence.frames[0].rows()) {
      throw InputError(path + " has " + std::to_string(mesh.num_vertices()) +
                       " vertices, " + sequence.paths[0] + " has " +
                       std::to_string(sequence.frames[0].rows()));
    } else if (mesh.faces.rows() != sequence.faces.rows() ||
               mesh.faces != sequence.faces) {
      throw InputError(path + " has other faces than " + sequence.paths[0]);
    }
    sequence.frames.push_back(std::move(mesh.positions));
  }
  return sequence;
}

void MakeDirectory(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir)) {
    throw InputError("cannot create output directory " + dir);
  }
}

void AddFrames(const std::string& dir, const Faces& faces,
               const std::vector<Positions>& frames, AtomicFileSet* files) {
  MakeDirectory(dir);
  for (size_t k = 0; k < frames.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof(name), "/shape_%03zu.ply", k);
    const std::string path = dir + name;
    files->Add(path, MeshWriter(Mesh{frames[k], faces}, path));
  }
}

void WriteFrames(const std::string& dir, const Faces& faces,
                 const std::vector<Positions>& frames) {
  AtomicFileSet files;
  AddFrames(dir, faces, frames, &files);
  files.Commit();
}

}  // namespace shellspace
