// Reading and writing triangle meshes (PLY, OBJ, OFF) and vertex masks.
#ifndef SHELLSPACE_IO_MESH_IO_H_
#define SHELLSPACE_IO_MESH_IO_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/runtime/stop_token.h"

namespace shellspace {

// Reads a triangle mesh with double-precision coordinates (every printed
// digit kept: a single-precision intermediate would change energies in the
// 6th digit). The format follows the extension: .ply (ascii,
// binary_little_endian, binary_big_endian; a vertex element with x, y, z and
// a face element with a vertex_indices list, other elements and properties
// read and ignored), .obj (v and f lines; vt, vn, vp, g, o, s, usemtl, mtllib
// ignored; f v/vt/vn and negative indices accepted), .off (the header OFF or
// a variant [ST][C][N][4]OFF: per-vertex normals N, colours C (r g b [a])
// and texture coordinates ST read and ignored, 4OFF's homogeneous x y z w
// read as x/w, y/w, z/w; optional r g b [a] face colours ignored; nOFF and
// binary OFF refused). The file must be a regular file of at most
// kMaxMeshFileBytes (io/input_file.h: FIFOs, devices, directories and
// sockets are refused without blocking or reading), a PLY or OFF header
// (up to end_header, or the counts) must end within its first MiB, and
// every element count a header declares must fit in the file's size (at
// least two bytes per ASCII value, the type sizes in binary PLY; an element
// of no properties with rows is refused) before a row is read or stored:
// the memory of a read is bounded by a few times the file size, and `stop`
// ends it (with ReadStopped, io/input_file.h) within a few thousand lines
// or rows. All formats go through the same checks, on the raw file data:
// every face a triangle of integer indices in range, no missing,
// extra or malformed values, nothing after the declared elements (PLY, OFF),
// then ValidateMeshStructure (geometry/validation.h: finite coordinates,
// manifold edges, no duplicate faces, no isolated vertex). Every failure is
// one InputError line naming the file, the element (0-based vertex/face
// number, and the line for text formats) and the problem; file content is
// echoed only as a short escaped excerpt. Degenerate triangles are checked
// by ValidateShell, not here.
Mesh ReadMesh(const std::string& path, const StopToken& stop = StopToken());

// Writes a mesh; the format follows the extension (.ply ASCII with double
// coordinates, .obj, .off), atomically (io/atomic_file.h), so a failure
// leaves no partial file. Throws InputError on failure.
void WriteMesh(const Mesh& mesh, const std::string& path);

// The writer of `mesh` in the format of `path`'s extension, for
// AtomicFileSet::Add (several files committed together). Throws InputError
// for an unsupported extension. `mesh` must outlive the writer.
StreamWriter MeshWriter(const Mesh& mesh, const std::string& path);

// Reads a vertex mask: 0-based vertex indices separated by white space, '#'
// starts a comment. Throws InputError (naming the file, and the line for a
// bad entry, with at most a short escaped excerpt of it) for a missing or
// unreadable file, anything but a regular file of at most kMaxMaskFileBytes
// (io/input_file.h), a binary file (NUL bytes), a token that is not a
// decimal integer, or an index outside [0, num_vertices). Returns sorted
// unique indices (memory: one byte per vertex, however long the file).
// `stop` ends the read with ReadStopped.
std::vector<int> ReadMask(const std::string& path, int num_vertices,
                          const StopToken& stop = StopToken());

}  // namespace shellspace

#endif  // SHELLSPACE_IO_MESH_IO_H_
