#include "shellspace/io/mesh_io.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/atomic_file.h"

namespace shellspace {
namespace {

std::string Extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  return AsciiLowercase(path.substr(dot + 1));
}

// At most `max` characters of `text`, quoted, with every byte outside
// printable ASCII written as \xNN, and "..." if cut: what an error message
// may echo of a file's content.
std::string Excerpt(const std::string& text, size_t max = 24) {
  std::string out = "'";
  for (size_t i = 0; i < text.size() && i < max; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      out += hex;
    }
  }
  if (text.size() > max) out += "...";
  return out + "'";
}

// The whole file; InputError if it is missing, a directory or unreadable.
std::string ReadFileBytes(const std::string& path, const std::string& what) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": is a directory, not a " + what);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open " + what + " " + path);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError("cannot read " + what + " " + path);
  return bytes.str();
}

// Lines of a text, split at '\n', with a trailing '\r' removed.
std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    begin = end + 1;
  }
  return lines;
}

// Whitespace-separated tokens of a line (space, tab, \r, \v, \f).
std::vector<std::string> Tokens(const std::string& line) {
  std::vector<std::string> tokens;
  size_t i = 0;
  const auto space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  };
  while (i < line.size()) {
    while (i < line.size() && space(line[i])) ++i;
    size_t j = i;
    while (j < line.size() && !space(line[j])) ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

bool ParseDouble(const std::string& token, double* value) {
  if (token.empty()) return false;
  char* end = nullptr;
  // strtod, unlike operator>>, parses "nan" and "inf": they are reported as
  // non-finite coordinates by the validation.
  *value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

// A decimal integer (optional sign, digits only).
bool ParseInteger(const std::string& token, long long* value) {
  if (token.empty()) return false;
  size_t i = token[0] == '-' || token[0] == '+' ? 1 : 0;
  if (i == token.size() || token.size() > 19) return false;
  for (size_t k = i; k < token.size(); ++k) {
    if (token[k] < '0' || token[k] > '9') return false;
  }
  *value = std::strtoll(token.c_str(), nullptr, 10);
  return true;
}

std::string LineTag(size_t line) {
  return " (line " + std::to_string(line) + ")";
}

// Collects vertices and triangles read from a file and checks each face's
// indices against the vertex count on the raw data.
struct MeshBuilder {
  std::string path;
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<long long, 3>> faces;
  std::vector<size_t> face_lines;  // file line of each face (0: binary)

  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(path + ": " + message);
  }

  // Checks the 0-based indices of every face against `num_vertices`;
  // `base` is added to the index printed (1 for OBJ).
  void CheckIndices(long long num_vertices, int base) const {
    for (size_t f = 0; f < faces.size(); ++f) {
      for (long long v : faces[f]) {
        if (v < 0 || v >= num_vertices) {
          Fail("face " + std::to_string(f) +
               (base == 0 ? " references vertex " : " has vertex index ") +
               std::to_string(v + base) + ", the mesh has " +
               std::to_string(num_vertices) + " vertices" +
               (base == 0 ? "" : " (1-based indices)") +
               (face_lines[f] ? LineTag(face_lines[f]) : ""));
        }
      }
    }
  }

  Mesh Build() const {
    if (points.empty()) Fail("mesh has no vertices");
    if (faces.empty()) Fail("mesh has no faces");
    CheckIndices(static_cast<long long>(points.size()), 0);
    Mesh mesh;
    mesh.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (size_t i = 0; i < points.size(); ++i) {
      for (int c = 0; c < 3; ++c) mesh.positions(i, c) = points[i][c];
    }
    mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (size_t f = 0; f < faces.size(); ++f) {
      for (int c = 0; c < 3; ++c) {
        mesh.faces(f, c) = static_cast<int>(faces[f][c]);
      }
    }
    return mesh;
  }
};

// The largest element count a file may declare (indices are int).
constexpr long long kMaxCount = 2147483647;

// ---------------------------------------------------------------- PLY ----

enum class PlyType {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64
};

bool ParsePlyType(const std::string& name, PlyType* type) {
  static const std::map<std::string, PlyType> kTypes = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},
      {"uchar", PlyType::kUint8},    {"uint8", PlyType::kUint8},
      {"short", PlyType::kInt16},    {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},
      {"int", PlyType::kInt32},      {"int32", PlyType::kInt32},
      {"uint", PlyType::kUint32},    {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32},
      {"double", PlyType::kFloat64}, {"float64", PlyType::kFloat64}};
  const auto it = kTypes.find(name);
  if (it == kTypes.end()) return false;
  *type = it->second;
  return true;
}

