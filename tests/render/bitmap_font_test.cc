// Tests of the bitmap font (render/bitmap_font.h): every digit inked and
// unlike the others, the glyph set, text widths, and DrawText's scaled,
// clipped pixels.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "shellspace/render/bitmap_font.h"

namespace shellspace {
namespace {

TEST(BitmapFontTest, DigitsAreDistinctAndInked) {
  for (char a = '0'; a <= '9'; ++a) {
    int ink = 0;
    for (int y = 0; y < kGlyphHeight; ++y) {
      for (int x = 0; x < kGlyphWidth; ++x) ink += GlyphInk(a, x, y);
    }
    EXPECT_GE(ink, 7) << a;
    for (char b = a + 1; b <= '9'; ++b) {
      int differing = 0;
      for (int y = 0; y < kGlyphHeight; ++y) {
        for (int x = 0; x < kGlyphWidth; ++x) {
          differing += GlyphInk(a, x, y) != GlyphInk(b, x, y);
        }
      }
      EXPECT_GE(differing, 2) << a << " vs " << b;
    }
  }
  for (char c : std::string("0123456789 t=.-+_|abcxyzAZ()")) {
    EXPECT_TRUE(HasGlyph(c)) << c;
  }
  EXPECT_FALSE(HasGlyph('\t'));
  // Unknown characters draw as '?'.
  for (int y = 0; y < kGlyphHeight; ++y) {
    for (int x = 0; x < kGlyphWidth; ++x) {
      EXPECT_EQ(GlyphInk('\x01', x, y), GlyphInk('?', x, y));
    }
  }
  EXPECT_EQ(TextWidth("", 3), 0);
  EXPECT_EQ(TextWidth("12", 1), 11);
  EXPECT_EQ(TextWidth("12", 2), 22);
}

TEST(BitmapFontTest, DrawTextPutsScaledGlyphsAndClips) {
  RgbImage image(40, 20, 255);
  DrawText("7", 3, 2, 2, {10, 20, 30}, &image);
  for (int y = 0; y < kGlyphHeight; ++y) {
    for (int x = 0; x < kGlyphWidth; ++x) {
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
          const std::uint8_t* p = image.at(3 + 2 * x + i, 2 + 2 * y + j);
          EXPECT_EQ(p[0] == 10 && p[1] == 20 && p[2] == 30, GlyphInk('7', x, y))
              << x << "," << y;
        }
      }
    }
  }
  DrawText("888", 35, -3, 1, {0, 0, 0}, &image);  // partly outside: no crash
  // Row 3 of '8' (".###.") lands on image row 0.
  EXPECT_EQ(image.at(35, 0)[0], 255);
  EXPECT_EQ(image.at(36, 0)[0], 0);
  EXPECT_EQ(image.at(39, 0)[0], 255);
}

}  // namespace
}  // namespace shellspace
