// The SVG / CSS text properties: parsing into TextProperties (the cascade itself is document.cpp's).
#include <algorithm>
#include <cmath>
#include <string>

#include "scan.hpp"
#include "text.hpp"

namespace vraster::svg::detail {
namespace {

constexpr double kMaxTextSize = 1e6;  // px: bigger font sizes and spacings are clamped (fonts refuse > 4096)

constexpr std::string_view kTextProperties[] = {
    "font",          "font-family",        "font-size",          "font-weight",       "font-style",
    "font-stretch",  "font-variant",       "font-kerning",       "font-feature-settings", "letter-spacing",
    "word-spacing",  "text-anchor",        "direction",          "writing-mode",      "dominant-baseline",
    "alignment-baseline", "baseline-shift", "text-decoration",   "font-variant-caps", "kerning",
    "font-variation-settings", "text-rendering"};

std::vector<std::string_view> split_words(std::string_view v) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < v.size()) {
    while (i < v.size() && is_wsp(v[i])) ++i;
    const std::size_t start = i;
    while (i < v.size() && !is_wsp(v[i])) ++i;
    if (i > start) out.push_back(v.substr(start, i - start));
  }
  return out;
}

/// A CSS length with em/ex relative to `em`, percentages of `percent_of` and physical units at `dpi`.
bool css_length(std::string_view v, double em, double percent_of, double dpi, double& out) {
  std::size_t pos = 0;
  double number = 0;
  if (scan_number(v, pos, number) != NumberScan::Ok) return false;
  const std::string_view unit = v.substr(pos);
  double scale = absolute_unit_scale(unit, dpi);
  if (scale == 0) scale = -1;
  if (iequals(unit, "em")) scale = em;
  if (iequals(unit, "ex")) scale = em / 2;
  if (unit == "%") scale = percent_of / 100;
  if (scale < 0) return false;
  out = number * scale;
  return std::isfinite(out);
}

bool parse_font_size(std::string_view v, double parent, double dpi, double& out) {
  // Absolute keywords: steps of 1.2 around medium = 12 px (what resvg's reference renderings use).
  static constexpr std::pair<std::string_view, int> kKeywords[] = {
      {"xx-small", -3}, {"x-small", -2}, {"small", -1}, {"medium", 0}, {"large", 1}, {"x-large", 2},
      {"xx-large", 3}, {"xxx-large", 4}};
  for (const auto& [name, step] : kKeywords) {
    if (v == name) {
      out = 12 * std::pow(1.2, step);
      return true;
    }
  }
  if (v == "larger") out = parent * 1.2;
  else if (v == "smaller") out = parent / 1.2;
  else if (!css_length(v, parent, parent, dpi, out) || out < 0) return false;
  out = std::min(out, kMaxTextSize);
  return true;
}

bool parse_weight(std::string_view v, int parent, int& out) {
  if (v == "normal") out = 400;
  else if (v == "bold") out = 700;
  else if (v == "bolder") out = parent < 350 ? 400 : parent < 550 ? 700 : 900;
  else if (v == "lighter") out = parent < 550 ? 100 : parent < 750 ? 400 : 700;
  else {
    std::size_t pos = 0;
    double n = 0;
    if (scan_number(v, pos, n) != NumberScan::Ok || pos != v.size() || !(n >= 1 && n <= 1000)) return false;
    out = static_cast<int>(std::lround(n));
  }
  return true;
}

bool parse_stretch(std::string_view v, double& out) {
  static constexpr std::pair<std::string_view, double> kKeywords[] = {
      {"ultra-condensed", 50}, {"extra-condensed", 62.5}, {"condensed", 75}, {"semi-condensed", 87.5},
      {"normal", 100},         {"semi-expanded", 112.5},  {"expanded", 125}, {"extra-expanded", 150},
      {"ultra-expanded", 200}};
  for (const auto& [name, percent] : kKeywords) {
    if (v == name) {
      out = percent;
      return true;
    }
  }
  if (v.empty() || v.back() != '%') return false;
  return css_length(v, 0, 100, /*dpi: a percentage has none*/ 96, out) && out >= 0 && out <= 1000;
}

bool parse_slant(std::string_view v, std::uint8_t& out) {
  if (v == "normal") out = 0;
  else if (v == "italic") out = 1;
  else if (v == "oblique" || istarts_with(v, "oblique ")) out = 2;
  else return false;
  return true;
}