bool IsIntegerType(PlyType t) {
  return t != PlyType::kFloat32 && t != PlyType::kFloat64;
}

bool IsSignedIntegerType(PlyType t) {
  return t == PlyType::kInt8 || t == PlyType::kInt16 || t == PlyType::kInt32;
}

int TypeSize(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 1;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat64;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { kAscii, kLittleEndian, kBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // byte offset of the data after end_header
  size_t data_line = 0;    // 1-based line number of the first data line
  long long num_vertices = 0;
  int vertex_element = -1, face_element = -1;
  int x = -1, y = -1, z = -1;  // property indices in the vertex element
  int face_list = -1;          // the vertex-index list of the face element
};

PlyHeader ParsePlyHeader(const std::string& bytes, const MeshBuilder& b) {
  PlyHeader header;
  size_t pos = 0, line_number = 0;
  bool have_format = false, ended = false;
  while (pos < bytes.size()) {
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::string line = bytes.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> t = Tokens(line);
    const std::string where = LineTag(line_number);
    if (line_number == 1) {
      if (t.size() != 1 || t[0] != "ply") {
        b.Fail("cannot read: not a PLY file (first line " + Excerpt(line) +
               ")");
      }
      continue;
    }
    if (t.empty()) continue;
    const std::string& keyword = t[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (t.size() != 3 || t[2] != "1.0") {
        b.Fail("malformed PLY format line " + Excerpt(line) + where);
      }
      if (t[1] == "ascii")
        header.format = PlyFormat::kAscii;
      else if (t[1] == "binary_little_endian")
        header.format = PlyFormat::kLittleEndian;
      else if (t[1] == "binary_big_endian")
        header.format = PlyFormat::kBigEndian;
      else
        b.Fail("unknown PLY format " + Excerpt(t[1]) + where);
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      if (t.size() != 3 || !ParseInteger(t[2], &element.count) ||
          element.count < 0 || element.count > kMaxCount) {
        b.Fail("malformed PLY element line " + Excerpt(line) + where);
      }
      element.name = t[1];
      for (const PlyElement& other : header.elements) {
        if (other.name == element.name) {
          b.Fail("PLY element " + Excerpt(element.name) + " declared twice" +
                 where);
        }
      }
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty())
        b.Fail("PLY property before element" + where);
      PlyProperty property;
      bool ok = false;
      if (t.size() == 5 && t[1] == "list") {
        property.is_list = true;
        ok = ParsePlyType(t[2], &property.count_type) &&
             ParsePlyType(t[3], &property.type) &&
             IsIntegerType(property.count_type);
        property.name = t[4];
      } else if (t.size() == 3) {
        ok = ParsePlyType(t[1], &property.type);
        property.name = t[2];
      }
      if (!ok) b.Fail("malformed PLY property line " + Excerpt(line) + where);
      header.elements.back().properties.push_back(property);
    } else if (keyword == "end_header") {
      if (t.size() != 1) b.Fail("malformed PLY end_header line" + where);
      ended = true;
      break;
    } else {
      b.Fail("unknown PLY header line " + Excerpt(line) + where);
    }
  }
  if (!ended) b.Fail("PLY header has no end_header");
  if (!have_format) b.Fail("PLY header has no format line");
  header.data_offset = std::min(pos, bytes.size());
  header.data_line = line_number + 1;
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.name == "vertex") {
      header.vertex_element = static_cast<int>(e);
      header.num_vertices = element.count;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        int* slot = property.name == "x"   ? &header.x
                    : property.name == "y" ? &header.y
                    : property.name == "z" ? &header.z
                                           : nullptr;
        if (slot == nullptr) continue;
        if (property.is_list || *slot != -1) {
          b.Fail("PLY vertex property '" + property.name +
                 "' is a list or repeated");
        }
        *slot = static_cast<int>(p);
      }
    } else if (element.name == "face") {
      header.face_element = static_cast<int>(e);
      int lists = 0;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        if (!property.is_list) continue;
        ++lists;
        if (property.name == "vertex_indices" ||
            property.name == "vertex_index" || header.face_list == -1) {
          header.face_list = static_cast<int>(p);
        }
      }
      if (header.face_list == -1)
        b.Fail("PLY face element has no list property");
      if (lists > 1 &&
          element.properties[header.face_list].name != "vertex_indices" &&
          element.properties[header.face_list].name != "vertex_index") {
        b.Fail("PLY face element has several lists and none is vertex_indices");
      }
      if (!IsIntegerType(element.properties[header.face_list].type)) {
        b.Fail("PLY face vertex indices have a non-integer type");
      }
    }
  }
  if (header.vertex_element == -1) b.Fail("PLY file has no vertex element");
  if (header.x == -1 || header.y == -1 || header.z == -1) {
    b.Fail("PLY vertex lacks x, y, z");
  }
  if (header.face_element == -1)
    b.Fail("mesh has no faces (no PLY face element)");
  return header;
}

