// A small built-in bitmap font for the labels, legends and axes of the
// pictures: 5 x 7 pixel glyphs (plus one descender row) for the printable
// ASCII letters, digits and the usual punctuation, drawn at an integer
// scale. No font files, no external library; deterministic pixels.
#ifndef SHELLSPACE_RENDER_BITMAP_FONT_H_
#define SHELLSPACE_RENDER_BITMAP_FONT_H_

#include <array>
#include <cstdint>
#include <string>

#include "shellspace/io/png_writer.h"

namespace shellspace {

// A glyph cell is kGlyphWidth x kGlyphHeight pixels at scale 1: capitals
// and digits fill rows 0..6 (row 6 is the baseline), lower-case letters have
// their x-height in rows 2..6 and descenders (g j p q y, and '_') reach row 7.
// Characters are kGlyphAdvance apart (one blank column between glyphs).
constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 8;
constexpr int kGlyphAdvance = 6;

// True if `c` has a glyph of its own: ' ', 0-9, a-z, A-Z and
// . , : ; = + - _ ( ) [ ] / | % * < > ! ? ' ^ ~. Any other character is drawn
// as '?'.
bool HasGlyph(char c);

// True where the glyph of `c` has ink: column x in [0, kGlyphWidth), row y in
// [0, kGlyphHeight); false outside the cell.
bool GlyphInk(char c, int x, int y);

// Pixel width of `text` drawn at `scale`: kGlyphAdvance * scale per
// character, minus the trailing blank column; 0 for "".
int TextWidth(const std::string& text, int scale);

// Pixel height of a line of text at `scale`: kGlyphHeight * scale.
inline int TextHeight(int scale) { return kGlyphHeight * scale; }

// Draws `text` with its cell's top-left corner at (left, top): every ink
// pixel of a glyph becomes a scale x scale block of `color`. Pixels outside
// the image are skipped (text may be clipped, never wraps).
void DrawText(const std::string& text, int left, int top, int scale,
              const std::array<std::uint8_t, 3>& color, RgbImage* image);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_BITMAP_FONT_H_
