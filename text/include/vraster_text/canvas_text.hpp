// vraster_text: text on a vraster::Canvas (the HTML canvas fillText / strokeText / measureText).
//
//   UTF-8 -> layout_text (HarfBuzz shaping, fribidi, fallback fonts; one line) -> offset by alignment and baseline
//     -> glyph outlines as one Path -> Canvas::fill (non-zero) or Canvas::stroke
//
// So text gets everything a shape gets: the canvas's transform, paint (gradients, patterns), clip, operator,
// global alpha, shadow and layers. This lives in the text library, not in the core: the core never links FreeType.
#pragma once

#include <cstdint>
#include <string_view>

#include "vraster/canvas.hpp"
#include "vraster_text/font.hpp"
#include "vraster_text/layout.hpp"

namespace vraster::text {

/// Where the anchor point lies horizontally on the text (canvas textAlign). Start and End follow the direction:
/// left and right for left-to-right text (and for Direction::Auto), the other way round for right-to-left.
enum class TextAlign : std::uint8_t { Start, End, Left, Right, Center };

/// Which line of the text the anchor's y is on (canvas textBaseline). Top, Middle and Bottom use the first font's
/// ascender and descender (the em box as the font's metrics give it); Hanging is placed at 80% of the ascender
/// and Ideographic at the descender (fonts rarely carry those baselines, and browsers approximate them likewise).
enum class TextBaseline : std::uint8_t { Alphabetic, Top, Hanging, Middle, Ideographic, Bottom };

/// The text part of a canvas's state (canvas font, textAlign, textBaseline, direction).
struct CanvasFont {
  FontList fonts = FontList::default_list();
  TextStyle style{10, {}, {}, {}, Direction::Auto};  ///< size 10 px, as the canvas default "10px sans-serif"
  TextAlign align = TextAlign::Start;
  TextBaseline baseline = TextBaseline::Alphabetic;
};

/// measure_text's answer (the canvas TextMetrics), in pixels of user space relative to the anchor point;
/// ascents count upwards, everything else as the canvas defines it.
struct CanvasTextMetrics {
  double width = 0;           ///< advance width
  double actual_left = 0;     ///< anchor to the ink's left edge (positive: left of the anchor)
  double actual_right = 0;    ///< anchor to the ink's right edge
  double actual_ascent = 0;   ///< anchor to the ink's top (positive: above)
  double actual_descent = 0;  ///< anchor to the ink's bottom (positive: below)
  double font_ascent = 0;     ///< anchor to the first font's ascender line
  double font_descent = 0;    ///< anchor to its descender line
};

/// Fills the text with its anchor at (x, y) in user space, through the canvas's current fill paint. Line breaks
/// count as spaces (one line, as fillText). `max_width` > 0 squeezes the text horizontally to fit it (0: no limit).
/// Non-finite x, y or max_width, or a negative max_width: nothing is drawn. Throws vraster::Error for a bad style
/// (font size, feature list) or an empty font list.
void fill_text(Canvas& canvas, const CanvasFont& font, std::string_view utf8, double x, double y,
               double max_width = 0);
/// The same, stroking the glyph outlines with the canvas's stroke paint and line style.
void stroke_text(Canvas& canvas, const CanvasFont& font, std::string_view utf8, double x, double y,
                 double max_width = 0);
/// Measures without drawing.
CanvasTextMetrics measure_text(const CanvasFont& font, std::string_view utf8);

}  // namespace vraster::text
