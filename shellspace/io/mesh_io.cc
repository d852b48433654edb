#include "shellspace/io/mesh_io.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <string_view>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/input_file.h"
#include "shellspace/io/mesh_reading.h"

// The readers of the formats: io/ply_reader.cc, io/obj_reader.cc,
// io/off_reader.cc (io/mesh_reading.h).
namespace shellspace {
namespace {

using mesh_reading::Excerpt;
using mesh_reading::kMaxHeaderBytes;
using mesh_reading::LineCursor;
using mesh_reading::MeshBuilder;
using mesh_reading::ParseInteger;
using mesh_reading::Tokenize;
using mesh_reading::WithoutComment;

std::string Extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  return AsciiLowercase(path.substr(dot + 1));
}

}  // namespace

Mesh ReadMesh(const std::string& path, const StopToken& stop) {
  const std::string ext = Extension(path);
  if (ext != "ply" && ext != "obj" && ext != "off") {
    std::error_code error;
    if (!std::filesystem::exists(path, error)) {
      throw InputError("cannot open mesh file " + path);
    }
    throw InputError("unsupported mesh format '" + ext + "' of " + path +
                     " (use .ply, .obj or .off)");
  }
  InputFile file(path, "mesh file", kMaxMeshFileBytes, stop);
  MeshBuilder builder;
  builder.path = path;
  builder.stop = stop;
  if (ext != "obj") {
    // The header first, from the first MiB: one whose counts the file size
    // cannot hold is refused before the rest of the file is read.
    const std::string& prefix = file.Read(kMaxHeaderBytes + 1);
    const uint64_t size =
        std::max<uint64_t>(static_cast<uint64_t>(file.size()), prefix.size());
    if (ext == "ply") {
      mesh_reading::CheckPlyHeader(prefix, size, builder);
    } else {
      mesh_reading::CheckOffHeader(prefix, size, &builder);
    }
  }
  const std::string bytes = file.ReadAll();
  const Mesh mesh = ext == "ply"   ? mesh_reading::ReadPly(bytes, &builder)
                    : ext == "obj" ? mesh_reading::ReadObj(bytes, &builder)
                                   : mesh_reading::ReadOff(bytes, &builder);
  CheckReadStop(stop, path);
  ValidateMeshStructure(mesh, path);
  return mesh;
}

StreamWriter MeshWriter(const Mesh& mesh, const std::string& path) {
  const std::string ext = Extension(path);
  if (ext != "ply" && ext != "obj" && ext != "off") {
    throw InputError("unsupported output format '" + ext + "' of " + path +
                     " (use .ply, .obj or .off)");
  }
  return [&mesh, ext](std::ostream& out) {
    out << std::setprecision(17);
    const int n = mesh.num_vertices(), m = mesh.num_faces();
    if (ext == "ply") {
      out << "ply\nformat ascii 1.0\ncomment written by shellspace\n"
          << "element vertex " << n << "\nproperty double x\n"
          << "property double y\nproperty double z\n"
          << "element face " << m
          << "\nproperty list uchar int vertex_indices\nend_header\n";
    } else if (ext == "off") {
      out << "OFF\n" << n << " " << m << " 0\n";
    }
    // Coordinates as printf's %.17g (what the stream would print at
    // precision 17: exact round trips), by std::to_chars, several times
    // faster than the stream's formatting.
    char line[3 * 32 + 8];
    for (int i = 0; i < n; ++i) {
      char* end = line;
      if (ext == "obj") *end++ = 'v', *end++ = ' ';
      for (int c = 0; c < 3; ++c) {
        end = std::to_chars(end, line + sizeof(line) - 2, mesh.positions(i, c),
                            std::chars_format::general, 17)
                  .ptr;
        *end++ = c < 2 ? ' ' : '\n';
      }
      out.write(line, end - line);
    }
    for (int f = 0; f < m; ++f) {
      const int base = ext == "obj" ? 1 : 0;
      out << (ext == "obj" ? "f " : "3 ") << mesh.faces(f, 0) + base << " "
          << mesh.faces(f, 1) + base << " " << mesh.faces(f, 2) + base << "\n";
    }
  };
}

void WriteMesh(const Mesh& mesh, const std::string& path) {
  WriteFileAtomically(path, MeshWriter(mesh, path));
}

std::vector<int> ReadMask(const std::string& path, int num_vertices,
                          const StopToken& stop) {
  const std::string bytes =
      ReadInputFile(path, "mask file", kMaxMaskFileBytes, stop);
  if (bytes.find('\0') != std::string::npos) {
    throw InputError(path + ": not a text file (it contains NUL bytes)");
  }
  // One flag per vertex: the mask's memory is bounded by the mesh, however
  // often the file repeats an index.
  std::vector<char> in_mask(static_cast<size_t>(std::max(num_vertices, 0)), 0);
  LineCursor lines(bytes, 1, path, stop);
  std::string_view text;
  std::vector<std::string_view> tokens;
  while (lines.Next(&text)) {
    Tokenize(WithoutComment(text), &tokens);
    for (const std::string_view token : tokens) {
      const auto where = [&] {
        return path + ":" + std::to_string(lines.number()) + ": ";
      };
      long long value = 0;
      if (!ParseInteger(token, &value)) {
        throw InputError(where() + "not a vertex index: " + Excerpt(token));
      }
      if (value < 0 || value >= num_vertices) {
        throw InputError(where() + "vertex index " + Excerpt(token) +
                         " out of range for a mesh with " +
                         std::to_string(num_vertices) + " vertices");
      }
      in_mask[static_cast<size_t>(value)] = 1;
    }
  }
  std::vector<int> mask;
  for (size_t v = 0; v < in_mask.size(); ++v) {
    if (in_mask[v]) mask.push_back(static_cast<int>(v));
  }
  return mask;
}

}  // namespace shellspace
