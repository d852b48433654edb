// Reading and writing triangle meshes (PLY, OBJ, OFF) and vertex masks.
#ifndef SHELLSPACE_IO_MESH_IO_H_
#define SHELLSPACE_IO_MESH_IO_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/atomic_file.h"

namespace shellspace {

// Reads a triangle mesh with double-precision coordinates. The format follows
// the extension (.ply, .obj, .off). ASCII PLY files are parsed directly so
// that coordinates keep every printed digit (a single-precision intermediate
// would change energies in the 6th digit, calculus.md); other files go through
// OpenMesh with double-precision points. Throws InputError if the file is
// missing or unreadable, has no faces, or has non-triangle faces. Does not
// validate geometry: see geometry/validation.h.
Mesh ReadMesh(const std::string& path);

// Writes a mesh; the format follows the extension (.ply ASCII with double
// coordinates, .obj, .off), atomically (io/atomic_file.h), so a failure
// leaves no partial file. Throws InputError on failure.
void WriteMesh(const Mesh& mesh, const std::string& path);

// The writer of `mesh` in the format of `path`'s extension, for
// AtomicFileSet::Add (several files committed together). Throws InputError
// for an unsupported extension. `mesh` must outlive the writer.
StreamWriter MeshWriter(const Mesh& mesh, const std::string& path);

// Reads a vertex mask: one 0-based vertex index per line, '#' starts a
// comment. Throws InputError for unreadable files, bad tokens, or indices
// outside [0, num_vertices). Returns sorted unique indices.
std::vector<int> ReadMask(const std::string& path, int num_vertices);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_MESH_IO_H_
