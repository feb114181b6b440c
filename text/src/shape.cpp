// Itemization, bidi and shaping.
//
//   analyze_paragraph: fribidi levels -> font per character (fallback list) -> script per character -> runs
//   shape_line:        fribidi_reorder_line -> runs in visual order -> HarfBuzz per run -> glyphs left to right
#include <fribidi.h>

#include <algorithm>
#include <numeric>

#include "font_impl.hpp"
#include "shape_impl.hpp"
#include "vraster/error.hpp"

namespace vraster::text {
namespace detail {
namespace {

bool is_default_ignorable_or_control(char32_t c) {
  return c < 0x20 || (c >= 0x7F && c < 0xA0) || c == 0x200B || c == 0x200C || c == 0x200D || c == 0x200E ||
         c == 0x200F || (c >= 0x202A && c <= 0x202E) || (c >= 0x2066 && c <= 0x2069) || c == 0x2060 ||
         c == 0xFEFF || (c >= 0xFE00 && c <= 0xFE0F) || (c >= 0xE0100 && c <= 0xE01EF);
}

bool is_mark(hb_unicode_general_category_t gc) {
  return gc == HB_UNICODE_GENERAL_CATEGORY_NON_SPACING_MARK || gc == HB_UNICODE_GENERAL_CATEGORY_SPACING_MARK ||
         gc == HB_UNICODE_GENERAL_CATEGORY_ENCLOSING_MARK;
}

// The font for one character: marks, joiners and neutral characters stay with the previous character's font when
// it has them (so a run is not split by a space or a combining mark); otherwise the first font that has a glyph;
// otherwise the first font (its .notdef).
std::uint16_t choose_font(char32_t c, int prev, hb_script_t script, const FontList& fonts, hb_unicode_funcs_t* uf) {
  if (prev >= 0) {
    if (is_default_ignorable_or_control(c)) return static_cast<std::uint16_t>(prev);
    const auto gc = hb_unicode_general_category(uf, c);
    if ((is_mark(gc) || script == HB_SCRIPT_COMMON || script == HB_SCRIPT_INHERITED) &&
        fonts.fonts[static_cast<std::size_t>(prev)]->has_glyph(c)) {
      return static_cast<std::uint16_t>(prev);
    }
  }
  for (std::size_t i = 0; i < fonts.fonts.size(); ++i) {
    if (fonts.fonts[i]->has_glyph(c)) return static_cast<std::uint16_t>(i);
  }
  return 0;
}

}  // namespace

std::u32string text_for_shaping(std::u32string_view text) {
  std::u32string out(text);
  for (char32_t& c : out) {
    if (c == U'\t') {
      c = U' ';
    } else if (c < 0x20 || (c >= 0x7F && c < 0xA0)) {
      c = 0x2060;
    }
  }
  return out;
}

bool Paragraph::rtl_base() const { return FRIBIDI_IS_RTL(base_type); }

ShapeContext::ShapeContext(const FontList& f, const TextStyle& style) : fonts(f), size(style.size) {
  if (fonts.empty()) throw Error("no font given");
  for (const auto& font : fonts.fonts) {
    if (!font) throw Error("a font in the font list is null");
  }
  check_font_size(style.size);
  for (const Feature& feat : parse_features(style.features)) {
    features.push_back({feat.tag, feat.value, feat.start, feat.end});
  }
  if (!style.language.empty()) {
    language = hb_language_from_string(style.language.data(), static_cast<int>(style.language.size()));
  }
  if (!style.script.empty()) {
    const bool four_letters = style.script.size() == 4 && std::all_of(style.script.begin(), style.script.end(), [](char c) {
      return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
    });
    if (!four_letters) throw Error("unknown script '" + style.script + "' (expected an ISO 15924 tag such as Latn, Arab, Deva)");
    script = hb_script_from_string(style.script.data(), static_cast<int>(style.script.size()));
    if (script == HB_SCRIPT_INVALID || script == HB_SCRIPT_UNKNOWN) {
      throw Error("unknown script '" + style.script + "' (expected an ISO 15924 tag such as Latn, Arab, Deva)");
    }
  }
  buffer = hb_buffer_create();
  if (!hb_buffer_allocation_successful(buffer)) throw Error("HarfBuzz: out of memory");
}

ShapeContext::~ShapeContext() { hb_buffer_destroy(buffer); }

Paragraph analyze_paragraph(std::u32string_view text, std::uint32_t begin, std::uint32_t end, Direction direction,
                            ShapeContext& ctx) {
  Paragraph p;
  p.text = text;
  p.begin = begin;
  p.end = end;
  const std::uint32_t n = end - begin;
  p.types.resize(n);
  p.levels.resize(n);
  FriBidiParType base = direction == Direction::LeftToRight   ? FRIBIDI_PAR_LTR
                        : direction == Direction::RightToLeft ? FRIBIDI_PAR_RTL
                                                              : FRIBIDI_PAR_ON;
  if (n > 0) {
    static_assert(sizeof(FriBidiChar) == sizeof(char32_t));
    static_assert(sizeof(FriBidiCharType) == sizeof(std::uint32_t));
    static_assert(sizeof(FriBidiLevel) == sizeof(std::int8_t));
    const auto* chars = reinterpret_cast<const FriBidiChar*>(text.data() + begin);
    auto* types = reinterpret_cast<FriBidiCharType*>(p.types.data());
    std::vector<FriBidiBracketType> brackets(n);
    fribidi_get_bidi_types(chars, static_cast<FriBidiStrIndex>(n), types);
    fribidi_get_bracket_types(chars, static_cast<FriBidiStrIndex>(n), types, brackets.data());
    if (fribidi_get_par_embedding_levels_ex(types, brackets.data(), static_cast<FriBidiStrIndex>(n), &base,
                                            reinterpret_cast<FriBidiLevel*>(p.levels.data())) == 0) {
      throw Error("fribidi could not resolve the paragraph's bidi levels");
    }
  } else if (base == FRIBIDI_PAR_ON) {
    base = FRIBIDI_PAR_LTR;
  }
  p.base_type = base;

  // Scripts: Common and Inherited characters take the script of the character before them (or, at the start, of
  // the first character with a real script).
  hb_unicode_funcs_t* uf = hb_unicode_funcs_get_default();
  std::vector<hb_script_t> scripts(n, HB_SCRIPT_COMMON);
  std::vector<hb_script_t> raw(n);
  hb_script_t first_real = HB_SCRIPT_COMMON;
  for (std::uint32_t i = 0; i < n; ++i) {
    raw[i] = hb_unicode_script(uf, text[begin + i]);
    if (first_real == HB_SCRIPT_COMMON && raw[i] != HB_SCRIPT_COMMON && raw[i] != HB_SCRIPT_INHERITED &&
        raw[i] != HB_SCRIPT_UNKNOWN) {
      first_real = raw[i];
    }
  }
  hb_script_t current = first_real;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (ctx.script != HB_SCRIPT_INVALID) {
      scripts[i] = ctx.script;
      continue;
    }
    if (raw[i] != HB_SCRIPT_COMMON && raw[i] != HB_SCRIPT_INHERITED && raw[i] != HB_SCRIPT_UNKNOWN) current = raw[i];
    scripts[i] = current;
  }

