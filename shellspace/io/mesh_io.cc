#include "shellspace/io/mesh_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <string_view>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/input_file.h"

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
std::string Excerpt(std::string_view text, size_t max = 24) {
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

// The lines of a text, one at a time, split at '\n' with a trailing '\r'
// removed, without copying them (a file of blank lines costs no memory per
// line); polls the stop request every 4096 lines.
class LineCursor {
 public:
  // `text` starts at line `first_line` (1-based) of the file `path`.
  LineCursor(std::string_view text, size_t first_line, const std::string& path)
      : text_(text), number_(first_line - 1), ticker_(path) {}

  // The next line, or false at the end of the text.
  bool Next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    ticker_.Tick();
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    *line = text_.substr(pos_, end - pos_);
    if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  // The 1-based file line number of the line Next returned last.
  size_t number() const { return number_; }
  // Bytes returned so far (with their line breaks).
  size_t consumed() const { return std::min(pos_, text_.size()); }
  // Bytes not yet returned.
  size_t remaining() const {
    return pos_ >= text_.size() ? 0 : text_.size() - pos_;
  }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  size_t number_;
  ReadStopTicker ticker_;
};

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Whitespace-separated tokens of a line (space, tab, \r, \v, \f) into
// `tokens` (views into `line`).
void Tokenize(std::string_view line, std::vector<std::string_view>* tokens) {
  tokens->clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    size_t j = i;
    while (j < line.size() && !IsSpace(line[j])) ++j;
    if (j > i) tokens->push_back(line.substr(i, j - i));
    i = j;
  }
}

