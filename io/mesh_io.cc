#include "shellspace/io/mesh_io.h"

#include "shellspace/io/atomic_file.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace shellspace {
namespace {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OpenMeshPoly = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

std::string Extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Parses an ASCII PLY with a vertex element whose first three properties
// include x, y, z, and a face element with one list property. Returns false
// if the file is not ASCII PLY (the caller then uses OpenMesh).
bool ReadAsciiPly(const std::string& path, Mesh* mesh) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) return false;
  struct Element {
    std::string name;
    long count = 0;
    std::vector<std::string> properties;  // "list" marks a list property
  };
  std::vector<Element> elements;
  bool ascii = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string format;
      words >> format;
      ascii = format == "ascii";
      if (!ascii) return false;
    } else if (keyword == "element") {
      Element element;
      words >> element.name >> element.count;
      elements.push_back(element);
    } else if (keyword == "property") {
      if (elements.empty())
        throw InputError(path + ": PLY property before element");
      std::string type, name;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> name;
        elements.back().properties.push_back("list");
      } else {
        words >> name;
        elements.back().properties.push_back(name);
      }
    } else if (keyword == "end_header") {
      break;
    }
  }
  if (!ascii) return false;
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 3>> faces;
  for (const Element& element : elements) {
    for (long r = 0; r < element.count; ++r) {
      if (!std::getline(in, line)) {
        throw InputError(path + ": PLY file ends early in element '" +
                         element.name + "'");
      }
      std::istringstream values(line);
      if (element.name == "vertex") {
        std::array<double, 3> p{0, 0, 0};
        int found = 0;
        for (const std::string& property : element.properties) {
          // strtod, unlike operator>>, parses "nan" and "inf": they are
          // reported as non-finite coordinates by the validation.
          std::string token;
          char* end = nullptr;
          double value = 0;
          if (values >> token) value = std::strtod(token.c_str(), &end);
          if (end == nullptr || *end != '\0') {
            throw InputError(path + ": malformed vertex line " +
                             std::to_string(r));
          }
          if (property == "x") p[0] = value, ++found;
          if (property == "y") p[1] = value, ++found;
          if (property == "z") p[2] = value, ++found;
        }
        if (found != 3) throw InputError(path + ": PLY vertex lacks x, y, z");
        points.push_back(p);
      } else if (element.name == "face") {
        int n = 0;
        if (!(values >> n)) {
          throw InputError(path + ": malformed face line " + std::to_string(r));
        }
        if (n != 3) {
          throw InputError(path + ": face " + std::to_string(r) + " has " +
                           std::to_string(n) +
                           " vertices; only triangle meshes are supported");
        }
        std::array<int, 3> f;
        for (int c = 0; c < 3; ++c) {
          if (!(values >> f[c])) {
            throw InputError(path + ": malformed face line " +
                             std::to_string(r));
          }
        }
        faces.push_back(f);
      }
    }
  }
  mesh->positions.resize(points.size(), 3);
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) mesh->positions(i, c) = points[i][c];
  }
  mesh->faces.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) mesh->faces(f, c) = faces[f][c];
  }
  return true;
}

Mesh ReadWithOpenMesh(const std::string& path) {
  OpenMeshPoly om;
  OpenMesh::IO::Options options;
  // OpenMesh prints its own diagnostics on std::cerr; silence them, we
  // report one line ourselves.
  std::streambuf* old = std::cerr.rdbuf(nullptr);
  omlog().disable();
  omerr().disable();
  const bool ok = OpenMesh::IO::read_mesh(om, path, options);
  std::cerr.rdbuf(old);
  if (!ok) throw InputError("cannot read mesh " + path);
  Mesh mesh;
  mesh.positions.resize(om.n_vertices(), 3);
  for (auto v : om.vertices()) {
    const auto& p = om.point(v);
    mesh.positions.row(v.idx()) << p[0], p[1], p[2];
  }
  mesh.faces.resize(om.n_faces(), 3);
  for (auto f : om.faces()) {
    int c = 0;
    for (auto v : om.fv_range(f)) {
      if (c == 3) {
        throw InputError(path + ": face " + std::to_string(f.idx()) +
                         " is not a triangle; only triangle meshes are "
                         "supported");
      }
      mesh.faces(f.idx(), c++) = v.idx();
    }
    if (c != 3) {
      throw InputError(path + ": face " + std::to_string(f.idx()) +
                       " is not a triangle");
    }
  }
  return mesh;
}

}  // namespace

Mesh ReadMesh(const std::string& path) {
  std::ifstream probe(path);
  if (!probe) throw InputError("cannot open mesh file " + path);
  probe.close();
  const std::string ext = Extension(path);
  if (ext != "ply" && ext != "obj" && ext != "off") {
    throw InputError("unsupported mesh format '" + ext + "' of " + path +
                     " (use .ply, .obj or .off)");
  }
  Mesh mesh;
  if (!(ext == "ply" && ReadAsciiPly(path, &mesh))) {
    mesh = ReadWithOpenMesh(path);
  }
  if (mesh.num_vertices() == 0 || mesh.num_faces() == 0) {
    throw InputError(
        path + ": mesh has no " +
        std::string(mesh.num_vertices() == 0 ? "vertices" : "faces"));
  }
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
    for (int i = 0; i < n; ++i) {
      if (ext == "obj") out << "v ";
      out << mesh.positions(i, 0) << " " << mesh.positions(i, 1) << " "
          << mesh.positions(i, 2) << "\n";
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

std::vector<int> ReadMask(const std::string& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open mask file " + path);
  std::vector<int> mask;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string token;
    while (words >> token) {
      char* end = nullptr;
      const long value = std::strtol(token.c_str(), &end, 10);
      if (*end != '\0') {
        throw InputError(path + ":" + std::to_string(line_number) +
                         ": not a vertex index: '" + token + "'");
      }
      if (value < 0 || value >= num_vertices) {
        throw InputError(path + ":" + std::to_string(line_number) +
                         ": vertex index " + token +
                         " out of range for a mesh with " +
                         std::to_string(num_vertices) + " vertices");
      }
      mask.push_back(static_cast<int>(value));
    }
  }
  std::sort(mask.begin(), mask.end());
  mask.erase(std::unique(mask.begin(), mask.end()), mask.end());
  return mask;
}

}  // namespace shellspace
