// The table of defective mesh files of the reader and CLI tests: each defect
// written in every mesh format it can be expressed in (PLY ascii, PLY binary
// little endian, OBJ, OFF), with the words its error must contain.
#ifndef SHELLSPACE_TESTS_IO_BAD_MESH_FILES_H_
#define SHELLSPACE_TESTS_IO_BAD_MESH_FILES_H_

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

namespace shellspace::testing {

enum class MeshFormat { kPlyAscii, kPlyBinary, kObj, kOff };

// The name of a format in test names, and its file extension (indexed by
// MeshFormat).
struct MeshFormatInfo {
  const char* name;
  const char* extension;
};
inline MeshFormatInfo FormatInfo(MeshFormat f) {
  static constexpr MeshFormatInfo kInfo[] = {{"ply_ascii", "ply"},
                                             {"ply_binary", "ply"},
                                             {"obj", "obj"},
                                             {"off", "off"}};
  return kInfo[static_cast<int>(f)];
}
inline const char* FormatName(MeshFormat f) { return FormatInfo(f).name; }
inline const char* FormatExtension(MeshFormat f) {
  return FormatInfo(f).extension;
}

// A mesh as text tokens: vertex coordinates and 0-based face indices (a
// non-integer token is written as it is; OBJ files get index + 1).
struct MeshSpec {
  std::vector<std::vector<std::string>> vertices;
  std::vector<std::vector<std::string>> faces;
  int declared_faces = -1;         // header face count; -1: faces.size()
  std::string extra_face_token;    // appended to the first face line
  std::string extra_vertex_token;  // appended to the first vertex line
  std::string extra_line;          // appended after the last face (text)
  std::string extra_bytes;         // appended after the data (binary PLY)
};

// The unit square (0,0,0) (1,0,0) (1,1,0) (0,1,0) as faces (0,1,2),
// (0,2,3); a valid mesh.
inline MeshSpec Square() {
  MeshSpec s;
  s.vertices = {
      {"0", "0", "0"}, {"1", "0", "0"}, {"1", "1", "0"}, {"0", "1", "0"}};
  s.faces = {{"0", "1", "2"}, {"0", "2", "3"}};
  return s;
}

inline bool IsInteger(const std::string& token) {
  char* end = nullptr;
  std::strtol(token.c_str(), &end, 10);
  return !token.empty() && *end == '\0';
}

inline std::string Join(const std::vector<std::string>& t) {
  std::string out;
  for (size_t i = 0; i < t.size(); ++i) out += (i ? " " : "") + t[i];
  return out;
}

inline std::string MeshFileContent(const MeshSpec& s, MeshFormat format) {
  const int nf = s.declared_faces >= 0 ? s.declared_faces
                                       : static_cast<int>(s.faces.size());
  const int nv = static_cast<int>(s.vertices.size());
  std::string out;
  const auto vertex_line = [&](size_t i) {
    return Join(s.vertices[i]) + (i == 0 && !s.extra_vertex_token.empty()
                                      ? " " + s.extra_vertex_token
                                      : "");
  };
  const auto face_tokens = [&](size_t f, int base) {
    std::vector<std::string> t;
    for (const std::string& v : s.faces[f]) {
      t.push_back(IsInteger(v) && base ? std::to_string(std::stol(v) + base)
                                       : v);
    }
    if (f == 0 && !s.extra_face_token.empty()) t.push_back(s.extra_face_token);
    return t;
  };
  // The text body of ASCII PLY and OFF: one line per vertex, then one per
  // face led by its vertex count, then the spec's extra line.
  const auto counted_lines = [&] {
    std::string body;
    for (size_t i = 0; i < s.vertices.size(); ++i) {
      body += vertex_line(i) + "\n";
    }
    for (size_t f = 0; f < s.faces.size(); ++f) {
      body += std::to_string(s.faces[f].size()) + " " +
              Join(face_tokens(f, 0)) + "\n";
    }
    return body + s.extra_line;
  };
  bool float_indices = false;
  for (const auto& f : s.faces) {
    for (const auto& v : f) float_indices |= !IsInteger(v);
  }
  switch (format) {
    case MeshFormat::kPlyAscii:
    case MeshFormat::kPlyBinary: {
      const bool binary = format == MeshFormat::kPlyBinary;
      out = std::string("ply\nformat ") +
            (binary ? "binary_little_endian" : "ascii") +
            " 1.0\nelement vertex " + std::to_string(nv) +
            "\nproperty double x\nproperty double y\nproperty double z\n"
            "element face " +
            std::to_string(nf) + "\nproperty list uchar " +
            (binary && float_indices ? "float" : "int") +
            " vertex_indices\nend_header\n";
      if (!binary) {
        out += counted_lines();
      } else {
        const auto put = [&out](const void* p, size_t n) {
          out.append(static_cast<const char*>(p), n);
        };
        for (const auto& v : s.vertices) {
          for (const std::string& c : v) {
            const double d = std::strtod(c.c_str(), nullptr);
            put(&d, 8);
          }
        }
        for (const auto& f : s.faces) {
          const uint8_t n = static_cast<uint8_t>(f.size());
          put(&n, 1);
          for (const std::string& v : f) {
            if (float_indices) {
              const float x = std::strtof(v.c_str(), nullptr);
              put(&x, 4);
            } else {
              const int32_t i = static_cast<int32_t>(std::stol(v));
              put(&i, 4);
            }
          }
        }
        out += s.extra_bytes;
      }
      break;
    }
    case MeshFormat::kObj:
      for (size_t i = 0; i < s.vertices.size(); ++i) {
        out += "v " + vertex_line(i) + "\n";
      }
      for (size_t f = 0; f < s.faces.size(); ++f) {
        out += "f " + Join(face_tokens(f, 1)) + "\n";
      }
      out += s.extra_line;
      break;
    case MeshFormat::kOff:
      out = "OFF\n" + std::to_string(nv) + " " + std::to_string(nf) + " 0\n" +
            counted_lines();
      break;
  }
  return out;
}

// One defect: its name, the file in each format it applies to, and the
// words (element and problem) every format's error contains.
struct BadMeshCase {
  std::string name;
  MeshSpec spec;
  std::vector<MeshFormat> formats;
  std::vector<std::string> expected;
  bool degenerate_only = false;  // rejected by ValidateShell, not ReadMesh
};

inline std::vector<BadMeshCase> BadMeshCases() {
  const std::vector<MeshFormat> all = {MeshFormat::kPlyAscii,
                                       MeshFormat::kPlyBinary, MeshFormat::kObj,
                                       MeshFormat::kOff};
  const std::vector<MeshFormat> text = {MeshFormat::kPlyAscii, MeshFormat::kObj,
                                        MeshFormat::kOff};
  // The formats with a header declaring the element counts and 0-based face
  // indices (not OBJ).
  const std::vector<MeshFormat> counted = {
      MeshFormat::kPlyAscii, MeshFormat::kPlyBinary, MeshFormat::kOff};
  std::vector<BadMeshCase> cases;
  {
    MeshSpec s = Square();
    s.vertices[1][0] = "nan";
    cases.push_back({"nan", s, all, {"vertex 1", "non-finite coordinate"}});
  }
  {
    MeshSpec s = Square();
    s.vertices[2][2] = "inf";
    cases.push_back({"inf", s, all, {"vertex 2", "non-finite coordinate"}});
  }
  {
    MeshSpec s = Square();
    s.faces[1] = {"0", "2", "99"};
    cases.push_back({"index_range",
                     s,
                     all,
                     {"face 1", "vertex", "the mesh has 4 vertices"}});
  }
  {
    MeshSpec s = Square();
    s.faces[1] = {"0", "-2", "3"};
    // OBJ reads -2 as a relative index (vertex 3 of 4): valid there.
    cases.push_back({"negative_index",
                     s,
                     counted,
                     {"face 1", "references vertex -2", "4 vertices"}});
  }
  {
    MeshSpec s = Square();
    s.faces[1] = {"0", "2.7", "3"};
    cases.push_back({"non_integer_index", s, all, {"face", "non-integer"}});
  }
  {
    MeshSpec s = Square();
    s.faces = {{"0", "1", "2", "3"}};
    cases.push_back(
        {"quad", s, all, {"face 0 has 4 vertices", "only triangle"}});
  }
  {
    MeshSpec s = Square();
    s.vertices.push_back({"0.5", "0.5", "1"});
    s.faces.push_back({"0", "2", "4"});
    cases.push_back({"non_manifold_edge",
                     s,
                     all,
                     {"non-manifold", "edge (0, 2)", "faces 1 and 2"}});
  }
  {
    MeshSpec s = Square();
    s.faces.push_back({"0", "2", "1"});
    cases.push_back({"duplicate_face",
                     s,
                     all,
                     {"face 2 duplicates face 0", "vertices 0, 1, 2"}});
  }
  {
    MeshSpec s = Square();
    s.faces.push_back({"0", "1", "2"});
    cases.push_back({"repeated_face", s, all, {"face 2 duplicates face 0"}});
  }
  {
    MeshSpec s = Square();
    s.vertices.push_back({"5", "5", "5"});
    cases.push_back({"isolated_vertex", s, all, {"vertex 4 is isolated"}});
  }
  {
    MeshSpec s = Square();
    s.declared_faces = 1;
    cases.push_back({"extra_face", s, counted, {"extra data"}});
  }
  {
    MeshSpec s = Square();
    s.extra_line = "junk\n";
    cases.push_back({"trailing_garbage", s, text, {"'junk'", "(line "}});
  }
  {
    MeshSpec s = Square();
    s.extra_bytes = "junk";
    cases.push_back({"trailing_bytes",
                     s,
                     {MeshFormat::kPlyBinary},
                     {"4 bytes of extra data"}});
  }
  {
    MeshSpec s = Square();
    s.extra_face_token = "7";
    cases.push_back({"extra_face_token",
                     s,
                     {MeshFormat::kPlyAscii, MeshFormat::kOff},
                     {"face 0", "extra"}});
  }
  {
    MeshSpec s = Square();
    s.extra_vertex_token = "x";
    cases.push_back({"extra_vertex_token", s, text, {"vertex 0"}});
  }
  {
    MeshSpec s = Square();
    s.declared_faces = 3;
    cases.push_back({"truncated", s, counted, {"ends early"}});
  }
  {
    MeshSpec s = Square();
    s.faces.clear();
    s.declared_faces = 0;
    cases.push_back({"no_faces", s, all, {"no faces"}});
  }
  {
    MeshSpec s = Square();
    s.vertices[2] = {"2", "0", "0"};
    s.faces = {{"0", "1", "2"}, {"0", "3", "1"}};
    BadMeshCase c{"degenerate", s, all, {"triangle 0 is degenerate"}};
    c.degenerate_only = true;
    cases.push_back(c);
  }
  // Valid structure and shape, but a scale at which fourth powers of
  // lengths overflow or underflow (1e+-35 are still finite floats for
  // binary PLY).
  for (const auto& [name, side, word] :
       {std::tuple<const char*, const char*, const char*>{
            "huge", "1e35", "coordinates up to 1e+35"},
        {"tiny", "1e-35", "spans only 1.41e-35"}}) {
    MeshSpec s = Square();
    for (auto& v : s.vertices) {
      for (auto& x : v) x = x == "0" ? "0" : side;
    }
    BadMeshCase c{name, s, all, {word, "flow"}};
    c.degenerate_only = true;
    cases.push_back(c);
  }
  return cases;
}

inline std::string WriteBadMesh(const std::string& dir, const BadMeshCase& c,
                                MeshFormat format) {
  const std::string path = dir + "/" + c.name + "_" + FormatName(format) + "." +
                           FormatExtension(format);
  std::ofstream(path, std::ios::binary) << MeshFileContent(c.spec, format);
  return path;
}

// One written file of the table: its defect, format and path.
struct BadMeshFile {
  BadMeshCase defect;
  MeshFormat format;
  std::string path;
};

// Every defect of BadMeshCases() named `only` (all of them if empty) in
// every format it applies to, written into `dir` (WriteBadMesh), in the
// table's order.
inline std::vector<BadMeshFile> WriteBadMeshFiles(
    const std::string& dir, const std::string& only = "") {
  std::vector<BadMeshFile> files;
  for (const BadMeshCase& c : BadMeshCases()) {
    if (!only.empty() && c.name != only) continue;
    for (MeshFormat format : c.formats) {
      files.push_back({c, format, WriteBadMesh(dir, c, format)});
    }
  }
  return files;
}

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_IO_BAD_MESH_FILES_H_