// `line` up to its first '#'.
std::string_view WithoutComment(std::string_view line) {
  const size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

bool ParseDouble(std::string_view token, double* value) {
  if (token.empty()) return false;
  const std::string text(token);  // strtod needs a terminated string
  char* end = nullptr;
  // strtod, unlike operator>>, parses "nan" and "inf": they are reported as
  // non-finite coordinates by the validation.
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// A decimal integer (optional sign, digits only).
bool ParseInteger(std::string_view token, long long* value) {
  if (token.empty()) return false;
  size_t i = token[0] == '-' || token[0] == '+' ? 1 : 0;
  if (i == token.size() || token.size() > 19) return false;
  long long magnitude = 0;
  for (size_t k = i; k < token.size(); ++k) {
    if (token[k] < '0' || token[k] > '9') return false;
    // At most 18 digits (19 characters with the sign) or 19 digits below
    // 10^19: checked against overflow of the 63-bit magnitude.
    const int digit = token[k] - '0';
    if (magnitude > (std::numeric_limits<long long>::max() - digit) / 10) {
      magnitude = std::numeric_limits<long long>::max();
      break;
    }
    magnitude = magnitude * 10 + digit;
  }
  *value = token[0] == '-' ? -magnitude : magnitude;
  return true;
}

std::string LineTag(size_t line) {
  return " (line " + std::to_string(line) + ")";
}

// The largest element count a file may declare (indices are int).
constexpr long long kMaxCount = 2147483647;

// The longest header read (PLY: up to end_header; OFF: up to the counts,
// comments included): 1 MiB. Real headers take a few hundred bytes; a
// header of millions of comment or element lines is refused after its
// first MiB instead of being scanned whole.
constexpr size_t kMaxHeaderBytes = size_t{1} << 20;

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

  // Reserves room for counts a header declared, once they were checked
  // against the file size.
  void Reserve(long long num_points, long long num_faces) {
    points.reserve(static_cast<size_t>(num_points));
    faces.reserve(static_cast<size_t>(num_faces));
    face_lines.reserve(static_cast<size_t>(num_faces));
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
    if (points.size() > static_cast<size_t>(kMaxCount)) {
      Fail("more than " + std::to_string(kMaxCount) + " vertices");
    }
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

// Checks that `rows` rows of at least `row_bytes` bytes each fit in the
// `*available` bytes left of the file's `data_bytes` bytes of data, before
// any of them is read or stored, and takes them off `*available`. The error
// is "`prefix`: the header declares `rows` `noun` of at least ...".
void CheckRowsFit(const MeshBuilder& b, const std::string& prefix,
                  long long rows, const std::string& noun, uint64_t row_bytes,
                  uint64_t* available, uint64_t data_bytes) {
  if (rows <= 0) return;
  if (row_bytes == 0 || static_cast<uint64_t>(rows) > *available / row_bytes) {
    b.Fail(prefix + ": the header declares " + std::to_string(rows) + " " +
           noun + " of at least " + std::to_string(row_bytes) +
           " bytes, more than the " + std::to_string(data_bytes) +
           " bytes of data hold");
  }
  *available -= static_cast<uint64_t>(rows) * row_bytes;
}

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
// The fewest bytes a row of `element` takes: binary, the sizes of its
// scalars, list counts and the three indices of the face list; ASCII, two
// bytes (a digit and a separator) per such value.
uint64_t MinRowBytes(const PlyElement& element, bool is_face, int face_list,
                     bool binary) {
  uint64_t bytes = 0;
  for (size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    const bool triangle = is_face && static_cast<int>(p) == face_list;
    if (binary) {
      bytes += property.is_list
                   ? TypeSize(property.count_type) +
                         (triangle ? 3 * TypeSize(property.type) : 0)
                   : TypeSize(property.type);
    } else {
      bytes += 2 * (property.is_list && triangle ? 4 : 1);
    }
  }
  return bytes;
}

// The header of a PLY file whose first bytes are `bytes` (the whole file, or
// a prefix of at least kMaxHeaderBytes + 1 bytes: the same result, as no
// line past that is parsed) and whose size is `file_size`.
PlyHeader ParsePlyHeader(const std::string& bytes, uint64_t file_size,
                         const MeshBuilder& b) {
  PlyHeader header;
  LineCursor lines(bytes, 1, b.path);
  std::string_view line;
  std::vector<std::string_view> t;
  std::set<std::string, std::less<>> element_names;
  bool have_format = false, ended = false;
  while (lines.Next(&line)) {
    if (lines.consumed() > kMaxHeaderBytes) {
      b.Fail("PLY header longer than " + std::to_string(kMaxHeaderBytes) +
             " bytes (no end_header before line " +
             std::to_string(lines.number()) + ")");
    }
    Tokenize(line, &t);
    const auto where = [&lines] { return LineTag(lines.number()); };
    if (lines.number() == 1) {
      if (t.size() != 1 || t[0] != "ply") {
        b.Fail("cannot read: not a PLY file (first line " + Excerpt(line) +
               ")");
      }
      continue;
    }
    if (t.empty()) continue;
    const std::string_view keyword = t[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (t.size() != 3 || t[2] != "1.0") {
        b.Fail("malformed PLY format line " + Excerpt(line) + where());
      }
      if (t[1] == "ascii")
        header.format = PlyFormat::kAscii;
      else if (t[1] == "binary_little_endian")
        header.format = PlyFormat::kLittleEndian;
      else if (t[1] == "binary_big_endian")
        header.format = PlyFormat::kBigEndian;
      else
        b.Fail("unknown PLY format " + Excerpt(t[1]) + where());
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      if (t.size() != 3 || !ParseInteger(t[2], &element.count) ||
          element.count < 0 || element.count > kMaxCount) {
        b.Fail("malformed PLY element line " + Excerpt(line) + where());
      }
      element.name = std::string(t[1]);
      if (!element_names.insert(element.name).second) {
        b.Fail("PLY element " + Excerpt(element.name) + " declared twice" +
               where());
      }
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty())
        b.Fail("PLY property before element" + where());
      PlyProperty property;
      bool ok = false;
      if (t.size() == 5 && t[1] == "list") {
        property.is_list = true;
        ok = ParsePlyType(std::string(t[2]), &property.count_type) &&
             ParsePlyType(std::string(t[3]), &property.type) &&
             IsIntegerType(property.count_type);
        property.name = std::string(t[4]);
      } else if (t.size() == 3) {
        ok = ParsePlyType(std::string(t[1]), &property.type);
        property.name = std::string(t[2]);
      }
      if (!ok) b.Fail("malformed PLY property line " + Excerpt(line) + where());
      header.elements.back().properties.push_back(property);
    } else if (keyword == "end_header") {
      if (t.size() != 1) b.Fail("malformed PLY end_header line" + where());
      ended = true;
      break;
    } else {
      b.Fail("unknown PLY header line " + Excerpt(line) + where());
    }
  }
  if (!ended) b.Fail("PLY header has no end_header");
  if (!have_format) b.Fail("PLY header has no format line");
  header.data_offset = bytes.size() - lines.remaining();
  header.data_line = lines.number() + 1;
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
  // Every declared row must fit in the data after the header, checked before
  // any row is read or stored: a header cannot make the reader loop over,
  // or allocate, rows the file does not hold.
  const bool binary = header.format != PlyFormat::kAscii;
  const uint64_t data_bytes = file_size - header.data_offset;
  uint64_t available = data_bytes + (binary ? 0 : 1);  // last line break
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.count > 0 && element.properties.empty()) {
      b.Fail("PLY element " + Excerpt(element.name) + " declares " +
             std::to_string(element.count) + " rows but has no properties");
    }
    CheckRowsFit(
        b, "PLY file ends early in element " + Excerpt(element.name),
        element.count, element.count == 1 ? "row" : "rows",
        MinRowBytes(element, static_cast<int>(e) == header.face_element,
                    header.face_list, binary),
        &available, data_bytes);
  }
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

// The name of row `r` of element `e` in errors: "vertex 3", "face 7",
// "element 'edge' 0".
std::string RowName(const PlyElement& element, long long r) {
  return element.name == "vertex" || element.name == "face"
             ? element.name + " " + std::to_string(r)
             : "element " + Excerpt(element.name) + " " + std::to_string(r);
}

void ReadAsciiPlyData(const std::string& bytes, const PlyHeader& header,
                      MeshBuilder* b) {
  LineCursor lines(std::string_view(bytes).substr(header.data_offset),
                   header.data_line, b->path);
  std::string_view text;
  std::vector<std::string_view> t;
  // The next line with a value, in `t`; false at the end of the file.
  const auto next_row = [&] {
    while (lines.Next(&text)) {
      Tokenize(text, &t);
      if (!t.empty()) return true;
    }
    return false;
  };
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    PlyRow row(header, e);
    for (long long r = 0; r < element.count; ++r) {
      if (!next_row()) {
        b->Fail("PLY file ends early in element " + Excerpt(element.name) +
                " (" + std::to_string(r) + " of " +
                std::to_string(element.count) + " read)");
      }
      const size_t line = lines.number();
      size_t k = 0;
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        long long n = 1;
        if (property.is_list) {
          if (k >= t.size()) {
            b->Fail(RowName(element, r) + " has too few values" +
                    LineTag(line));
          }
          if (!ParseInteger(t[k], &n) || n < 0) {
            b->Fail(RowName(element, r) + " has a malformed list count " +
                    Excerpt(t[k]) + LineTag(line));
          }
          ++k;
          if (row.IsFaceList(p)) CheckTriangleCount(*b, r, n, line);
          if (static_cast<unsigned long long>(n) > t.size() - k) {
            b->Fail(RowName(element, r) + " has too few values" +
                    LineTag(line));
          }
        }
        for (long long i = 0; i < n; ++i, ++k) {
          if (k >= t.size()) {
            b->Fail(RowName(element, r) + " has too few values" +
                    LineTag(line));
          }
          if (IsIntegerType(property.type)) {
            long long value = 0;
            if (!ParseInteger(t[k], &value)) {
              b->Fail(RowName(element, r) + " has a non-integer value " +
                      Excerpt(t[k]) + " for " + Excerpt(property.name) +
                      LineTag(line));
            }
            row.Store(p, i, value, static_cast<double>(value));
          } else {
            double value = 0;
            if (!ParseDouble(t[k], &value)) {
              b->Fail(RowName(element, r) + " has a malformed number " +
                      Excerpt(t[k]) + LineTag(line));
            }
            row.StoreCoordinate(p, value);
          }
        }
      }
      if (k != t.size()) {
        b->Fail(RowName(element, r) + " has " + std::to_string(t.size() - k) +
                " extra values" + LineTag(line));
      }
      row.Finish(b, line);
    }
  }
  if (next_row()) {
    b->Fail("extra data after the last PLY element: " + Excerpt(text) +
            LineTag(lines.number()));
  }
}