/// font-family: a comma-separated list of quoted strings or identifier sequences.
bool parse_families(std::string_view v, std::vector<std::string>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < v.size()) {
    while (i < v.size() && is_wsp(v[i])) ++i;
    if (i >= v.size()) break;
    std::string name;
    if (v[i] == '"' || v[i] == '\'') {
      const char q = v[i];
      const std::size_t close = v.find(q, i + 1);
      if (close == std::string_view::npos) return false;
      name = std::string(v.substr(i + 1, close - i - 1));
      i = close + 1;
      while (i < v.size() && is_wsp(v[i])) ++i;
      if (i < v.size() && v[i] != ',') return false;
    } else {
      const std::size_t comma = std::min(v.find(',', i), v.size());
      for (const std::string_view w : split_words(v.substr(i, comma - i))) {
        if (!name.empty()) name += ' ';
        name += w;
      }
      i = comma;
    }
    if (name.empty()) return false;
    out.push_back(std::move(name));
    if (i < v.size() && v[i] == ',') ++i;
  }
  return !out.empty();
}

/// font-feature-settings: normal | "tag" [integer | on | off], ... -> HarfBuzz syntax ("liga=0,smcp=1").
bool parse_feature_settings(std::string_view v, std::string& out) {
  out.clear();
  if (v == "normal") return true;
  std::size_t i = 0;
  while (i < v.size()) {
    while (i < v.size() && (is_wsp(v[i]) || v[i] == ',')) ++i;
    if (i >= v.size()) break;
    if (v[i] != '"' && v[i] != '\'') return false;
    const char q = v[i];
    const std::size_t close = v.find(q, i + 1);
    if (close == std::string_view::npos || close - i - 1 != 4) return false;
    const std::string_view tag = v.substr(i + 1, 4);
    if (!std::all_of(tag.begin(), tag.end(), [](char c) { return c >= 0x20 && c <= 0x7e; })) return false;
    i = close + 1;
    const std::size_t end = std::min(v.find(',', i), v.size());
    const std::string_view arg = trim(v.substr(i, end - i));
    long value = 1;
    if (arg == "off") value = 0;
    else if (arg.empty() || arg == "on") value = 1;
    else {
      std::size_t pos = 0;
      double n = 0;
      if (scan_number(arg, pos, n) != NumberScan::Ok || pos != arg.size() || n < 0 || n > 65535 || n != std::floor(n))
        return false;
      value = static_cast<long>(n);
    }
    if (!out.empty()) out += ',';
    out += std::string(tag) + "=" + std::to_string(value);
    i = end;
  }
  return true;
}

/// font-variation-settings: normal | "tag" number, ...
bool parse_variation_settings(std::string_view v, std::vector<std::pair<std::uint32_t, double>>& out) {
  std::vector<std::pair<std::uint32_t, double>> list;
  if (v != "normal") {
    std::size_t i = 0;
    while (i < v.size()) {
      while (i < v.size() && (is_wsp(v[i]) || v[i] == ',')) ++i;
      if (i >= v.size()) break;
      if (v[i] != '"' && v[i] != '\'') return false;
      const std::size_t close = v.find(v[i], i + 1);
      if (close == std::string_view::npos || close - i - 1 != 4) return false;
      std::uint32_t tag = 0;
      for (std::size_t k = i + 1; k < close; ++k) tag = tag << 8 | static_cast<unsigned char>(v[k]);
      i = close + 1;
      const std::size_t end = std::min(v.find(',', i), v.size());
      const std::string_view number = trim(v.substr(i, end - i));
      std::size_t pos = 0;
      double d = 0;
      if (scan_number(number, pos, d) != NumberScan::Ok || pos != number.size() || !std::isfinite(d)) return false;
      list.emplace_back(tag, d);
      i = end;
    }
  }
  out = std::move(list);
  return true;
}

