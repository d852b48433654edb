// The one policy for the files a run reads and writes, every front end (the
// CLI's verbs, the collection verbs, the Python functions), checked before
// any work:
//
//  - no output is an input under any spelling: ".." and "." and trailing
//    slashes (NormalOutputPath), symbolic links (resolved), hard links
//    (the same device and inode), and a name that a case-folding file
//    system folds onto the input (the same inode once it exists);
//  - no output directory holds an input, and no input directory is an
//    output or holds one;
//  - no two outputs name one file (the same spellings; two new names that
//    differ only in case, in one directory of a file system that folds
//    case), no output file lies inside an output directory (which is
//    replaced as a whole), no two output directories overlap;
//  - an existing output directory is replaceable (the output of an earlier
//    run, io/output_directory.h), an existing output file is a regular file
//    (not a directory, FIFO, socket or device);
//  - every output can be written: its parent directory exists and is
//    writable, an existing output is writable, and its name (with the
//    suffix of the temporary it is staged under, io/atomic_file.h and
//    io/output_directory.h) fits the file system's NAME_MAX and PATH_MAX;
//  - an output's container matches its name: a .glb for glTF, a .png for a
//    film strip, a .html or .htm for a viewer page, a .ply, .obj or .off for
//    a mesh (case does not matter);
//  - a list of inputs has no empty item ("a.ply,,b.ply", "a.ply,b.ply,").
//
// Each failure is one InputError naming the item by the name its front end
// gives it ("--output" on the command line, "output" in Python). Once every
// check passed, the temporaries of killed runs beside each output are
// removed (RemoveLeftoversOfEndedRuns). Outputs are then written staged and
// renamed (io/atomic_file.h), a directory replaced whole
// (io/output_directory.h).
#ifndef SHELLSPACE_IO_OUTPUT_PATHS_H_
#define SHELLSPACE_IO_OUTPUT_PATHS_H_

#include <string>
#include <vector>

namespace shellspace {

class OutputPaths {
 public:
  // An input file (an empty `path`: not given, ignored).
  OutputPaths& InputFile(const std::string& name, const std::string& path);
  // A comma-separated list of input files. An empty item (nothing, or only
  // spaces and tabs, between two commas, before the first or after the
  // last) is an InputError naming its position ("has an empty item: item
  // 2 of 3 (two commas in a row)"),
  // and so is an item that names no file and begins or ends with a space
  // or tab ("a, b.ply": items are split at the commas only).
  OutputPaths& InputList(const std::string& name, const std::string& list);
  // A directory of frames or a comma list (io/frame_sequence.h): the
  // directory itself and every frame file in it.
  OutputPaths& InputFrames(const std::string& name, const std::string& input);
  // An output file, written atomically.
  OutputPaths& OutputFile(const std::string& name, const std::string& path);
  // An output file written as binary glTF: also its name must end in .glb
  // (io/gltf_writer.h CheckGltfFileName), checked after the collisions.
  OutputPaths& OutputGlb(const std::string& name, const std::string& path);
  // An output file of PNG (named .png), of a viewer page (.html, .htm) or
  // of one mesh (.ply, .obj, .off): the name checked after the collisions.
  OutputPaths& OutputPng(const std::string& name, const std::string& path);
  OutputPaths& OutputHtml(const std::string& name, const std::string& path);
  OutputPaths& OutputMesh(const std::string& name, const std::string& path);
  // An output directory, written whole (io/output_directory.h).
  OutputPaths& OutputDirectory(const std::string& name,
                               const std::string& path);

  // Throws InputError for the first problem (see the file comment).
  void Check() const;

 private:
  struct Entry {
    std::string name, path;
  };
  OutputPaths& Add(std::vector<Entry>* entries, const std::string& name,
                   const std::string& path);

  // An output file whose name must end in one of `extensions`
  // (lowercase, with the dot), `container` saying what is written.
  struct NamedContainer {
    Entry entry;
    std::vector<std::string> extensions;
    std::string container;
  };
  OutputPaths& AddNamed(const std::string& name, const std::string& path,
                        std::vector<std::string> extensions,
                        const std::string& container);

  // The parts of Check: output file i and output directory i against the
  // inputs and the outputs before them and on disk; the names of the
  // named containers.
  void CheckOutputFile(size_t i) const;
  void CheckOutputDirectory(size_t i) const;
  void CheckContainerNames() const;

  std::vector<Entry> input_files_, input_dirs_, output_files_, output_dirs_,
      glb_files_;
  std::vector<NamedContainer> named_files_;
};

// True if the file system of directory `dir` folds case (a name and its
// case-swapped spelling name one file): probed with a hidden file created
// and removed in `dir`; false if it cannot be told.
bool FoldsCase(const std::string& dir);

// Why the output `path` cannot be named on its file system: its last name,
// with the longest suffix of the temporaries it is staged under, longer
// than NAME_MAX of its parent directory, or the whole path longer than
// PATH_MAX; "" if it fits. `name` names the item in the message.
std::string OutputNameLengthProblem(const std::string& name,
                                    const std::string& path);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_OUTPUT_PATHS_H_
