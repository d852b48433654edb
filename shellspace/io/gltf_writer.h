// Writing a path of shells as one binary glTF 2.0 file (.glb): a morph
// animation that Blender (File > Import > glTF 2.0) and web viewers play.
#ifndef SHELLSPACE_IO_GLTF_WRITER_H_
#define SHELLSPACE_IO_GLTF_WRITER_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// How the frames are played: `frames_per_second` > 0 (frame k is shown at
// time k / frames_per_second) and the interpolation of the morph weights
// between keys (LINEAR blends frames k and k + 1 linearly, vertex by vertex;
// STEP shows each frame until the next key).
struct GltfAnimationOptions {
  double frames_per_second = 4.0;
  enum class Interpolation { kLinear, kStep } interpolation =
      Interpolation::kLinear;
};

// "linear" -> kLinear, "step" -> kStep; anything else throws InputError
// naming `name` (the caller's name of the option, e.g. "--interpolation").
GltfAnimationOptions::Interpolation ParseGltfInterpolation(
    const std::string& text, const std::string& name);

// The .glb bytes of `frames` (K + 1 shapes, each #V x 3, sharing `faces`,
// #F x 3): one mesh whose base POSITION is frames[0] and whose K morph
// targets are the POSITION deltas frames[k] - frames[0] (k = 1..K; float32,
// computed against the float32 base so that base + delta reproduces
// frames[k] to float rounding; every POSITION accessor with its min and
// max), indices as UNSIGNED_INT triangles, one node and scene, and one
// animation of the node's morph weights with a key per frame at k /
// frames_per_second whose weights are one-hot (key 0 all zero, key k the
// target k - 1 at 1). Target names "shape_001" ... in the mesh's
// extras.targetNames. Throws InputError for no frames, frames of different
// vertex counts, a face index out of range, or a coordinate, morph delta or
// key time that is not finite as float32 (|x| beyond 3.4e38: glTF cannot
// hold it), or two key times that are one float32 (a rate near 1e38 or
// beyond), before any byte is encoded.
std::string EncodeGltfMorphAnimation(const std::vector<Positions>& frames,
                                     const Faces& faces,
                                     const GltfAnimationOptions& options = {});

// The files written here are binary glTF (.glb): a name that does not end
// in ".glb" (any case; a ".gltf" name promises the JSON container) throws
// InputError naming `name` (the caller's name of the option).
void CheckGltfFileName(const std::string& path, const std::string& name);

// Writes EncodeGltfMorphAnimation's bytes to `path` atomically
// (io/atomic_file.h). Throws InputError as it does, or if the file cannot
// be written.
void WriteGltfMorphAnimation(const std::string& path,
                             const std::vector<Positions>& frames,
                             const Faces& faces,
                             const GltfAnimationOptions& options = {});

}  // namespace shellspace

#endif  // SHELLSPACE_IO_GLTF_WRITER_H_
