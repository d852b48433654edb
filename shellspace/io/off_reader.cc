// The OFF reader (io/mesh_reading.h): OFF and [ST][C][N][4]OFF.
#include "shellspace/io/mesh_reading.h"

namespace shellspace::mesh_reading {
namespace {

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
      : lines_(bytes, 1, b.path, b.stop), b_(b) {}
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

// The values of a vertex line of an OFF file: x y z [w] [nx ny nz]
// [r g b [a]] [s t].
struct OffVertexColumns {
  size_t coordinates = 3;  // x y z [w]
  size_t min_values = 3;   // without a colour's alpha
  size_t max_values = 3;   // with it
  std::string expected;    // the counts for messages, "6 or 7 (COFF)"
};

// The columns of a vertex line that `header`'s keyword declares.
OffVertexColumns VertexColumnsOf(const OffHeader& header) {
  const OffKeyword& kind = header.kind;
  const std::string& keyword = header.keyword;
  OffVertexColumns columns;
  columns.coordinates = kind.homogeneous ? 4 : 3;
  const size_t before_colour = columns.coordinates + (kind.normal ? 3 : 0);
  const size_t min_values =
      before_colour + (kind.colour ? 3 : 0) + (kind.texture ? 2 : 0);
  const size_t max_values = min_values + (kind.colour ? 1 : 0);
  columns.min_values = min_values;
  columns.max_values = max_values;
  columns.expected =
      std::to_string(min_values) +
      (max_values > min_values ? " or " + std::to_string(max_values) : "") +
      (keyword == "OFF" ? "" : " (" + keyword + ")");
  return columns;
}

// Reads vertex i of nv (the next row of `rows`) into b->points.
void ReadOffVertex(OffRows& rows, long long i, long long nv,
                   const OffKeyword& kind, const OffVertexColumns& columns,
                   MeshBuilder* b) {
  if (!rows.Next()) {
    b->Fail("OFF file ends early at vertex " + std::to_string(i) + " of " +
            std::to_string(nv));
  }
  const std::vector<std::string_view>& t = rows.t;
  if (t.size() != columns.min_values && t.size() != columns.max_values) {
    b->Fail("vertex " + std::to_string(i) + " has " + std::to_string(t.size()) +
            " values, expected " + columns.expected + LineTag(rows.line()));
  }
  double values[4] = {0, 0, 0, 1};
  for (size_t c = 0; c < t.size(); ++c) {
    double value = 0;
    if (!ParseDouble(t[c], &value)) {
      b->Fail("vertex " + std::to_string(i) + " has a malformed number " +
              Excerpt(t[c]) + LineTag(rows.line()));
    }
    if (c < columns.coordinates) values[c] = value;
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

// Reads face r of nf (the next row of `rows`) into b->faces and
// b->face_lines.
void ReadOffFace(OffRows& rows, long long r, long long nf, MeshBuilder* b) {
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
      b->Fail("face " + std::to_string(r) + " has a non-integer vertex index " +
              Excerpt(t[c + 1]) + LineTag(line));
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

}  // namespace

void CheckOffHeader(const std::string& prefix, uint64_t file_size,
                    MeshBuilder* b) {
  OffRows rows(prefix, *b);
  ParseOffHeader(rows, file_size, b);
}

Mesh ReadOff(const std::string& bytes, MeshBuilder* b) {
  OffRows rows(bytes, *b);
  const OffHeader header = ParseOffHeader(rows, bytes.size(), b);
  const long long nv = header.nv, nf = header.nf;
  const OffVertexColumns columns = VertexColumnsOf(header);
  b->Reserve(nv, nf);
  for (long long i = 0; i < nv; ++i) {
    ReadOffVertex(rows, i, nv, header.kind, columns, b);
  }
  for (long long r = 0; r < nf; ++r) ReadOffFace(rows, r, nf, b);
  if (rows.Next()) {
    b->Fail("extra data after the " + std::to_string(nf) +
            " faces: " + Excerpt(rows.raw) + LineTag(rows.line()));
  }
  b->CheckIndices(nv, 0);
  return b->Build();
}

}  // namespace shellspace::mesh_reading