void AddFace(MeshBuilder* b, const std::array<long long, 3>& f, size_t line) {
  b->faces.push_back(f);
  b->face_lines.push_back(line);
}

// One row of a PLY element being read: where each value goes (a vertex
// coordinate, a face's vertex index, or nowhere for other properties).
class PlyRow {
 public:
  PlyRow(const PlyHeader& header, size_t element)
      : header_(header),
        is_vertex_(static_cast<int>(element) == header.vertex_element),
        is_face_(static_cast<int>(element) == header.face_element) {}

  bool IsFaceList(size_t property) const {
    return is_face_ && static_cast<int>(property) == header_.face_list;
  }
  // Value i of property `property`: `integer` for a face index, `value`
  // for a coordinate.
  void Store(size_t property, long long i, long long integer, double value) {
    if (IsFaceList(property)) {
      face_[i] = integer;
    } else {
      StoreCoordinate(property, value);
    }
  }
  void StoreCoordinate(size_t property, double value) {
    if (!is_vertex_) return;
    const int p = static_cast<int>(property);
    if (p == header_.x) point_[0] = value;
    if (p == header_.y) point_[1] = value;
    if (p == header_.z) point_[2] = value;
  }
  // Adds the row's vertex or face to the mesh and resets the row.
  void Finish(MeshBuilder* b, size_t line) {
    if (is_vertex_) b->points.push_back(point_);
    if (is_face_) AddFace(b, face_, line);
    point_ = {0, 0, 0};
    face_ = {0, 0, 0};
  }

 private:
  const PlyHeader& header_;
  const bool is_vertex_, is_face_;
  std::array<double, 3> point_{0, 0, 0};
  std::array<long long, 3> face_{0, 0, 0};
};

void CheckTriangleCount(const MeshBuilder& b, long long r, long long n,
                        size_t line) {
  if (n != 3) {
    b.Fail("face " + std::to_string(r) + " has " + std::to_string(n) +
           " vertices; only triangle meshes are supported" +
           (line ? LineTag(line) : ""));
  }
}

void ReadAsciiPlyData(const std::string& bytes, const PlyHeader& header,
                      MeshBuilder* b) {
  const std::vector<std::string> lines =
      SplitLines(bytes.substr(header.data_offset));
  size_t next = 0;  // index into lines
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    PlyRow row(header, e);
    for (long long r = 0; r < element.count; ++r) {
      while (next < lines.size() && Tokens(lines[next]).empty()) ++next;
      if (next >= lines.size()) {
        b->Fail("PLY file ends early in element " + Excerpt(element.name) +
                " (" + std::to_string(r) + " of " +
                std::to_string(element.count) + " read)");
      }
      const size_t line = header.data_line + next;
      const std::vector<std::string> t = Tokens(lines[next++]);
      const std::string what =
          element.name == "vertex" || element.name == "face"
              ? element.name + " " + std::to_string(r)
              : "element " + Excerpt(element.name) + " " + std::to_string(r);
      size_t k = 0;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        long long n = 1;
        if (property.is_list) {
          if (k >= t.size())
            b->Fail(what + " has too few values" + LineTag(line));
          if (!ParseInteger(t[k], &n) || n < 0) {
            b->Fail(what + " has a malformed list count " + Excerpt(t[k]) +
                    LineTag(line));
          }
          ++k;
          if (row.IsFaceList(p)) CheckTriangleCount(*b, r, n, line);
        }
        for (long long i = 0; i < n; ++i, ++k) {
          if (k >= t.size())
            b->Fail(what + " has too few values" + LineTag(line));
          if (IsIntegerType(property.type)) {
            long long value = 0;
            if (!ParseInteger(t[k], &value)) {
              b->Fail(what + " has a non-integer value " + Excerpt(t[k]) +
                      " for " + Excerpt(property.name) + LineTag(line));
            }
            row.Store(p, i, value, static_cast<double>(value));
          } else {
            double value = 0;
            if (!ParseDouble(t[k], &value)) {
              b->Fail(what + " has a malformed number " + Excerpt(t[k]) +
                      LineTag(line));
            }
            row.StoreCoordinate(p, value);
          }
        }
      }
      if (k != t.size()) {
        b->Fail(what + " has " + std::to_string(t.size() - k) +
                " extra values" + LineTag(line));
      }
      row.Finish(b, line);
    }
  }
  while (next < lines.size() && Tokens(lines[next]).empty()) ++next;
  if (next < lines.size()) {
    b->Fail("extra data after the last PLY element: " + Excerpt(lines[next]) +
            LineTag(header.data_line + next));
  }
}

