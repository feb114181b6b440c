// Private: paragraph analysis (bidi levels, runs) and run shaping, shared by shape_text and layout_text.
#pragma once

#include <hb.h>

#include <cstdint>
#include <string_view>
#include <vector>

#include "vraster_text/layout.hpp"

namespace vraster::text::detail {

/// A maximal range of one font, one script and one bidi embedding level.
struct Run {
  std::uint32_t begin = 0, end = 0;  // code point indices in the full text
  std::uint16_t font = 0;
  hb_script_t script = HB_SCRIPT_COMMON;
  std::uint8_t level = 0;
};

/// The bidi analysis and itemization of one paragraph [begin, end) of `text`.
struct Paragraph {
  std::u32string_view text;  // the whole text (clusters are indices into it)
  std::uint32_t begin = 0, end = 0;
  std::uint32_t base_type = 0;        // FriBidiParType after resolution
  std::vector<std::uint32_t> types;   // FriBidiCharType per character of the paragraph
  std::vector<std::int8_t> levels;    // embedding level per character of the paragraph
  std::vector<Run> runs;              // logical order
  bool rtl_base() const;
};

struct ShapeContext {
  const FontList& fonts;
  double size;
  std::vector<hb_feature_t> features;
  hb_language_t language = HB_LANGUAGE_INVALID;
  hb_script_t script = HB_SCRIPT_INVALID;  // forced script or invalid
  hb_buffer_t* buffer = nullptr;

  ShapeContext(const FontList& f, const TextStyle& style);
  ~ShapeContext();
  ShapeContext(const ShapeContext&) = delete;
  ShapeContext& operator=(const ShapeContext&) = delete;
};

/// The text HarfBuzz sees: a tab becomes a space (no tab stops), other control characters U+2060 WORD JOINER
/// (default-ignorable: no glyph, no advance) instead of .notdef boxes. Same length, so clusters still index the
/// original text.
std::u32string text_for_shaping(std::u32string_view text);

Paragraph analyze_paragraph(std::u32string_view text, std::uint32_t begin, std::uint32_t end, Direction direction,
                            ShapeContext& ctx);

/// Shapes text[run.begin, run.end) with context text[context_begin, context_end); appends glyphs in visual order.
void shape_run(std::u32string_view text, const Run& run, std::uint32_t context_begin, std::uint32_t context_end,
               ShapeContext& ctx, std::vector<ShapedGlyph>& out);

/// Shapes the line [begin, end) of a paragraph: reordered visually by fribidi, each run shaped with the line as
/// its context. Appends glyphs left to right.
void shape_line(const Paragraph& para, std::uint32_t begin, std::uint32_t end, ShapeContext& ctx,
                std::vector<ShapedGlyph>& out);

}  // namespace vraster::text::detail
