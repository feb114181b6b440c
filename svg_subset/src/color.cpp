// svg_subset: colour values (#rgb, #rgba, #rrggbb, #rrggbbaa, rgb(), rgba(), hsl(), hsla(), the 147 CSS/SVG
// colour keywords, transparent, none).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "scan.hpp"
#include "svg_subset/svg.hpp"

namespace vraster::svg {
namespace {

using detail::NumberScan;

struct NamedColor {
  std::string_view name;
  std::uint8_t r, g, b;
};

// The SVG 1.1 / CSS3 colour keywords, sorted by name for binary search.
// clang-format off
constexpr std::array<NamedColor, 147> kNamedColors = {{
    {"aliceblue", 240, 248, 255},       {"antiquewhite", 250, 235, 215},   {"aqua", 0, 255, 255},
    {"aquamarine", 127, 255, 212},      {"azure", 240, 255, 255},          {"beige", 245, 245, 220},
    {"bisque", 255, 228, 196},          {"black", 0, 0, 0},                {"blanchedalmond", 255, 235, 205},
    {"blue", 0, 0, 255},                {"blueviolet", 138, 43, 226},      {"brown", 165, 42, 42},
    {"burlywood", 222, 184, 135},       {"cadetblue", 95, 158, 160},       {"chartreuse", 127, 255, 0},
    {"chocolate", 210, 105, 30},        {"coral", 255, 127, 80},           {"cornflowerblue", 100, 149, 237},
    {"cornsilk", 255, 248, 220},        {"crimson", 220, 20, 60},          {"cyan", 0, 255, 255},
    {"darkblue", 0, 0, 139},            {"darkcyan", 0, 139, 139},         {"darkgoldenrod", 184, 134, 11},
    {"darkgray", 169, 169, 169},        {"darkgreen", 0, 100, 0},          {"darkgrey", 169, 169, 169},
    {"darkkhaki", 189, 183, 107},       {"darkmagenta", 139, 0, 139},      {"darkolivegreen", 85, 107, 47},
    {"darkorange", 255, 140, 0},        {"darkorchid", 153, 50, 204},      {"darkred", 139, 0, 0},
    {"darksalmon", 233, 150, 122},      {"darkseagreen", 143, 188, 143},   {"darkslateblue", 72, 61, 139},
    {"darkslategray", 47, 79, 79},      {"darkslategrey", 47, 79, 79},     {"darkturquoise", 0, 206, 209},
    {"darkviolet", 148, 0, 211},        {"deeppink", 255, 20, 147},        {"deepskyblue", 0, 191, 255},
    {"dimgray", 105, 105, 105},         {"dimgrey", 105, 105, 105},        {"dodgerblue", 30, 144, 255},
    {"firebrick", 178, 34, 34},         {"floralwhite", 255, 250, 240},    {"forestgreen", 34, 139, 34},
    {"fuchsia", 255, 0, 255},           {"gainsboro", 220, 220, 220},      {"ghostwhite", 248, 248, 255},
    {"gold", 255, 215, 0},              {"goldenrod", 218, 165, 32},       {"gray", 128, 128, 128},
    {"green", 0, 128, 0},               {"greenyellow", 173, 255, 47},     {"grey", 128, 128, 128},
    {"honeydew", 240, 255, 240},        {"hotpink", 255, 105, 180},        {"indianred", 205, 92, 92},
    {"indigo", 75, 0, 130},             {"ivory", 255, 255, 240},          {"khaki", 240, 230, 140},
    {"lavender", 230, 230, 250},        {"lavenderblush", 255, 240, 245},  {"lawngreen", 124, 252, 0},
    {"lemonchiffon", 255, 250, 205},    {"lightblue", 173, 216, 230},      {"lightcoral", 240, 128, 128},
    {"lightcyan", 224, 255, 255},       {"lightgoldenrodyellow", 250, 250, 210},
    {"lightgray", 211, 211, 211},       {"lightgreen", 144, 238, 144},     {"lightgrey", 211, 211, 211},
    {"lightpink", 255, 182, 193},       {"lightsalmon", 255, 160, 122},    {"lightseagreen", 32, 178, 170},
    {"lightskyblue", 135, 206, 250},    {"lightslategray", 119, 136, 153}, {"lightslategrey", 119, 136, 153},
    {"lightsteelblue", 176, 196, 222},  {"lightyellow", 255, 255, 224},    {"lime", 0, 255, 0},
    {"limegreen", 50, 205, 50},         {"linen", 250, 240, 230},          {"magenta", 255, 0, 255},
    {"maroon", 128, 0, 0},              {"mediumaquamarine", 102, 205, 170}, {"mediumblue", 0, 0, 205},
    {"mediumorchid", 186, 85, 211},     {"mediumpurple", 147, 112, 219},   {"mediumseagreen", 60, 179, 113},
    {"mediumslateblue", 123, 104, 238}, {"mediumspringgreen", 0, 250, 154}, {"mediumturquoise", 72, 209, 204},
    {"mediumvioletred", 199, 21, 133},  {"midnightblue", 25, 25, 112},     {"mintcream", 245, 255, 250},
    {"mistyrose", 255, 228, 225},       {"moccasin", 255, 228, 181},       {"navajowhite", 255, 222, 173},
    {"navy", 0, 0, 128},                {"oldlace", 253, 245, 230},        {"olive", 128, 128, 0},
    {"olivedrab", 107, 142, 35},        {"orange", 255, 165, 0},           {"orangered", 255, 69, 0},
    {"orchid", 218, 112, 214},          {"palegoldenrod", 238, 232, 170},  {"palegreen", 152, 251, 152},
    {"paleturquoise", 175, 238, 238},   {"palevioletred", 219, 112, 147},  {"papayawhip", 255, 239, 213},
    {"peachpuff", 255, 218, 185},       {"peru", 205, 133, 63},            {"pink", 255, 192, 203},
    {"plum", 221, 160, 221},            {"powderblue", 176, 224, 230},     {"purple", 128, 0, 128},
    {"red", 255, 0, 0},                 {"rosybrown", 188, 143, 143},      {"royalblue", 65, 105, 225},
    {"saddlebrown", 139, 69, 19},       {"salmon", 250, 128, 114},         {"sandybrown", 244, 164, 96},
    {"seagreen", 46, 139, 87},          {"seashell", 255, 245, 238},       {"sienna", 160, 82, 45},
    {"silver", 192, 192, 192},          {"skyblue", 135, 206, 235},        {"slateblue", 106, 90, 205},
    {"slategray", 112, 128, 144},       {"slategrey", 112, 128, 144},      {"snow", 255, 250, 250},
    {"springgreen", 0, 255, 127},       {"steelblue", 70, 130, 180},       {"tan", 210, 180, 140},
    {"teal", 0, 128, 128},              {"thistle", 216, 191, 216},        {"tomato", 255, 99, 71},
    {"turquoise", 64, 224, 208},        {"violet", 238, 130, 238},         {"wheat", 245, 222, 179},
    {"white", 255, 255, 255},           {"whitesmoke", 245, 245, 245},     {"yellow", 255, 255, 0},
    {"yellowgreen", 154, 205, 50},
}};
// clang-format on

static_assert(std::is_sorted(kNamedColors.begin(), kNamedColors.end(),
                             [](const NamedColor& a, const NamedColor& b) { return a.name < b.name; }),
              "colour table must stay sorted for binary search");

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = detail::to_lower(c);
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

/// #rgb, #rgba, #rrggbb, #rrggbbaa (the 4 and 8 digit forms are CSS Color 4, accepted because editors write them).
std::optional<Color> parse_hex(std::string_view digits) {
  if (digits.size() != 3 && digits.size() != 4 && digits.size() != 6 && digits.size() != 8) return std::nullopt;
  int v[8];
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if ((v[i] = hex_value(digits[i])) < 0) return std::nullopt;
  }
  switch (digits.size()) {
    case 3:
      return Color::rgb8(v[0] * 17, v[1] * 17, v[2] * 17);
    case 4:
      return Color::rgb8(v[0] * 17, v[1] * 17, v[2] * 17, v[3] * 17);
    case 6:
      return Color::rgb8(v[0] * 16 + v[1], v[2] * 16 + v[3], v[4] * 16 + v[5]);
    case 8:
      return Color::rgb8(v[0] * 16 + v[1], v[2] * 16 + v[3], v[4] * 16 + v[5], v[6] * 16 + v[7]);
    default:
      return std::nullopt;
  }
}

/// rgb(r, g, b) / rgba(r, g, b, a): channels as numbers 0..255 or percentages, alpha as 0..1 or a percentage.
/// Out-of-range values are clamped, as CSS says. Components may be separated by commas or whitespace. CSS Color 4:
/// the comma-separated (legacy) form takes three numbers or three percentages, never a mix of the two; the
/// space-separated form may mix them.
std::optional<Color> parse_rgb_function(std::string_view args) {
  float channel[4] = {0, 0, 0, 1};
  bool channel_percent[3] = {false, false, false};
  bool commas = false;
  std::size_t pos = 0;
  int count = 0;
  detail::skip_wsp(args, pos);
  while (pos < args.size() && count < 4) {
    if (count > 0) {
      const bool comma = detail::skip_comma_wsp(args, pos);
      commas = commas || comma;
      if (!comma && count == 3 && pos < args.size() && args[pos] == '/') {  // CSS 4 "rgb(r g b / a)"
        ++pos;
        detail::skip_wsp(args, pos);
      }
    }
    double v = 0;
    if (detail::scan_number(args, pos, v) != NumberScan::Ok) return std::nullopt;
    const bool percent = pos < args.size() && args[pos] == '%';
    if (percent) ++pos;
    if (count < 3) channel_percent[count] = percent;
    const double scale = percent ? 100.0 : (count == 3 ? 1.0 : 255.0);
    channel[count++] = static_cast<float>(std::clamp(v / scale, 0.0, 1.0));
    detail::skip_wsp(args, pos);
  }
  if (pos != args.size() || count < 3) return std::nullopt;
  const bool mixed = channel_percent[0] != channel_percent[1] || channel_percent[1] != channel_percent[2];
  if (commas && mixed) return std::nullopt;
  return Color{channel[0], channel[1], channel[2], channel[3]};
}

/// One channel of an HSL colour (CSS Color 3, section 4.2.4): m1, m2 from lightness and saturation, h in turns.
float hue_to_channel(double m1, double m2, double h) {
  h -= std::floor(h);
  double v = m1;
  if (h * 6 < 1)
    v = m1 + (m2 - m1) * h * 6;
  else if (h * 2 < 1)
    v = m2;
  else if (h * 3 < 2)
    v = m1 + (m2 - m1) * (2.0 / 3 - h) * 6;
  return static_cast<float>(v);
}

/// hsl(h, s%, l%) / hsla(h, s%, l%, a): hue in degrees (any value, wrapped; "deg" allowed), saturation and
/// lightness as percentages (or plain numbers, CSS 4) clamped to 0..100%, alpha as 0..1 or a percentage.
std::optional<Color> parse_hsl_function(std::string_view args) {
  double v[4] = {0, 0, 0, 1};
  std::size_t pos = 0;
  int count = 0;
  detail::skip_wsp(args, pos);
  while (pos < args.size() && count < 4) {
    if (count > 0) {
      const bool comma = detail::skip_comma_wsp(args, pos);
      if (!comma && count == 3 && pos < args.size() && args[pos] == '/') {
        ++pos;
        detail::skip_wsp(args, pos);
      }
    }
    double x = 0;
    if (detail::scan_number(args, pos, x) != NumberScan::Ok) return std::nullopt;
    if (count == 0 && args.substr(pos, 3) == "deg") pos += 3;
    const bool percent = pos < args.size() && args[pos] == '%';
    if (percent) ++pos;
    if (count == 1 || count == 2) x = std::clamp(x / 100, 0.0, 1.0);
    if (count == 3) x = std::clamp(percent ? x / 100 : x, 0.0, 1.0);
    if (!std::isfinite(x)) return std::nullopt;
    v[count++] = x;
    detail::skip_wsp(args, pos);
  }
  if (pos != args.size() || count < 3) return std::nullopt;
  const double h = v[0] / 360, sat = v[1], light = v[2];
  const double m2 = light <= 0.5 ? light * (sat + 1) : light + sat - light * sat;
  const double m1 = light * 2 - m2;
  return Color{hue_to_channel(m1, m2, h + 1.0 / 3), hue_to_channel(m1, m2, h), hue_to_channel(m1, m2, h - 1.0 / 3),
               static_cast<float>(v[3])};
}

}  // namespace

