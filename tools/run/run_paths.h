// The files a verb run reads and writes, named by their flags and checked
// before any work by the library's one policy (io/output_paths.h): no
// output is an input under any spelling, no two outputs name one file, an
// output directory is replaceable, every output can be written and named.
#ifndef SHELLSPACE_TOOLS_RUN_RUN_PATHS_H_
#define SHELLSPACE_TOOLS_RUN_RUN_PATHS_H_

#include <string>

#include "shellspace/io/output_paths.h"

namespace shellspace {

class RunPaths {
 public:
  // An input file (empty `path`: the flag is not set, ignored).
  RunPaths& InputFile(const std::string& flag, const std::string& path) {
    paths_.InputFile("--" + flag, path);
    return *this;
  }
  // A comma-separated list of input files (no empty item).
  RunPaths& InputList(const std::string& flag, const std::string& list) {
    paths_.InputList("--" + flag, list);
    return *this;
  }
  // A directory of frames or a comma list (io/frame_sequence.h).
  RunPaths& InputFrames(const std::string& flag, const std::string& input) {
    paths_.InputFrames("--" + flag, input);
    return *this;
  }
  // An output file (PLY, PNG, ...), written atomically.
  RunPaths& OutputFile(const std::string& flag, const std::string& path) {
    paths_.OutputFile("--" + flag, path);
    return *this;
  }
  // An output file of PNG (named .png), of a viewer page (.html, .htm), of
  // one mesh (.ply, .obj, .off).
  RunPaths& OutputPng(const std::string& flag, const std::string& path) {
    paths_.OutputPng("--" + flag, path);
    return *this;
  }
  RunPaths& OutputHtml(const std::string& flag, const std::string& path) {
    paths_.OutputHtml("--" + flag, path);
    return *this;
  }
  RunPaths& OutputMesh(const std::string& flag, const std::string& path) {
    paths_.OutputMesh("--" + flag, path);
    return *this;
  }
  // An output file of binary glTF (named .glb).
  RunPaths& OutputGlb(const std::string& flag, const std::string& path) {
    paths_.OutputGlb("--" + flag, path);
    return *this;
  }
  // An output directory, written whole (io/output_directory.h).
  RunPaths& OutputDirectory(const std::string& flag, const std::string& path) {
    paths_.OutputDirectory("--" + flag, path);
    return *this;
  }
  // Throws InputError for the first problem (io/output_paths.h).
  void Check() const { paths_.Check(); }

 private:
  OutputPaths paths_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_RUN_PATHS_H_