bool parse_baseline(std::string_view v, Baseline& out) {
  static constexpr std::pair<std::string_view, Baseline> kKeywords[] = {
      {"auto", Baseline::Auto},
      {"baseline", Baseline::Alphabetic},
      {"alphabetic", Baseline::Alphabetic},
      {"middle", Baseline::Middle},
      {"central", Baseline::Central},
      {"hanging", Baseline::Hanging},
      {"mathematical", Baseline::Mathematical},
      {"text-before-edge", Baseline::TextBeforeEdge},
      {"before-edge", Baseline::TextBeforeEdge},
      {"text-top", Baseline::TextBeforeEdge},
      {"text-after-edge", Baseline::TextAfterEdge},
      {"after-edge", Baseline::TextAfterEdge},
      {"text-bottom", Baseline::TextAfterEdge},
      {"ideographic", Baseline::Ideographic}};
  for (const auto& [name, value] : kKeywords) {
    if (v == name) {
      out = value;
      return true;
    }
  }
  return false;
}

/// The `font` shorthand: [style] [variant] [weight] [stretch] size[/line-height] family-list.
bool apply_font_shorthand(std::string_view v, TextProperties& s, const TextProperties& parent, double dpi) {
  TextProperties t = s;
  t.font_style = 0;
  t.small_caps = false;
  t.font_weight = 400;
  t.font_stretch = 100;
  t.kerning = true;  // the shorthand resets font-kerning too
  std::size_t i = 0;
  for (int words = 0; words < 5; ++words) {
    while (i < v.size() && is_wsp(v[i])) ++i;
    std::size_t end = i;
    while (end < v.size() && !is_wsp(v[end])) ++end;
    std::string_view word = v.substr(i, end - i);
    const std::size_t slash = word.find('/');
    if (word == "normal") {
    } else if (parse_slant(word, t.font_style)) {
    } else if (word == "small-caps") {
      t.small_caps = true;
    } else if (parse_weight(word, parent.font_weight, t.font_weight)) {
    } else if (parse_stretch(word, t.font_stretch) && word.back() != '%') {
    } else if (parse_font_size(word.substr(0, slash), parent.font_size, dpi, t.font_size)) {
      if (!parse_families(v.substr(end), t.font_family)) return false;
      s = t;
      return true;
    } else {
      return false;
    }
    i = end;
  }
  return false;
}

}  // namespace

bool is_text_attribute(std::string_view name) {
  // CSS-only: no presentation attribute of that name exists.
  return is_text_property(name) && name != "font-kerning" && name != "font-feature-settings" &&
         name != "font-variant-caps" && name != "font-variation-settings";
}

bool is_text_property(std::string_view name) {
  return std::find(std::begin(kTextProperties), std::end(kTextProperties), name) != std::end(kTextProperties);
}