std::optional<Color> parse_color(std::string_view text, bool& is_none) {
  is_none = false;
  const std::string_view s = detail::trim(text);
  if (s.empty()) return std::nullopt;
  if (s[0] == '#') return parse_hex(s.substr(1));
  if (detail::iequals(s, "none")) {
    is_none = true;
    return std::nullopt;
  }
  if (detail::iequals(s, "transparent")) return Color::transparent();
  for (std::string_view fn : {std::string_view("rgb"), std::string_view("rgba")}) {
    if (detail::istarts_with(s, fn)) {
      std::size_t pos = fn.size();
      detail::skip_wsp(s, pos);  // CSS forbids space before '(' but old SVG files have it; harmless
      if (pos < s.size() && s[pos] == '(' && s.back() == ')') {
        return parse_rgb_function(s.substr(pos + 1, s.size() - pos - 2));
      }
    }
  }
  for (std::string_view fn : {std::string_view("hsl"), std::string_view("hsla")}) {
    if (detail::istarts_with(s, fn)) {
      std::size_t pos = fn.size();
      detail::skip_wsp(s, pos);
      if (pos < s.size() && s[pos] == '(' && s.back() == ')') {
        return parse_hsl_function(s.substr(pos + 1, s.size() - pos - 2));
      }
    }
  }
  // Keywords are ASCII and at most 20 letters; anything longer is not one.
  char lower[24];
  if (s.size() >= sizeof lower) return std::nullopt;
  for (std::size_t i = 0; i < s.size(); ++i) lower[i] = detail::to_lower(s[i]);
  const std::string_view key(lower, s.size());
  const auto it = std::lower_bound(kNamedColors.begin(), kNamedColors.end(), key,
                                   [](const NamedColor& c, std::string_view k) { return c.name < k; });
  if (it == kNamedColors.end() || it->name != key) return std::nullopt;
  return Color::rgb8(it->r, it->g, it->b);
}

}  // namespace vraster::svg
