// Text on the canvas: shaping and placement here, pixels through the canvas (see canvas_text.hpp).
#include "vraster_text/canvas_text.hpp"

#include <cmath>
#include <string>

#include "vraster/error.hpp"
#include "vraster_text/render.hpp"

namespace vraster::text {
namespace {

// One line laid out at the origin, and where the anchor sits relative to it.
struct PlacedText {
  TextLayout layout;
  double dx = 0, dy = 0;  // added to the layout's coordinates to put the anchor at the origin
};

PlacedText place(const CanvasFont& font, std::string_view utf8) {
  if (font.fonts.empty()) throw Error("text: the font list is empty");
  std::string line(utf8);
  for (char& ch : line) {
    if (ch == '\n' || ch == '\r') ch = ' ';  // fillText draws one line: breaks are spaces
  }
  PlacedText out;
  out.layout = layout_text(line, font.fonts, font.style);
  const double width = out.layout.advance;
  const bool rtl = font.style.direction == Direction::RightToLeft;
  switch (font.align) {
    case TextAlign::Left: break;
    case TextAlign::Right: out.dx = -width; break;
    case TextAlign::Center: out.dx = -width / 2; break;
    case TextAlign::Start: out.dx = rtl ? -width : 0; break;
    case TextAlign::End: out.dx = rtl ? 0 : -width; break;
  }
  const FontMetrics m = font.fonts.fonts[0]->metrics(font.style.size);  // ascender < 0 < descender
  switch (font.baseline) {
    case TextBaseline::Alphabetic: break;
    case TextBaseline::Top: out.dy = -m.ascender; break;
    case TextBaseline::Hanging: out.dy = -0.8 * m.ascender; break;
    case TextBaseline::Middle: out.dy = -(m.ascender + m.descender) / 2; break;
    case TextBaseline::Ideographic:
    case TextBaseline::Bottom: out.dy = -m.descender; break;
  }
  return out;
}

// The glyph outlines of the text in user space, anchored at (x, y); false when there is nothing to draw.
bool text_path(const CanvasFont& font, std::string_view utf8, double x, double y, double max_width, Path& out) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(max_width) || max_width < 0) return false;
  if (utf8.empty()) return false;
  const PlacedText placed = place(font, utf8);
  Path glyphs;
  TextRenderer::append_outlines(placed.layout, glyphs);
  if (glyphs.empty()) return false;
  const double width = placed.layout.advance;
  const double squeeze = max_width > 0 && width > max_width ? max_width / width : 1;
  const Affine m = Affine::translate(x, y) * Affine::scale(squeeze, 1) * Affine::translate(placed.dx, placed.dy);
  try {
    out = glyphs.transformed(m);
  } catch (const Error&) {
    return false;  // coordinates beyond the doubles' range: a bad number, so nothing is drawn
  }
  return true;
}

}  // namespace

void fill_text(Canvas& canvas, const CanvasFont& font, std::string_view utf8, double x, double y, double max_width) {
  Path path;
  if (text_path(font, utf8, x, y, max_width, path)) canvas.fill(path, FillRule::NonZero);
}

void stroke_text(Canvas& canvas, const CanvasFont& font, std::string_view utf8, double x, double y,
                 double max_width) {
  Path path;
  if (text_path(font, utf8, x, y, max_width, path)) canvas.stroke(path);
}

CanvasTextMetrics measure_text(const CanvasFont& font, std::string_view utf8) {
  CanvasTextMetrics out;
  const PlacedText placed = place(font, utf8);
  const FontMetrics m = font.fonts.fonts[0]->metrics(font.style.size);
  const Rect& ink = placed.layout.ink;
  out.width = placed.layout.advance;
  out.actual_left = -(ink.x0 + placed.dx);
  out.actual_right = ink.x1 + placed.dx;
  out.actual_ascent = -(ink.y0 + placed.dy);
  out.actual_descent = ink.y1 + placed.dy;
  out.font_ascent = -(m.ascender + placed.dy);
  out.font_descent = m.descender + placed.dy;
  return out;
}

}  // namespace vraster::text
