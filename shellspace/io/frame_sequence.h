// Reading and writing a sequence of shells (frames): the paths of the
// calculus as directories of PLY files.
#ifndef SHELLSPACE_IO_FRAME_SEQUENCE_H_
#define SHELLSPACE_IO_FRAME_SEQUENCE_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/runtime/stop_token.h"

namespace shellspace {

// Frames of one shell: per-frame positions sharing one connectivity.
struct FrameSequence {
  std::vector<std::string> paths;   // the file of each frame
  std::vector<Positions> frames;
  Faces faces;
};

// The mesh files named by `input`: either a directory, giving every regular
// file in it ending in .ply, .obj or .off (any case) in natural name order
// (digit runs compare as numbers, so shape_2 comes before shape_10), hidden
// files (".name") and the temporaries of io/atomic_file.h and
// io/output_directory.h excepted, or a
// comma-separated list of files, kept in the given order. Throws InputError
// if `input` is empty, a directory does not exist or holds no meshes, or a
// list entry is empty.
std::vector<std::string> ListFrameFiles(const std::string& input);

// Reads the meshes of ListFrameFiles(input) with ReadMesh (each asking
// `stop`). Throws InputError as ListFrameFiles and ReadMesh do, and if a
// mesh has another vertex count or other faces than the first one.
FrameSequence ReadFrameSequence(const std::string& input,
                                const StopToken& stop = StopToken());

// Creates directory `dir` (and parents) if missing; InputError naming it on
// failure.
void MakeDirectory(const std::string& dir);

// Writes shapes (each #V x 3, sharing `faces`) as DIR/shape_000.ply ...,
// creating DIR if missing, all together or none (io/atomic_file.h
// AtomicFileSet).
void WriteFrames(const std::string& dir, const Faces& faces,
                 const std::vector<Positions>& frames);

// The frames of WriteFrames added to `files` (committed by the caller with
// other files, all together or none); creates DIR if missing.
void AddFrames(const std::string& dir, const Faces& faces,
               const std::vector<Positions>& frames, AtomicFileSet* files);

// True if `a` comes before `b` in natural order (see ListFrameFiles).
bool NaturalLess(const std::string& a, const std::string& b);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_FRAME_SEQUENCE_H_
