// A built-in 5x7 bitmap font for labels in generated sheets (the seeds' "bitmap character generation").
#pragma once

#include <string_view>

#include "vraster/image.hpp"

namespace vraster::cli {

/// Width and height of one character cell in font pixels (5x7 glyph plus one column and row of spacing).
inline constexpr int kGlyphAdvance = 6;
inline constexpr int kGlyphHeight = 8;

/// Draws `text` with its top-left corner at (x, y), each font pixel a `scale` x `scale` block of `color`.
/// Characters the font lacks draw as a box. Pixels outside the image are skipped.
void draw_label(Image& image, int x, int y, std::string_view text, Color color, int scale = 1);

/// Width in image pixels of `text` drawn at `scale`.
inline int label_width(std::string_view text, int scale = 1) {
  return static_cast<int>(text.size()) * kGlyphAdvance * scale;
}

}  // namespace vraster::cli