// Reads binary scalars of one byte order.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& bytes, size_t pos, bool big_endian,
               const MeshBuilder& b)
      : bytes_(bytes), pos_(pos), big_endian_(big_endian), b_(b) {}

  size_t remaining() const { return bytes_.size() - pos_; }

  // Reads a scalar of `type`; `integer` is set if it is an integer type.
  double Read(PlyType type, const std::string& what, long long* integer) {
    const int size = TypeSize(type);
    if (remaining() < static_cast<size_t>(size)) {
      b_.Fail("PLY file ends early in " + what);
    }
    unsigned char raw[8];
    for (int i = 0; i < size; ++i) {
      raw[big_endian_ ? size - 1 - i : i] =
          static_cast<unsigned char>(bytes_[pos_ + i]);
    }
    pos_ += size;
    uint64_t u = 0;
    for (int i = size - 1; i >= 0; --i) u = (u << 8) | raw[i];
    if (type == PlyType::kFloat32) {
      float f;
      const uint32_t u32 = static_cast<uint32_t>(u);
      std::memcpy(&f, &u32, 4);
      return f;
    }
    if (type == PlyType::kFloat64) {
      double d;
      std::memcpy(&d, &u, 8);
      return d;
    }
    // An integer of `size` (at most 4) bytes, two's complement if signed.
    long long value = static_cast<long long>(u);
    if (IsSignedIntegerType(type) && (u >> (8 * size - 1)) != 0) {
      value -= 1LL << (8 * size);
    }
    if (integer) *integer = value;
    return static_cast<double>(value);
  }

 private:
  const std::string& bytes_;
  size_t pos_;
  bool big_endian_;
  const MeshBuilder& b_;
};

void ReadBinaryPlyData(const std::string& bytes, const PlyHeader& header,
                       MeshBuilder* b) {
  BinaryCursor in(bytes, header.data_offset,
                  header.format == PlyFormat::kBigEndian, *b);
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    PlyRow row(header, e);
    for (long long r = 0; r < element.count; ++r) {
      const std::string what = "element " + Excerpt(element.name) + " (" +
                               std::to_string(r) + " of " +
                               std::to_string(element.count) + " read)";
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        long long n = 1;
        if (property.is_list) {
          in.Read(property.count_type, what, &n);
          if (n < 0) {
            b->Fail(element.name + " " + std::to_string(r) +
                    " has a negative list count");
          }
          if (row.IsFaceList(p)) CheckTriangleCount(*b, r, n, 0);
          if (static_cast<size_t>(n) * TypeSize(property.type) >
              in.remaining()) {
            b->Fail("PLY file ends early in " + what);
          }
        }
        for (long long i = 0; i < n; ++i) {
          long long integer = 0;
          const double value = in.Read(property.type, what, &integer);
          row.Store(p, i, integer, value);
        }
      }
      row.Finish(b, 0);
    }
  }
  if (in.remaining() != 0) {
    b->Fail(std::to_string(in.remaining()) +
            " bytes of extra data after the last PLY element");
  }
}

Mesh ReadPly(const std::string& bytes, MeshBuilder* b) {
  const PlyHeader header = ParsePlyHeader(bytes, *b);
  if (header.format == PlyFormat::kAscii) {
    ReadAsciiPlyData(bytes, header, b);
  } else {
    ReadBinaryPlyData(bytes, header, b);
  }
  b->CheckIndices(header.num_vertices, 0);
  return b->Build();
}

// ---------------------------------------------------------------- OBJ ----

