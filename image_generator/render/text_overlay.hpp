#pragma once
// Short labels burned into frames (the sim time in the run's video): a built-in 5x7 bitmap font,
// white glyphs on a dark semi-opaque box, so a label reads on any background. No allocation.

#include <array>
#include <cstdint>
#include <string_view>

namespace vcockpit::render {

// The box draw_text covers (before clipping to the image): one glyph cell is 5x7 pixels times
// scale, glyphs are one scaled pixel apart, and the box has a one-scaled-pixel margin.
struct TextBox {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};
TextBox text_box(int x, int y, int scale, std::string_view text);

// Burns `text` into an RGBA8 (channels 4) or RGB8 (channels 3) image of top-down rows, with the
// box's top-left corner at (x, y). The box darkens what is under it to 40%; glyph pixels become
// white. Alpha is left as it was. Clipped to the image. Printable ASCII: digits, letters and
// . : - / _ + = , ( ) % ? are drawn; any other character shows as '?'.
void draw_text(uint8_t* pixels, int width, int height, int channels, int x, int y, int scale,
               std::string_view text);

// The font's glyph for `c`: 7 rows top down, 5 columns each, bit 4 the leftmost ('?' for a
// character the font lacks). Labels drawn as geometry use it too (instrument_panel.hpp).
const std::array<uint8_t, 7>& glyph_rows(char c);

}  // namespace vcockpit::render
