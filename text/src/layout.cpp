// Paragraph layout: hard breaks -> bidi paragraphs -> measured runs -> greedy line breaking -> shaped lines placed on
// baselines and aligned.
#include <algorithm>
#include <cmath>

#include "shape_impl.hpp"
#include "vraster/error.hpp"

namespace vraster::text {
namespace {

bool is_hard_break(char32_t c) { return c == U'\n' || c == U'\r' || c == 0x2028 || c == 0x2029 || c == 0x0B || c == 0x0C || c == 0x85; }

// Characters after which a line may break (and which vanish at the end of a line).
bool is_break_space(char32_t c) {
  return c == U' ' || c == U'\t' || c == 0x1680 || (c >= 0x2000 && c <= 0x2006) || (c >= 0x2008 && c <= 0x200A) ||
         c == 0x205F || c == 0x3000 || c == 0x200B;
}

// Greedy line breaking of paragraph [begin, end) given each character's advance. A line may break after a run of
// spaces; a word longer than the width gets a line of its own (it overflows rather than being cut).
std::vector<std::pair<std::uint32_t, std::uint32_t>> break_lines(std::u32string_view text, std::uint32_t begin,
                                                                  std::uint32_t end, const std::vector<double>& adv,
                                                                  double max_width) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> lines;
  if (max_width <= 0) {
    lines.emplace_back(begin, end);
    return lines;
  }
  std::uint32_t line_start = begin;
  double line_width = 0;  // including trailing spaces of the words placed so far
  std::uint32_t i = begin;
  while (i < end) {
    // One segment: a word and the spaces after it.
    std::uint32_t j = i;
    double word = 0, spaces = 0;
    while (j < end && !is_break_space(text[j])) word += adv[j++ - begin];
    while (j < end && is_break_space(text[j])) spaces += adv[j++ - begin];
    if (i > line_start && line_width + word > max_width + 1e-9) {
      lines.emplace_back(line_start, i);
      line_start = i;
      line_width = 0;
    }
    line_width += word + spaces;
    i = j;
  }
  lines.emplace_back(line_start, end);
  return lines;
}

}  // namespace

