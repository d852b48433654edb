// The parts the mesh readers share (io/mesh_io.cc reads through them): the
// lines and tokens of a text without copying, number parsing, the size
// limits, MeshBuilder (the vertices and faces read, checked and built into a
// Mesh) and the check of declared rows against the file size; and the
// readers of the formats, one file each: PLY (ply_reader.cc), OBJ
// (obj_reader.cc), OFF (off_reader.cc). Internal to the io room: ReadMesh
// (io/mesh_io.h) is the interface.
#ifndef SHELLSPACE_IO_MESH_READING_H_
#define SHELLSPACE_IO_MESH_READING_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/input_file.h"

namespace shellspace::mesh_reading {

// At most `max` characters of `text`, quoted, with every byte outside
// printable ASCII written as \xNN, and "..." if cut: what an error message
// may echo of a file's content.
inline std::string Excerpt(std::string_view text, size_t max = 24) {
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
// line); asks `stop` every 4096 lines (`path` and `stop` must outlive the
// cursor).
class LineCursor {
 public:
  // `text` starts at line `first_line` (1-based) of the file `path`.
  LineCursor(std::string_view text, size_t first_line, const std::string& path,
             const StopToken& stop)
      : text_(text), number_(first_line - 1), ticker_(path, stop) {}

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

inline bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Whitespace-separated tokens of a line (space, tab, \r, \v, \f) into
// `tokens` (views into `line`).
inline void Tokenize(std::string_view line,
                     std::vector<std::string_view>* tokens) {
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
inline std::string_view WithoutComment(std::string_view line) {
  const size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

inline bool ParseDouble(std::string_view token, double* value) {
  if (token.empty()) return false;
  const std::string text(token);  // strtod needs a terminated string
  char* end = nullptr;
  // strtod, unlike operator>>, parses "nan" and "inf": they are reported as
  // non-finite coordinates by the validation.
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// A decimal integer (optional sign, digits only).
inline bool ParseInteger(std::string_view token, long long* value) {
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

inline std::string LineTag(size_t line) {
  return " (line " + std::to_string(line) + ")";
}

// The largest element count a file may declare (indices are int).
inline constexpr long long kMaxCount = 2147483647;

// The longest header read (PLY: up to end_header; OFF: up to the counts,
// comments included): 1 MiB. Real headers take a few hundred bytes; a
// header of millions of comment or element lines is refused after its
// first MiB instead of being scanned whole.
inline constexpr size_t kMaxHeaderBytes = size_t{1} << 20;

// Collects vertices and triangles read from a file and checks each face's
// indices against the vertex count on the raw data; `stop` is the reader's
// stop token, asked every few thousand lines or values.
struct MeshBuilder {
  std::string path;
  StopToken stop;
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
inline void CheckRowsFit(const MeshBuilder& b, const std::string& prefix,
                         long long rows, const std::string& noun,
                         uint64_t row_bytes, uint64_t* available,
                         uint64_t data_bytes) {
  if (rows <= 0) return;
  if (row_bytes == 0 || static_cast<uint64_t>(rows) > *available / row_bytes) {
    b.Fail(prefix + ": the header declares " + std::to_string(rows) + " " +
           noun + " of at least " + std::to_string(row_bytes) +
           " bytes, more than the " + std::to_string(data_bytes) +
           " bytes of data hold");
  }
  *available -= static_cast<uint64_t>(rows) * row_bytes;
}

inline void CheckTriangleCount(const MeshBuilder& b, long long r, long long n,
                               size_t line) {
  if (n != 3) {
    b.Fail("face " + std::to_string(r) + " has " + std::to_string(n) +
           " vertices; only triangle meshes are supported" +
           (line ? LineTag(line) : ""));
  }
}

// ------------------------------------------------------------ formats ----

// PLY (ascii, binary_little_endian, binary_big_endian). CheckPlyHeader
// parses and checks the header of a file of `file_size` bytes from its first
// `prefix` bytes (at least kMaxHeaderBytes + 1 of them, or the whole file);
// ReadPly reads the whole file's `bytes` into a mesh.
void CheckPlyHeader(const std::string& prefix, uint64_t file_size,
                    const MeshBuilder& b);
Mesh ReadPly(const std::string& bytes, MeshBuilder* b);

// OBJ (v and f lines).
Mesh ReadObj(const std::string& bytes, MeshBuilder* b);

// OFF and its variants [ST][C][N][4]OFF; CheckOffHeader as CheckPlyHeader.
void CheckOffHeader(const std::string& prefix, uint64_t file_size,
                    MeshBuilder* b);
Mesh ReadOff(const std::string& bytes, MeshBuilder* b);

}  // namespace shellspace::mesh_reading

#endif  // SHELLSPACE_IO_MESH_READING_H_
