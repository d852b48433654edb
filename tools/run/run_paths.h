// The files a verb run reads and writes, checked before any work: no output
// is an input (after resolving symbolic links and `..`; hard links by
// inode), no output directory holds an input, no two outputs coincide, an
// output file is not inside an output directory (which is replaced as a
// whole), an existing output directory is replaceable (the output of an
// earlier run, io/output_directory.h), and every output can be written
// (its parent directory exists and is writable; an existing output file is
// writable). Each failure is one InputError naming the flags. Paths are
// compared as written (io/output_directory.h NormalOutputPath: "out/../out",
// "./out" and "out/" are "out"), so two spellings of one file are one
// file. Once every check passed, the temporaries of killed runs beside each
// output are removed (RemoveLeftoversOfEndedRuns).
#ifndef SHELLSPACE_TOOLS_RUN_RUN_PATHS_H_
#define SHELLSPACE_TOOLS_RUN_RUN_PATHS_H_

#include <string>
#include <vector>

namespace shellspace {

class RunPaths {
 public:
  // An input file (empty `path`: the flag is not set, ignored).
  RunPaths& InputFile(const std::string& flag, const std::string& path);
  // A comma-separated list of input files.
  RunPaths& InputList(const std::string& flag, const std::string& list);
  // A directory of frames or a comma list (io/frame_sequence.h): the
  // directory itself and every frame file in it.
  RunPaths& InputFrames(const std::string& flag, const std::string& input);
  // An output file (PLY, PNG, ...), written atomically.
  RunPaths& OutputFile(const std::string& flag, const std::string& path);
  // An output directory, written whole (io/output_directory.h).
  RunPaths& OutputDirectory(const std::string& flag, const std::string& path);

  // Throws InputError for the first problem (see the file comment).
  void Check() const;

 private:
  struct Entry {
    std::string flag, path;
  };
  // Appends (flag, path) to `entries` unless `path` is empty (the flag is
  // not set).
  RunPaths& Add(std::vector<Entry>* entries, const std::string& flag,
                const std::string& path);

  std::vector<Entry> input_files_, input_dirs_, output_files_, output_dirs_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_RUN_PATHS_H_