TextLayout layout_text(std::string_view utf8, const FontList& fonts, const TextStyle& style,
                       const LayoutOptions& options, Point origin) {
  if (!std::isfinite(options.max_width) || options.max_width < 0) throw Error("text width must be 0 or positive");
  if (!std::isfinite(options.line_height) || options.line_height < 0) {
    throw Error("line height must be 0 or positive");
  }
  if (!is_finite(origin)) throw Error("text origin is not finite");
  detail::ShapeContext ctx(fonts, style);
  TextLayout out;
  out.fonts = fonts.fonts;
  out.size = style.size;
  out.text = decode_utf8(utf8);
  const std::u32string original = out.text;
  // Hard breaks are found in the original; everything else is shaped from the cleaned copy (tabs as spaces, other
  // control characters invisible).
  const std::u32string shaping = detail::text_for_shaping(out.text);
  const std::u32string_view text = shaping;
  const auto n = static_cast<std::uint32_t>(text.size());
  const FontMetrics fm = fonts.fonts[0]->metrics(style.size);
  const double line_height = options.line_height > 0 ? options.line_height : fm.line_height();

  // 1. Lines: paragraphs split at hard breaks, each broken to the width.
  struct LineSpan {
    std::uint32_t begin, end;
    std::size_t para;
  };
  std::vector<detail::Paragraph> paras;
  std::vector<LineSpan> spans;
  std::vector<ShapedGlyph> glyphs;
  std::vector<double> adv;
  std::uint32_t p0 = 0;
  while (p0 <= n) {
    std::uint32_t p1 = p0;
    while (p1 < n && !is_hard_break(original[p1])) ++p1;
    paras.push_back(detail::analyze_paragraph(text, p0, p1, style.direction, ctx));
    const detail::Paragraph& para = paras.back();
    adv.assign(p1 - p0, 0.0);
    if (options.max_width > 0) {
      glyphs.clear();
      for (const detail::Run& r : para.runs) detail::shape_run(text, r, p0, p1, ctx, glyphs);
      for (const ShapedGlyph& g : glyphs) adv[g.cluster - p0] += g.x_advance;
    }
    for (auto [b, e] : break_lines(text, p0, p1, adv, options.max_width)) spans.push_back({b, e, paras.size() - 1});
    if (p1 >= n) break;
    p0 = p1 + ((original[p1] == U'\r' && p1 + 1 < n && original[p1 + 1] == U'\n') ? 2 : 1);
    if (p0 == n) {  // text ends with a break: one more (empty) line
      paras.push_back(detail::analyze_paragraph(text, n, n, style.direction, ctx));
      spans.push_back({n, n, paras.size() - 1});
      break;
    }
  }

  // 2. Shape every line (trailing spaces dropped) in visual order and measure it.
  std::vector<std::vector<ShapedGlyph>> line_glyphs(spans.size());
  for (std::size_t k = 0; k < spans.size(); ++k) {
    std::uint32_t e = spans[k].end;
    while (e > spans[k].begin && is_break_space(text[e - 1])) --e;
    spans[k].end = e;
    detail::shape_line(paras[spans[k].para], spans[k].begin, e, ctx, line_glyphs[k]);
    TextLine line;
    line.text_begin = spans[k].begin;
    line.text_end = e;
    for (const ShapedGlyph& g : line_glyphs[k]) line.width += g.x_advance;
    out.advance = std::max(out.advance, line.width);
    out.lines.push_back(line);
  }

  // 3. Place: baselines one line height apart, lines aligned within the box width.
  const double box = options.max_width > 0 ? options.max_width : out.advance;
  bool any_ink = false;
  for (std::size_t k = 0; k < out.lines.size(); ++k) {
    TextLine& line = out.lines[k];
    line.baseline = origin.y + static_cast<double>(k) * line_height;
    const double slack = box - line.width;
    line.x = origin.x + (options.align == Align::Left ? 0.0 : options.align == Align::Center ? 0.5 * slack : slack);
    line.glyph_begin = static_cast<std::uint32_t>(out.glyphs.size());
    double pen_x = line.x, pen_y = line.baseline;
    for (const ShapedGlyph& g : line_glyphs[k]) {
      PositionedGlyph pg;
      pg.font = g.font;
      pg.glyph = g.glyph;
      pg.position = {pen_x + g.x_offset, pen_y - g.y_offset};  // HarfBuzz's y points up
      pg.cluster = g.cluster;
      out.glyphs.push_back(pg);
      pen_x += g.x_advance;
      pen_y -= g.y_advance;
      const Font& font = *fonts.fonts[g.font];
      const Path& outline = font.outline_units(g.glyph);
      if (outline.empty()) continue;
      const Rect b = outline.bounds();
      const double s = style.size / font.units_per_em();
      const Rect gb{pg.position.x + b.x0 * s, pg.position.y + b.y0 * s, pg.position.x + b.x1 * s,
                    pg.position.y + b.y1 * s};
      if (!any_ink) {
        out.ink = gb;
        any_ink = true;
      } else {
        out.ink.include({gb.x0, gb.y0});
        out.ink.include({gb.x1, gb.y1});
      }
    }
    line.glyph_end = static_cast<std::uint32_t>(out.glyphs.size());
  }
  if (!any_ink) out.ink = Rect::from_point(origin);
  const double last_baseline = origin.y + static_cast<double>(out.lines.size() - 1) * line_height;
  out.logical = {origin.x, origin.y + fm.ascender, origin.x + box, last_baseline + fm.descender};
  return out;
}

TextMetrics measure_text(std::string_view utf8, const FontList& fonts, const TextStyle& style,
                         const LayoutOptions& options) {
  const TextLayout layout = layout_text(utf8, fonts, style, options);
  TextMetrics m;
  m.advance = layout.advance;
  m.lines = static_cast<int>(layout.lines.size());
  const double lh = options.line_height > 0 ? options.line_height : fonts.fonts[0]->metrics(style.size).line_height();
  m.height = lh * m.lines;
  m.ink = layout.ink;
  m.logical = layout.logical;
  return m;
}

}  // namespace vraster::text
