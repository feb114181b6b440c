// vraster_text: shaping (HarfBuzz), bidi reordering (fribidi) and paragraph layout.
//
//   1. decode_utf8:    bytes -> code points (invalid sequences become U+FFFD)
//   2. paragraphs:     split at hard line breaks ('\n', '\r\n', U+2029)
//   3. bidi levels:    fribidi resolves the embedding level of every character (UAX #9)
//   4. itemize:        runs of one font (fallback list), one script and one bidi level
//   5. shape runs:     HarfBuzz, with features, language and direction
//   6. break lines:    greedy, at break opportunities (after spaces), to the width
//   7. per line:       fribidi reorders the line visually; its runs are shaped again (line-local context) and
//                      placed left to right, aligned, one line height apart
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster_text/font.hpp"

namespace vraster::text {

/// Base direction of a paragraph.
enum class Direction : std::uint8_t {
  Auto,  ///< from the first strong character (UAX #9 P2-P3), left-to-right when there is none
  LeftToRight,
  RightToLeft,
};

/// Horizontal alignment of lines within the layout width.
enum class Align : std::uint8_t { Left, Center, Right };

/// How text is shaped.
struct TextStyle {
  double size = 16;          ///< pixels per em (0 < size <= kMaxFontSize)
  std::string features;      ///< HarfBuzz feature list, e.g. "liga=0,kern" or "-kern,+smcp"
  std::string language;      ///< BCP 47 tag ("ar", "hi"); empty: HarfBuzz's default language
  std::string script;        ///< ISO 15924 tag ("Arab"); empty: from the characters
  Direction direction = Direction::Auto;
};

/// How shaped text is laid out.
struct LayoutOptions {
  double max_width = 0;      ///< wrap lines to this width in pixels; 0: no wrapping (only hard breaks)
  Align align = Align::Left;
  double line_height = 0;    ///< baseline-to-baseline distance in pixels; 0: the first font's natural line height
};

/// One glyph as HarfBuzz shaped it, in pixels; y_advance and y_offset keep HarfBuzz's direction (y up).
struct ShapedGlyph {
  std::uint16_t font = 0;      ///< index into the font list
  std::uint32_t glyph = 0;
  double x_advance = 0, y_advance = 0;
  double x_offset = 0, y_offset = 0;
  std::uint32_t cluster = 0;   ///< index of the first code point of its cluster in the decoded text
};

/// A glyph placed on the page: its pen position (origin on the baseline), pixels, y down.
struct PositionedGlyph {
  std::uint16_t font = 0;
  std::uint32_t glyph = 0;
  Point position;
  std::uint32_t cluster = 0;   ///< code point index in the decoded text
};

/// One laid-out line.
struct TextLine {
  std::uint32_t text_begin = 0, text_end = 0;   ///< code point range (trailing spaces excluded)
  std::uint32_t glyph_begin = 0, glyph_end = 0; ///< range in TextLayout::glyphs
  double x = 0;          ///< left end of the line's glyphs after alignment
  double baseline = 0;   ///< y of the baseline
  double width = 0;      ///< advance width of the line
};

/// The result of layout: glyphs with positions and the fonts they refer to. Drawing needs nothing else.
struct TextLayout {
  std::vector<std::shared_ptr<Font>> fonts;
  double size = 0;
  std::vector<PositionedGlyph> glyphs;
  std::vector<TextLine> lines;
  std::u32string text;   ///< the decoded text (clusters index into it)
  double advance = 0;    ///< widest line's advance width
  Rect logical;          ///< from the first line's ascender to the last line's descender, across the layout width
  Rect ink;              ///< tight box of the glyph outlines (empty rect at the origin when nothing has ink)
};

/// Decodes UTF-8. Each maximal invalid subsequence (stray continuation bytes, truncated or overlong sequences,
/// surrogates, values above U+10FFFF) becomes one U+FFFD; never throws.
std::u32string decode_utf8(std::string_view utf8);

/// Parses a HarfBuzz feature list ("liga=0,kern", "-kern", "+smcp[3:5]", "aalt=2"); commas or spaces separate
/// items. Throws vraster::Error naming the first item HarfBuzz rejects.
struct Feature {
  std::uint32_t tag = 0;
  std::uint32_t value = 1;
  unsigned start = 0, end = ~0u;
};
std::vector<Feature> parse_features(std::string_view list);

/// Shapes one line of text in logical order into glyphs in visual order (left to right), with fallback fonts,
/// bidi reordering and per-run scripts. The simplest entry point for "what does HarfBuzz give".
std::vector<ShapedGlyph> shape_text(std::u32string_view text, const FontList& fonts, const TextStyle& style);

/// Lays out UTF-8 text with its first baseline at `origin.y` and the layout box's left edge at `origin.x`.
/// Throws vraster::Error for an empty font list, a bad size, width or feature list.
TextLayout layout_text(std::string_view utf8, const FontList& fonts, const TextStyle& style,
                       const LayoutOptions& options = {}, Point origin = {});

/// Measuring without drawing.
struct TextMetrics {
  double advance = 0;  ///< widest line
  double height = 0;   ///< lines x line height
  int lines = 0;
  Rect ink;            ///< tight ink box relative to the origin
  Rect logical;
};
TextMetrics measure_text(std::string_view utf8, const FontList& fonts, const TextStyle& style,
                         const LayoutOptions& options = {});

}  // namespace vraster::text