  int prev_font = -1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint16_t f = choose_font(text[begin + i], prev_font, raw[i], ctx.fonts, uf);
    prev_font = f;
    const auto level = static_cast<std::uint8_t>(p.levels[i]);
    if (!p.runs.empty()) {
      Run& last = p.runs.back();
      if (last.font == f && last.script == scripts[i] && last.level == level) {
        last.end = begin + i + 1;
        continue;
      }
    }
    p.runs.push_back({begin + i, begin + i + 1, f, scripts[i], level});
  }
  return p;
}

void shape_run(std::u32string_view text, const Run& run, std::uint32_t context_begin, std::uint32_t context_end,
               ShapeContext& ctx, std::vector<ShapedGlyph>& out) {
  hb_buffer_t* buf = ctx.buffer;
  hb_buffer_clear_contents(buf);
  hb_buffer_add_utf32(buf, reinterpret_cast<const std::uint32_t*>(text.data() + context_begin),
                      static_cast<int>(context_end - context_begin), run.begin - context_begin,
                      static_cast<int>(run.end - run.begin));
  hb_buffer_set_direction(buf, (run.level & 1) ? HB_DIRECTION_RTL : HB_DIRECTION_LTR);
  hb_buffer_set_script(buf, run.script);
  if (ctx.language != HB_LANGUAGE_INVALID) hb_buffer_set_language(buf, ctx.language);
  hb_buffer_guess_segment_properties(buf);
  const Font& font = *ctx.fonts.fonts[run.font];
  hb_shape(font.impl().hb, buf, ctx.features.data(), static_cast<unsigned>(ctx.features.size()));
  unsigned count = 0;
  const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buf, &count);
  const hb_glyph_position_t* pos = hb_buffer_get_glyph_positions(buf, &count);
  const double s = ctx.size / font.units_per_em();
  for (unsigned i = 0; i < count; ++i) {
    ShapedGlyph g;
    g.font = run.font;
    g.glyph = info[i].codepoint;
    g.x_advance = pos[i].x_advance * s;
    g.y_advance = pos[i].y_advance * s;
    g.x_offset = pos[i].x_offset * s;
    g.y_offset = pos[i].y_offset * s;
    g.cluster = info[i].cluster + context_begin;
    out.push_back(g);
  }
}