// Reads binary scalars of one byte order; polls the stop request every
// 4096 values.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& bytes, size_t pos, bool big_endian,
               const std::string& path)
      : bytes_(bytes), pos_(pos), big_endian_(big_endian), ticker_(path) {}

  size_t remaining() const { return bytes_.size() - pos_; }

  // Reads a scalar of `type`, false if the data ends first; `integer` is
  // set if it is an integer type.
  bool Read(PlyType type, double* value, long long* integer) {
    ticker_.Tick();
    const int size = TypeSize(type);
    if (remaining() < static_cast<size_t>(size)) return false;
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
      *value = f;
      return true;
    }
    if (type == PlyType::kFloat64) {
      std::memcpy(value, &u, 8);
      return true;
    }
    // An integer of `size` (at most 4) bytes, two's complement if signed.
    long long v = static_cast<long long>(u);
    if (IsSignedIntegerType(type) && (u >> (8 * size - 1)) != 0) {
      v -= 1LL << (8 * size);
    }
    *integer = v;
    *value = static_cast<double>(v);
    return true;
  }

 private:
  const std::string& bytes_;
  size_t pos_;
  bool big_endian_;
  ReadStopTicker ticker_;
};

void ReadBinaryPlyData(const std::string& bytes, const PlyHeader& header,
                       MeshBuilder* b) {
  BinaryCursor in(bytes, header.data_offset,
                  header.format == PlyFormat::kBigEndian, b->path);
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    PlyRow row(header, e);
    const auto ends_early = [&](long long r) {
      b->Fail("PLY file ends early in element " + Excerpt(element.name) + " (" +
              std::to_string(r) + " of " + std::to_string(element.count) +
              " read)");
    };
    for (long long r = 0; r < element.count; ++r) {
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        long long n = 1;
        double value = 0;
        if (property.is_list) {
          if (!in.Read(property.count_type, &value, &n)) ends_early(r);
          if (n < 0) {
            b->Fail(element.name + " " + std::to_string(r) +
                    " has a negative list count");
          }
          if (row.IsFaceList(p)) CheckTriangleCount(*b, r, n, 0);
          if (static_cast<size_t>(n) * TypeSize(property.type) >
              in.remaining()) {
            ends_early(r);
          }
        }
        for (long long i = 0; i < n; ++i) {
          long long integer = 0;
          if (!in.Read(property.type, &value, &integer)) ends_early(r);
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
  const PlyHeader header = ParsePlyHeader(bytes, bytes.size(), *b);
  if (header.vertex_element >= 0 && header.face_element >= 0) {
    b->Reserve(header.elements[header.vertex_element].count,
               header.elements[header.face_element].count);
  }
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
  LineCursor lines(bytes, 1, b->path);
  std::string_view text;
  std::vector<std::string_view> t;
  while (lines.Next(&text)) {
    Tokenize(WithoutComment(text), &t);
    if (t.empty()) continue;
    const size_t l = lines.number();
    const auto where = [l] { return LineTag(l); };
    const std::string_view keyword = t[0];
    if (keyword == "v") {
      // x y z, optionally w or an r g b colour.
      if (t.size() != 4 && t.size() != 5 && t.size() != 7) {
        b->Fail("vertex " + std::to_string(b->points.size()) + " has " +
                std::to_string(t.size() - 1) +
                " values (expected x y z [w | r g b])" + where());
      }
      std::array<double, 3> p{0, 0, 0};
      for (size_t k = 1; k < t.size(); ++k) {
        double value = 0;
        if (!ParseDouble(t[k], &value)) {
          b->Fail("vertex " + std::to_string(b->points.size()) +
                  " has a malformed number " + Excerpt(t[k]) + where());
        }
        if (k <= 3) p[k - 1] = value;
      }
      b->points.push_back(p);
    } else if (keyword == "f") {
      const long long r = static_cast<long long>(b->faces.size());
      CheckTriangleCount(*b, r, static_cast<long long>(t.size()) - 1, l);
      std::array<long long, 3> f{0, 0, 0};
      for (int c = 0; c < 3; ++c) {
        // v, v/vt, v//vn or v/vt/vn: the vertex index is the first part.
        const std::string_view token = t[c + 1];
        const std::string_view index = token.substr(0, token.find('/'));
        long long value = 0;
        if (!ParseInteger(index, &value)) {
          b->Fail("face " + std::to_string(r) +
                  " has a non-integer vertex index " + Excerpt(token) +
                  where());
        }
        if (value == 0) {
          b->Fail("face " + std::to_string(r) +
                  " has vertex index 0 (OBJ indices start at 1)" + where());
        }
        // Negative indices count back from the last vertex read so far.
        f[c] = value > 0 ? value - 1
                         : static_cast<long long>(b->points.size()) + value;
        if (value < 0 && f[c] < 0) {
          b->Fail("face " + std::to_string(r) + " has vertex index " +
                  std::to_string(value) + " before vertex " +
                  std::to_string(-value) + " is defined" + where());
        }
      }
      b->faces.push_back(f);
      b->face_lines.push_back(l);
    } else if (keyword == "vt" || keyword == "vn" || keyword == "vp" ||
               keyword == "g" || keyword == "o" || keyword == "s" ||
               keyword == "usemtl" || keyword == "mtllib") {
      continue;  // texture, normals, groups, materials: not used
    } else {
      b->Fail("unsupported OBJ statement " + Excerpt(keyword) +
              " (a mesh has only v and f lines)" + where());
    }
  }
  b->CheckIndices(static_cast<long long>(b->points.size()), 1);
  return b->Build();
}

// ---------------------------------------------------------------- OFF ----

// The header keyword of an OFF file, [ST][C][N][4][n]OFF (Geomview's OFF
// format): which optional columns each vertex line has after x y z.
struct OffKeyword {
  bool texture = false;      // ST: s t
  bool colour = false;       // C: r g b [a]
  bool normal = false;       // N: nx ny nz
  bool homogeneous = false;  // 4: x y z w
  bool dimension = false;    // n: the vertex dimension is declared (refused)
};

bool ParseOffKeyword(std::string_view word, OffKeyword* k) {
  const auto take = [&word](std::string_view prefix) {
    if (word.substr(0, prefix.size()) != prefix) return false;
    word.remove_prefix(prefix.size());
    return true;
  };
  k->texture = take("ST");
  k->colour = take("C");
  k->normal = take("N");
  k->homogeneous = take("4");
  k->dimension = take("n");
  return word == "OFF";
}

// Reads the lines of an OFF file that hold values (comments and blank lines
// skipped): Next fills `t` with the tokens of the next one.
class OffRows {
 public:
  OffRows(const std::string& bytes, const MeshBuilder& b)
      : lines_(bytes, 1, b.path), b_(b) {}
  // The header (keyword and counts) was read: no limit from here on.
  void EndHeader() { in_header_ = false; }
  bool Next() {
    std::string_view text;
    while (lines_.Next(&text)) {
      if (in_header_ && lines_.consumed() > kMaxHeaderBytes) {
        b_.Fail("OFF header longer than " + std::to_string(kMaxHeaderBytes) +
                " bytes (no vertex and face counts before line " +
                std::to_string(lines_.number()) + ")");
      }
      Tokenize(WithoutComment(text), &t);
      if (!t.empty()) {
        raw = text;
        return true;
      }
    }
    return false;
  }
  size_t line() const { return lines_.number(); }
  size_t consumed() const { return lines_.consumed(); }

  std::vector<std::string_view> t;  // tokens of the current line
  std::string_view raw;             // the current line as it is

 private:
  LineCursor lines_;
  const MeshBuilder& b_;
  bool in_header_ = true;
};

// What the header of an OFF file declares.
struct OffHeader {
  OffKeyword kind;
  std::string keyword;
  long long nv = 0, nf = 0;
};

// Reads the header (keyword and counts) of `rows`, an OFF file of
// `file_size` bytes (`rows` may hold a prefix of at least kMaxHeaderBytes + 1
// bytes: the same result), and checks the counts against the file size.
OffHeader ParseOffHeader(OffRows& rows, uint64_t file_size,
                         const MeshBuilder* b) {
  OffHeader header;
  OffKeyword& kind = header.kind;
  if (!rows.Next() || !ParseOffKeyword(rows.t[0], &kind)) {
    b->Fail("cannot read: not an OFF file (no OFF header" +
            std::string(rows.t.empty()
                            ? ")"
                            : ", first line " + Excerpt(rows.raw) + ")"));
  }
  const std::string& keyword = header.keyword = std::string(rows.t[0]);
  if (kind.dimension) {
    b->Fail("cannot read " + keyword +
            ": OFF with a declared vertex dimension is not read (a shell's "
            "vertices are 3-D: write OFF)" +
            LineTag(rows.line()));
  }
  std::vector<std::string_view> counts(rows.t.begin() + 1, rows.t.end());
  if (!counts.empty() && counts[0] == "BINARY") {
    b->Fail("cannot read " + keyword +
            " BINARY: binary OFF is not read "
            "(write ASCII OFF or binary PLY)" +
            LineTag(rows.line()));
  }
  size_t counts_line = rows.line();
  if (counts.empty()) {
    if (!rows.Next()) b->Fail("OFF file has no vertex and face counts");
    counts = rows.t;
    counts_line = rows.line();
  }
  long long& nv = header.nv;
  long long& nf = header.nf;
  long long ne = 0;
  if (counts.size() != 3 || !ParseInteger(counts[0], &nv) ||
      !ParseInteger(counts[1], &nf) || !ParseInteger(counts[2], &ne) ||
      nv < 0 || nf < 0 || ne < 0 || nv > kMaxCount || nf > kMaxCount) {
    b->Fail("malformed OFF counts line (expected 'vertices faces edges')" +
            LineTag(counts_line));
  }
  rows.EndHeader();
  // Every declared vertex and face must fit in the rest of the file, checked
  // before any is read or stored: a vertex line takes 6 bytes at least (x y
  // z: two bytes a value; the variant's columns are not counted, so that a
  // line without them is reported as such), a face line 8 (3 i j k).
  const uint64_t data_bytes = file_size - rows.consumed();
  uint64_t available = data_bytes + 1;  // the last line break
  CheckRowsFit(*b, "OFF file ends early", nv, "vertices", 2 * 3, &available,
               data_bytes);
  CheckRowsFit(*b, "OFF file ends early", nf, "faces", 2 * 4, &available,
               data_bytes);
  return header;
}

Mesh ReadOff(const std::string& bytes, MeshBuilder* b) {
  OffRows rows(bytes, *b);
  const OffHeader header = ParseOffHeader(rows, bytes.size(), b);
  const OffKeyword& kind = header.kind;
  const std::string& keyword = header.keyword;
  const long long nv = header.nv, nf = header.nf;
  // The values of a vertex line: x y z [w] [nx ny nz] [r g b [a]] [s t].
  const size_t coordinates = kind.homogeneous ? 4 : 3;
  const size_t before_colour = coordinates + (kind.normal ? 3 : 0);
  const size_t min_values =
      before_colour + (kind.colour ? 3 : 0) + (kind.texture ? 2 : 0);
  const size_t max_values = min_values + (kind.colour ? 1 : 0);
  const std::string expected =
      std::to_string(min_values) +
      (max_values > min_values ? " or " + std::to_string(max_values) : "") +
      (keyword == "OFF" ? "" : " (" + keyword + ")");
  b->Reserve(nv, nf);
  for (long long i = 0; i < nv; ++i) {
    if (!rows.Next()) {
      b->Fail("OFF file ends early at vertex " + std::to_string(i) + " of " +
              std::to_string(nv));
    }
    const std::vector<std::string_view>& t = rows.t;
    if (t.size() != min_values && t.size() != max_values) {
      b->Fail("vertex " + std::to_string(i) + " has " +
              std::to_string(t.size()) + " values, expected " + expected +
              LineTag(rows.line()));
    }
    double values[4] = {0, 0, 0, 1};
    for (size_t c = 0; c < t.size(); ++c) {
      double value = 0;
      if (!ParseDouble(t[c], &value)) {
        b->Fail("vertex " + std::to_string(i) + " has a malformed number " +
                Excerpt(t[c]) + LineTag(rows.line()));
      }
      if (c < coordinates) values[c] = value;
    }
    if (kind.homogeneous) {
      // x y z w is the point (x/w, y/w, z/w).
      if (values[3] == 0 || !std::isfinite(values[3])) {
        b->Fail("vertex " + std::to_string(i) +
                " has the homogeneous coordinate w = " + Excerpt(t[3]) +
                " (a point at infinity)" + LineTag(rows.line()));
      }
      for (int c = 0; c < 3; ++c) values[c] /= values[3];
    }
    b->points.push_back({values[0], values[1], values[2]});
  }
  for (long long r = 0; r < nf; ++r) {
    if (!rows.Next()) {
      b->Fail("OFF file ends early at face " + std::to_string(r) + " of " +
              std::to_string(nf));
    }
    const std::vector<std::string_view>& t = rows.t;
    const size_t line = rows.line();
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
  if (rows.Next()) {
    b->Fail("extra data after the " + std::to_string(nf) +
            " faces: " + Excerpt(rows.raw) + LineTag(rows.line()));
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
  InputFile file(path, "mesh file", kMaxMeshFileBytes);
  MeshBuilder builder;
  builder.path = path;
  if (ext != "obj") {
    // The header first, from the first MiB: one whose counts the file size
    // cannot hold is refused before the rest of the file is read.
    const std::string& prefix = file.Read(kMaxHeaderBytes + 1);
    const uint64_t size =
        std::max<uint64_t>(static_cast<uint64_t>(file.size()), prefix.size());
    if (ext == "ply") {
      ParsePlyHeader(prefix, size, builder);
    } else {
      OffRows rows(prefix, builder);
      ParseOffHeader(rows, size, &builder);
    }
  }
  const std::string bytes = file.ReadAll();
  const Mesh mesh = ext == "ply"   ? ReadPly(bytes, &builder)
                    : ext == "obj" ? ReadObj(bytes, &builder)
                                   : ReadOff(bytes, &builder);
  CheckReadStop(path);
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
  const std::string bytes = ReadInputFile(path, "mask file", kMaxMaskFileBytes);
  if (bytes.find('\0') != std::string::npos) {
    throw InputError(path + ": not a text file (it contains NUL bytes)");
  }
  // One flag per vertex: the mask's memory is bounded by the mesh, however
  // often the file repeats an index.
  std::vector<char> in_mask(static_cast<size_t>(std::max(num_vertices, 0)), 0);
  LineCursor lines(bytes, 1, path);
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