bool apply_text_property(std::string_view name, std::string_view v, TextProperties& s, const TextProperties& parent,
                         double dpi) {
  if (name == "font") return apply_font_shorthand(v, s, parent, dpi);
  if (name == "font-family") return parse_families(v, s.font_family);
  if (name == "font-size") return parse_font_size(v, parent.font_size, dpi, s.font_size);
  if (name == "font-weight") return parse_weight(v, parent.font_weight, s.font_weight);
  if (name == "font-style") return parse_slant(v, s.font_style);
  if (name == "font-stretch") return parse_stretch(v, s.font_stretch);
  if (name == "font-variant" || name == "font-variant-caps") {
    if (v != "normal" && v != "small-caps") return false;
    s.small_caps = v == "small-caps";
    return true;
  }
  if (name == "font-kerning") {
    if (v != "auto" && v != "normal" && v != "none") return false;
    s.kerning = v != "none";
    return true;
  }
  if (name == "kerning") {  // SVG 1.1: auto, or a length (0 turns kerning off; others are not supported)
    if (v == "auto") {
      s.kerning = true;
      return true;
    }
    double d = 0;
    if (!css_length(v, s.font_size, s.font_size, dpi, d)) return false;
    s.kerning = d != 0;
    return true;
  }
  if (name == "font-variation-settings") return parse_variation_settings(v, s.variation_settings);
  if (name == "font-feature-settings") return parse_feature_settings(v, s.feature_settings);
  if (name == "letter-spacing" || name == "word-spacing") {
    double d = 0;
    const bool percent = !v.empty() && v.back() == '%';
    if (v != "normal" && !css_length(v, s.font_size, 100, dpi, d)) return false;
    (name == "letter-spacing" ? s.letter_spacing : s.word_spacing) = std::clamp(d, -kMaxTextSize, kMaxTextSize);
    (name == "letter-spacing" ? s.letter_spacing_percent : s.word_spacing_percent) = percent;
    return true;
  }
  if (name == "text-rendering") {
    if (v != "auto" && v != "optimizeSpeed" && v != "optimizeLegibility" && v != "geometricPrecision") return false;
    s.speed = v == "optimizeSpeed";
    return true;
  }
  if (name == "text-anchor") {
    if (v == "start") s.anchor = TextAnchor::Start;
    else if (v == "middle") s.anchor = TextAnchor::Middle;
    else if (v == "end") s.anchor = TextAnchor::End;
    else return false;
    return true;
  }
  if (name == "direction") {
    if (v != "ltr" && v != "rtl") return false;
    s.rtl = v == "rtl";
    return true;
  }
  if (name == "writing-mode") {
    if (v == "lr" || v == "lr-tb" || v == "rl" || v == "rl-tb" || v == "horizontal-tb") s.vertical = false;
    else if (v == "tb" || v == "tb-rl" || v == "vertical-rl" || v == "vertical-lr") s.vertical = true;
    else return false;
    return true;
  }
  if (name == "dominant-baseline") {
    if (v == "no-change" || v == "reset-size" || v == "use-script") return true;  // SVG 1.1: keep the inherited
    return parse_baseline(v, s.dominant_baseline);
  }
  if (name == "alignment-baseline") {
    if (v == "baseline") {  // the dominant baseline
      s.alignment_baseline = Baseline::Auto;
      return true;
    }
    return parse_baseline(v, s.alignment_baseline);
  }
  if (name == "baseline-shift") {
    if (v == "baseline") {
      s.shift = TextProperties::Shift::None;
    } else if (v == "sub" || v == "super") {
      s.shift = v == "sub" ? TextProperties::Shift::Sub : TextProperties::Shift::Super;
    } else {
      double d = 0;
      if (!css_length(v, s.font_size, s.font_size, dpi, d)) return false;
      s.shift = TextProperties::Shift::Length;
      s.shift_length = std::clamp(d, -kMaxTextSize, kMaxTextSize);
    }
    return true;
  }
  if (name == "text-decoration") {
    std::uint8_t d = 0;
    for (const std::string_view w : split_words(v)) {
      if (w == "underline") d |= TextProperties::kUnderline;
      else if (w == "overline") d |= TextProperties::kOverline;
      else if (w == "line-through") d |= TextProperties::kLineThrough;
      else if (w != "none") return false;
    }
    s.decoration = d;
    return true;
  }
  return false;
}

void inherit_text_property(std::string_view name, TextProperties& s, const TextProperties& p) {
  if (name == "font") {
    s.font_family = p.font_family;
    s.font_size = p.font_size;
    s.font_weight = p.font_weight;
    s.font_style = p.font_style;
    s.font_stretch = p.font_stretch;
    s.small_caps = p.small_caps;
  } else if (name == "font-family") s.font_family = p.font_family;
  else if (name == "font-size") s.font_size = p.font_size;
  else if (name == "font-weight") s.font_weight = p.font_weight;
  else if (name == "font-style") s.font_style = p.font_style;
  else if (name == "font-stretch") s.font_stretch = p.font_stretch;
  else if (name == "font-variant" || name == "font-variant-caps") s.small_caps = p.small_caps;
  else if (name == "font-kerning" || name == "kerning") s.kerning = p.kerning;
  else if (name == "font-feature-settings") s.feature_settings = p.feature_settings;
  else if (name == "font-variation-settings") s.variation_settings = p.variation_settings;
  else if (name == "letter-spacing") {
    s.letter_spacing = p.letter_spacing;
    s.letter_spacing_percent = p.letter_spacing_percent;
  } else if (name == "word-spacing") {
    s.word_spacing = p.word_spacing;
    s.word_spacing_percent = p.word_spacing_percent;
  }
  else if (name == "text-anchor") s.anchor = p.anchor;
  else if (name == "direction") s.rtl = p.rtl;
  else if (name == "writing-mode") s.vertical = p.vertical;
  else if (name == "text-rendering") s.speed = p.speed;
  else if (name == "dominant-baseline") s.dominant_baseline = p.dominant_baseline;
  else if (name == "alignment-baseline") s.alignment_baseline = p.alignment_baseline;
  else if (name == "baseline-shift") {
    s.shift = p.shift;
    s.shift_length = p.shift_length;
  } else if (name == "text-decoration") s.decoration = p.decoration;
}

}  // namespace vraster::svg::detail
