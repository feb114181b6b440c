// Private: the FreeType and HarfBuzz objects behind a Font.
#pragma once

#include <ft2build.h>
#include FT_FREETYPE_H
#include <hb.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "vraster_text/font.hpp"

namespace vraster::text {

struct Font::Impl {
  std::uint64_t id = 0;
  std::string name;
  std::vector<std::uint8_t> owned;       // the file's bytes (empty for the embedded font)
  std::span<const std::uint8_t> bytes;   // owned, or the embedded data
  FT_Library library = nullptr;          // one FreeType library per font: no shared state between fonts
  FT_Face face = nullptr;
  hb_font_t* hb = nullptr;               // scale = units per em: positions come out in font units
  double sized_at = -1;                  // the char size FT_Set_Char_Size last set (hinted loads)
  std::unordered_map<std::uint32_t, GlyphOutline> outlines;  // unhinted, font units, y down, with control boxes
  mutable std::unordered_map<char32_t, std::uint32_t> cmap; // code point -> glyph
  int color_strike = -1;                 // the largest colour bitmap strike, -1: none
  std::unordered_map<std::uint32_t, std::optional<ColorBitmap>> color_bitmaps;  // per glyph; nullopt: none

  ~Impl();
  /// Loads `glyph` with `flags` into face->glyph; false when FreeType refuses.
  bool load(std::uint32_t glyph, FT_Int32 flags);
  /// Loads a glyph's image from the colour strike; nothing when it has none there.
  std::optional<ColorBitmap> load_color_bitmap(std::uint32_t glyph);
};

/// Converts the outline in face->glyph to a Path, scaling FreeType's coordinates by (sx, sy) and flipping y.
void decompose_outline(const FT_Outline& outline, double sx, double sy, Path& out);

}  // namespace vraster::text
