// Tests of the viewer page (render/html_viewer.h): the frames it carries
// decode to the input as float32, the summary cannot end its script
// element, and bad frames are refused. Its drawing in a browser:
// tests/render/viewer_test.sh.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/render/html_viewer.h"

namespace shellspace {
namespace {

// The text of the element with id `id`.
std::string ElementText(const std::string& page, const std::string& id) {
  const size_t open = page.find("id=\"" + id + "\">");
  EXPECT_NE(open, std::string::npos) << id;
  const size_t start = page.find('>', open) + 1;
  return page.substr(start, page.find("</script>", start) - start);
}

std::vector<unsigned char> DecodeBase64(const std::string& text) {
  std::vector<unsigned char> out;
  int bits = 0, value = 0;
  for (const char c : text) {
    const char* alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(alphabet, c);
    if (c == '=' || at == nullptr) break;
    value = (value << 6) | static_cast<int>(at - alphabet);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((value >> bits) & 255));
    }
  }
  return out;
}

TEST(HtmlViewerTest, FramesAndFacesDecodeToTheInput) {
  const Mesh finger = MakeFinger(0.5, 4.0, 8, 5, 2);
  const std::vector<Positions> frames = {
      finger.positions, BendAlongY(finger.positions, 4.0, 1.0),
      BendAlongY(finger.positions, 4.0, 1.5)};
  const std::string page = EncodeHtmlViewer(frames, finger.faces, "a <title>");
  EXPECT_NE(page.find("<title>a &lt;title&gt;</title>"), std::string::npos);
  EXPECT_NE(page.find("data-vertices=\"57\" data-frames=\"3\""),
            std::string::npos);
  const std::vector<unsigned char> positions =
      DecodeBase64(ElementText(page, "positions"));
  ASSERT_EQ(positions.size(), 3 * 57 * 3 * sizeof(float));
  std::vector<float> floats(positions.size() / sizeof(float));
  std::memcpy(floats.data(), positions.data(), positions.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    for (Eigen::Index i = 0; i < frames[k].size(); ++i) {
      ASSERT_EQ(floats[k * 171 + i], static_cast<float>(frames[k].data()[i]));
    }
  }
  const std::vector<unsigned char> faces = DecodeBase64(ElementText(page, "faces"));
  ASSERT_EQ(faces.size(), finger.faces.size() * sizeof(uint32_t));
  std::vector<uint32_t> indices(finger.faces.size());
  std::memcpy(indices.data(), faces.data(), faces.size());
  for (Eigen::Index i = 0; i < finger.faces.size(); ++i) {
    ASSERT_EQ(indices[i], static_cast<uint32_t>(finger.faces.data()[i]));
  }
  // Nothing is fetched: no src= or href= anywhere.
  EXPECT_EQ(page.find("src="), std::string::npos);
  EXPECT_EQ(page.find("href="), std::string::npos);
}

TEST(HtmlViewerTest, TheSummaryCannotEndItsScriptElement) {
  const Mesh finger = MakeFinger(0.5, 4.0, 8, 5, 2);
  const std::string page =
      EncodeHtmlViewer({finger.positions}, finger.faces, "t",
                       "{\"path_energy\": 0.5, \"note\": \"</script><b>\"}");
  EXPECT_EQ(ElementText(page, "summary"),
            "{\"path_energy\": 0.5, \"note\": \"\\u003c/script>\\u003cb>\"}");
}

TEST(HtmlViewerTest, BadFramesAreRefused) {
  const Mesh finger = MakeFinger(0.5, 4.0, 8, 5, 2);
  EXPECT_THROW(EncodeHtmlViewer({}, finger.faces, "t"), InputError);
  EXPECT_THROW(EncodeHtmlViewer({finger.positions, finger.positions.topRows(5)},
                                finger.faces, "t"),
               InputError);
  Positions bad = finger.positions;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(EncodeHtmlViewer({finger.positions, bad}, finger.faces, "t"),
               InputError);
  Faces faces = finger.faces;
  faces(0, 0) = 57;
  EXPECT_THROW(EncodeHtmlViewer({finger.positions}, faces, "t"), InputError);
}

}  // namespace
}  // namespace shellspace