Mesh ReadObj(const std::string& bytes, MeshBuilder* b) {
  const std::vector<std::string> lines = SplitLines(bytes);
  for (size_t l = 0; l < lines.size(); ++l) {
    std::string line = lines[l];
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> t = Tokens(line);
    if (t.empty()) continue;
    const std::string where = LineTag(l + 1);
    const std::string& keyword = t[0];
    if (keyword == "v") {
      // x y z, optionally w or an r g b colour.
      if (t.size() != 4 && t.size() != 5 && t.size() != 7) {
        b->Fail("vertex " + std::to_string(b->points.size()) + " has " +
                std::to_string(t.size() - 1) +
                " values (expected x y z [w | r g b])" + where);
      }
      std::array<double, 3> p{0, 0, 0};
      for (size_t k = 1; k < t.size(); ++k) {
        double value = 0;
        if (!ParseDouble(t[k], &value)) {
          b->Fail("vertex " + std::to_string(b->points.size()) +
                  " has a malformed number " + Excerpt(t[k]) + where);
        }
        if (k <= 3) p[k - 1] = value;
      }
      b->points.push_back(p);
    } else if (keyword == "f") {
      const long long r = static_cast<long long>(b->faces.size());
      CheckTriangleCount(*b, r, static_cast<long long>(t.size()) - 1, l + 1);
      std::array<long long, 3> f{0, 0, 0};
      for (int c = 0; c < 3; ++c) {
        // v, v/vt, v//vn or v/vt/vn: the vertex index is the first part.
        const std::string& token = t[c + 1];
        const std::string index = token.substr(0, token.find('/'));
        long long value = 0;
        if (!ParseInteger(index, &value)) {
          b->Fail("face " + std::to_string(r) +
                  " has a non-integer vertex index " + Excerpt(token) + where);
        }
        if (value == 0) {
          b->Fail("face " + std::to_string(r) +
                  " has vertex index 0 (OBJ indices start at 1)" + where);
        }
        // Negative indices count back from the last vertex read so far.
        f[c] = value > 0 ? value - 1
                         : static_cast<long long>(b->points.size()) + value;
        if (value < 0 && f[c] < 0) {
          b->Fail("face " + std::to_string(r) + " has vertex index " +
                  std::to_string(value) + " before vertex " +
                  std::to_string(-value) + " is defined" + where);
        }
      }
      b->faces.push_back(f);
      b->face_lines.push_back(l + 1);
    } else if (keyword == "vt" || keyword == "vn" || keyword == "vp" ||
               keyword == "g" || keyword == "o" || keyword == "s" ||
               keyword == "usemtl" || keyword == "mtllib") {
      continue;  // texture, normals, groups, materials: not used
    } else {
      b->Fail("unsupported OBJ statement " + Excerpt(keyword) +
              " (a mesh has only v and f lines)" + where);
    }
  }
  b->CheckIndices(static_cast<long long>(b->points.size()), 1);
  return b->Build();
}

// ---------------------------------------------------------------- OFF ----

