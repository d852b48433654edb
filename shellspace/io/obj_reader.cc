// The OBJ reader (io/mesh_reading.h).
#include "shellspace/io/mesh_reading.h"

namespace shellspace::mesh_reading {

Mesh ReadObj(const std::string& bytes, MeshBuilder* b) {
  LineCursor lines(bytes, 1, b->path, b->stop);
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

}  // namespace shellspace::mesh_reading