void shape_line(const Paragraph& para, std::uint32_t begin, std::uint32_t end, ShapeContext& ctx,
                std::vector<ShapedGlyph>& out) {
  if (end <= begin) return;
  const std::uint32_t n = end - begin, off = begin - para.begin;
  // fribidi's line reordering (rule L1 resets trailing whitespace, L2 reverses); map[visual] = logical.
  std::vector<FriBidiLevel> levels(para.levels.begin() + off, para.levels.begin() + off + n);
  std::vector<FriBidiStrIndex> map(n);
  std::iota(map.begin(), map.end(), 0);
  FriBidiParType base = para.base_type;
  if (fribidi_reorder_line(0, reinterpret_cast<const FriBidiCharType*>(para.types.data()) + off,
                           static_cast<FriBidiStrIndex>(n), 0, base, levels.data(), nullptr, map.data()) == 0) {
    throw Error("fribidi could not reorder a line");
  }
  std::vector<std::uint32_t> visual_of(n);
  for (std::uint32_t v = 0; v < n; ++v) visual_of[static_cast<std::size_t>(map[v])] = v;
  // The paragraph's runs clipped to the line and split where rule L1 changed a level.
  std::vector<Run> runs;
  for (const Run& r : para.runs) {
    const std::uint32_t b = std::max(r.begin, begin), e = std::min(r.end, end);
    for (std::uint32_t i = b; i < e; ++i) {
      const auto level = static_cast<std::uint8_t>(levels[i - begin]);
      if (i > b && runs.back().level == level) {
        runs.back().end = i + 1;
      } else {
        Run piece = r;
        piece.begin = i;
        piece.end = i + 1;
        piece.level = level;
        runs.push_back(piece);
      }
    }
  }
  // Each run's characters are contiguous in visual order: sort the runs by where their first character lands.
  std::sort(runs.begin(), runs.end(), [&](const Run& a, const Run& b) {
    return visual_of[a.begin - begin] < visual_of[b.begin - begin];
  });
  for (const Run& r : runs) shape_run(para.text, r, begin, end, ctx, out);
}

}  // namespace detail

std::vector<Feature> parse_features(std::string_view list) {
  std::vector<Feature> out;
  std::size_t i = 0;
  while (i < list.size()) {
    while (i < list.size() && (list[i] == ',' || list[i] == ' ')) ++i;
    std::size_t j = i;
    while (j < list.size() && list[j] != ',' && list[j] != ' ') ++j;
    if (j > i) {
      const std::string_view item = list.substr(i, j - i);
      hb_feature_t f{};
      if (!hb_feature_from_string(item.data(), static_cast<int>(item.size()), &f)) {
        throw Error("invalid font feature '" + std::string(item) + "' (expected e.g. liga=0, kern, -kern, +smcp)");
      }
      out.push_back({f.tag, f.value, f.start, f.end});
    }
    i = j;
  }
  return out;
}

std::vector<ShapedGlyph> shape_text(std::u32string_view text, const FontList& fonts, const TextStyle& style) {
  detail::ShapeContext ctx(fonts, style);
  const std::u32string shaping = detail::text_for_shaping(text);
  const auto n = static_cast<std::uint32_t>(shaping.size());
  const detail::Paragraph para = detail::analyze_paragraph(shaping, 0, n, style.direction, ctx);
  std::vector<ShapedGlyph> out;
  detail::shape_line(para, 0, n, ctx, out);
  return out;
}

}  // namespace vraster::text