Mesh ReadOff(const std::string& bytes, MeshBuilder* b) {
  const std::vector<std::string> lines = SplitLines(bytes);
  // Non-empty lines without comments, with their line numbers.
  std::vector<std::pair<std::vector<std::string>, size_t>> rows;
  for (size_t l = 0; l < lines.size(); ++l) {
    std::string line = lines[l];
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::vector<std::string> t = Tokens(line);
    if (!t.empty()) rows.emplace_back(std::move(t), l + 1);
  }
  size_t next = 0;
  if (rows.empty() || rows[0].first[0] != "OFF") {
    b->Fail("cannot read: not an OFF file (no OFF header" +
            std::string(rows.empty()
                            ? ")"
                            : ", first line " +
                                  Excerpt(lines[rows[0].second - 1]) + ")"));
  }
  std::vector<std::string> counts(rows[0].first.begin() + 1,
                                  rows[0].first.end());
  size_t counts_line = rows[0].second;
  ++next;
  if (counts.empty()) {
    if (next >= rows.size()) b->Fail("OFF file has no vertex and face counts");
    counts = rows[next].first;
    counts_line = rows[next].second;
    ++next;
  }
  long long nv = 0, nf = 0, ne = 0;
  if (counts.size() != 3 || !ParseInteger(counts[0], &nv) ||
      !ParseInteger(counts[1], &nf) || !ParseInteger(counts[2], &ne) ||
      nv < 0 || nf < 0 || ne < 0 || nv > kMaxCount || nf > kMaxCount) {
    b->Fail("malformed OFF counts line (expected 'vertices faces edges')" +
            LineTag(counts_line));
  }
  for (long long i = 0; i < nv; ++i, ++next) {
    if (next >= rows.size()) {
      b->Fail("OFF file ends early at vertex " + std::to_string(i) + " of " +
              std::to_string(nv));
    }
    const auto& [t, line] = rows[next];
    if (t.size() != 3) {
      b->Fail("vertex " + std::to_string(i) + " has " +
              std::to_string(t.size()) + " values, expected 3" + LineTag(line));
    }
    std::array<double, 3> p{0, 0, 0};
    for (int c = 0; c < 3; ++c) {
      if (!ParseDouble(t[c], &p[c])) {
        b->Fail("vertex " + std::to_string(i) + " has a malformed number " +
                Excerpt(t[c]) + LineTag(line));
      }
    }
    b->points.push_back(p);
  }
  for (long long r = 0; r < nf; ++r, ++next) {
    if (next >= rows.size()) {
      b->Fail("OFF file ends early at face " + std::to_string(r) + " of " +
              std::to_string(nf));
    }
    const auto& [t, line] = rows[next];
    long long n = 0;
    if (!ParseInteger(t[0], &n)) {
      b->Fail("face " + std::to_string(r) + " has a malformed vertex count " +
              Excerpt(t[0]) + LineTag(line));
    }
    CheckTriangleCount(*b, r, n, line);
    // Three indices, optionally followed by an r g b [a] colour.
    if (t.size() != 4 && t.size() != 7 && t.size() != 8) {
      b->Fail("face " + std::to_string(r) + " has " +
              std::to_string(t.size() - 1) +
              " values after the count (expected 3 indices [and a colour])" +
              LineTag(line));
    }
    std::array<long long, 3> f{0, 0, 0};
    for (int c = 0; c < 3; ++c) {
      if (!ParseInteger(t[c + 1], &f[c])) {
        b->Fail("face " + std::to_string(r) +
                " has a non-integer vertex index " + Excerpt(t[c + 1]) +
                LineTag(line));
      }
    }
    for (size_t k = 4; k < t.size(); ++k) {
      double colour = 0;
      if (!ParseDouble(t[k], &colour)) {
        b->Fail("face " + std::to_string(r) + " has a malformed colour " +
                Excerpt(t[k]) + LineTag(line));
      }
    }
    b->faces.push_back(f);
    b->face_lines.push_back(line);
  }
  if (next < rows.size()) {
    b->Fail("extra data after the " + std::to_string(nf) + " faces: " +
            Excerpt(lines[rows[next].second - 1]) + LineTag(rows[next].second));
  }
  b->CheckIndices(nv, 0);
  return b->Build();
}

}  // namespace

Mesh ReadMesh(const std::string& path) {
  const std::string ext = Extension(path);
  if (ext != "ply" && ext != "obj" && ext != "off") {
    std::error_code error;
    if (!std::filesystem::exists(path, error)) {
      throw InputError("cannot open mesh file " + path);
    }
    throw InputError("unsupported mesh format '" + ext + "' of " + path +
                     " (use .ply, .obj or .off)");
  }
  const std::string bytes = ReadFileBytes(path, "mesh file");
  MeshBuilder builder;
  builder.path = path;
  const Mesh mesh = ext == "ply"   ? ReadPly(bytes, &builder)
                    : ext == "obj" ? ReadObj(bytes, &builder)
                                   : ReadOff(bytes, &builder);
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
  const std::string bytes = ReadFileBytes(path, "mask file");
  if (bytes.find('\0') != std::string::npos) {
    throw InputError(path + ": not a text file (it contains NUL bytes)");
  }
  const std::vector<std::string> lines = SplitLines(bytes);
  std::vector<int> mask;
  for (size_t l = 0; l < lines.size(); ++l) {
    std::string line = lines[l];
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::string where = path + ":" + std::to_string(l + 1) + ": ";
    for (const std::string& token : Tokens(line)) {
      long long value = 0;
      if (!ParseInteger(token, &value)) {
        throw InputError(where + "not a vertex index: " + Excerpt(token));
      }
      if (value < 0 || value >= num_vertices) {
        throw InputError(where + "vertex index " + Excerpt(token) +
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
