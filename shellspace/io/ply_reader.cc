// The PLY reader (io/mesh_reading.h): the header, ASCII and binary data.
#include "shellspace/io/mesh_reading.h"

#include <map>
#include <set>

namespace shellspace::mesh_reading {
namespace {

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

// A header's "format" line, tokens `t`, line `number`: sets header->format.
void ReadPlyFormatLine(const std::vector<std::string_view>& t,
                       std::string_view line, size_t number,
                       const MeshBuilder& b, PlyHeader* header) {
  if (t.size() != 3 || t[2] != "1.0") {
    b.Fail("malformed PLY format line " + Excerpt(line) + LineTag(number));
  }
  if (t[1] == "ascii")
    header->format = PlyFormat::kAscii;
  else if (t[1] == "binary_little_endian")
    header->format = PlyFormat::kLittleEndian;
  else if (t[1] == "binary_big_endian")
    header->format = PlyFormat::kBigEndian;
  else
    b.Fail("unknown PLY format " + Excerpt(t[1]) + LineTag(number));
}

// A header's "element" line, tokens `t`, line `number`: appends the element
// to header->elements (its name must not be in `element_names`, which gets
// it).
void ReadPlyElementLine(const std::vector<std::string_view>& t,
                        std::string_view line, size_t number,
                        const MeshBuilder& b,
                        std::set<std::string, std::less<>>* element_names,
                        PlyHeader* header) {
  PlyElement element;
  if (t.size() != 3 || !ParseInteger(t[2], &element.count) ||
      element.count < 0 || element.count > kMaxCount) {
    b.Fail("malformed PLY element line " + Excerpt(line) + LineTag(number));
  }
  element.name = std::string(t[1]);
  if (!element_names->insert(element.name).second) {
    b.Fail("PLY element " + Excerpt(element.name) + " declared twice" +
           LineTag(number));
  }
  header->elements.push_back(element);
}

// A header's "property" line, tokens `t`, line `number`: appends the
// property to the last element.
void ReadPlyPropertyLine(const std::vector<std::string_view>& t,
                         std::string_view line, size_t number,
                         const MeshBuilder& b, PlyHeader* header) {
  if (header->elements.empty())
    b.Fail("PLY property before element" + LineTag(number));
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
  if (!ok) {
    b.Fail("malformed PLY property line " + Excerpt(line) + LineTag(number));
  }
  header->elements.back().properties.push_back(property);
}

// Reads the header's lines, from "ply" through "end_header", into header's
// format and elements; `lines` is left after end_header.
void ReadPlyHeaderLines(LineCursor* lines, const MeshBuilder& b,
                        PlyHeader* header) {
  std::string_view line;
  std::vector<std::string_view> t;
  std::set<std::string, std::less<>> element_names;
  bool have_format = false, ended = false;
  while (lines->Next(&line)) {
    if (lines->consumed() > kMaxHeaderBytes) {
      b.Fail("PLY header longer than " + std::to_string(kMaxHeaderBytes) +
             " bytes (no end_header before line " +
             std::to_string(lines->number()) + ")");
    }
    Tokenize(line, &t);
    const size_t number = lines->number();
    if (number == 1) {
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
      ReadPlyFormatLine(t, line, number, b, header);
      have_format = true;
    } else if (keyword == "element") {
      ReadPlyElementLine(t, line, number, b, &element_names, header);
    } else if (keyword == "property") {
      ReadPlyPropertyLine(t, line, number, b, header);
    } else if (keyword == "end_header") {
      if (t.size() != 1)
        b.Fail("malformed PLY end_header line" + LineTag(number));
      ended = true;
      break;
    } else {
      b.Fail("unknown PLY header line " + Excerpt(line) + LineTag(number));
    }
  }
  if (!ended) b.Fail("PLY header has no end_header");
  if (!have_format) b.Fail("PLY header has no format line");
}

// Element e is the vertex element: records it, its count and which of its
// properties are x, y and z.
void ReadPlyVertexElement(size_t e, const MeshBuilder& b, PlyHeader* header) {
  const PlyElement& element = header->elements[e];
  header->vertex_element = static_cast<int>(e);
  header->num_vertices = element.count;
  for (size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    int* slot = property.name == "x"   ? &header->x
                : property.name == "y" ? &header->y
                : property.name == "z" ? &header->z
                                       : nullptr;
    if (slot == nullptr) continue;
    if (property.is_list || *slot != -1) {
      b.Fail("PLY vertex property '" + property.name +
             "' is a list or repeated");
    }
    *slot = static_cast<int>(p);
  }
}

// Element e is the face element: records it and which of its list
// properties holds the vertex indices.
void ReadPlyFaceElement(size_t e, const MeshBuilder& b, PlyHeader* header) {
  const PlyElement& element = header->elements[e];
  header->face_element = static_cast<int>(e);
  int lists = 0;
  for (size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    if (!property.is_list) continue;
    ++lists;
    if (property.name == "vertex_indices" || property.name == "vertex_index" ||
        header->face_list == -1) {
      header->face_list = static_cast<int>(p);
    }
  }
  if (header->face_list == -1) b.Fail("PLY face element has no list property");
  if (lists > 1 &&
      element.properties[header->face_list].name != "vertex_indices" &&
      element.properties[header->face_list].name != "vertex_index") {
    b.Fail("PLY face element has several lists and none is vertex_indices");
  }
  if (!IsIntegerType(element.properties[header->face_list].type)) {
    b.Fail("PLY face vertex indices have a non-integer type");
  }
}

// Every declared row must fit in the data after the header, checked before
// any row is read or stored: a header cannot make the reader loop over, or
// allocate, rows the file does not hold.
void CheckPlyRowsFit(const PlyHeader& header, uint64_t file_size,
                     const MeshBuilder& b) {
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
}

// The header of a PLY file whose first bytes are `bytes` (the whole file, or
// a prefix of at least kMaxHeaderBytes + 1 bytes: the same result, as no
// line past that is parsed) and whose size is `file_size`.
PlyHeader ParsePlyHeader(const std::string& bytes, uint64_t file_size,
                         const MeshBuilder& b) {
  PlyHeader header;
  LineCursor lines(bytes, 1, b.path, b.stop);
  ReadPlyHeaderLines(&lines, b, &header);
  header.data_offset = bytes.size() - lines.remaining();
  header.data_line = lines.number() + 1;
  for (size_t e = 0; e < header.elements.size(); ++e) {
    if (header.elements[e].name == "vertex") {
      ReadPlyVertexElement(e, b, &header);
    } else if (header.elements[e].name == "face") {
      ReadPlyFaceElement(e, b, &header);
    }
  }
  if (header.vertex_element == -1) b.Fail("PLY file has no vertex element");
  if (header.x == -1 || header.y == -1 || header.z == -1) {
    b.Fail("PLY vertex lacks x, y, z");
  }
  if (header.face_element == -1)
    b.Fail("mesh has no faces (no PLY face element)");
  CheckPlyRowsFit(header, file_size, b);
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
                   header.data_line, b->path, b->stop);
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

// Reads binary scalars of one byte order; asks `stop` every 4096 values.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& bytes, size_t pos, bool big_endian,
               const std::string& path, const StopToken& stop)
      : bytes_(bytes),
        pos_(pos),
        big_endian_(big_endian),
        ticker_(path, stop) {}

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
                  header.format == PlyFormat::kBigEndian, b->path, b->stop);
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

}  // namespace

void CheckPlyHeader(const std::string& prefix, uint64_t file_size,
                    const MeshBuilder& b) {
  ParsePlyHeader(prefix, file_size, b);
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

}  // namespace shellspace::mesh_reading
