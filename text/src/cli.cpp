// `vraster text`: text -> layout -> image sized to fit -> PNG.
#include "vraster_text/cli.hpp"

#include "vraster/fxaa.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vraster/error.hpp"
#include "vraster/png.hpp"
#include "vraster_text/font_db.hpp"
#include "vraster_text/text.hpp"

namespace vraster::text {
namespace {

constexpr const char* kUsage =
    "usage: vraster text \"TEXT\" -o OUT.png [--font FILE]... [--face-index N] [--size PX] [--width W]\n"
    "                    [--align left|center|right] [--line-height PX] [--color C] [--background C]\n"
    "                    [--aa MODE] [--features F] [--lang L] [--script S] [--dir auto|ltr|rtl]\n"
    "                    [--hinting none|light] [--margin PX] [--font-dir DIR]... [--no-system-fonts]\n"
    "  --font may be given more than once: later fonts are fallbacks, then the embedded Noto Sans; characters\n"
    "  none of them has fall back to the fonts of --font-dir directories, then to the system's (fontconfig).\n"
    "  C: #rgb, #rrggbb, #rrggbbaa, black, white, red, green, blue, gray, transparent\n"
    "  MODE: none | analytic | exact | ssaa-2|4|8|16 | msaa-4|8|16 | fxaa\n";

struct UsageError {
  std::string message;
};

double parse_number(std::string_view flag, std::string_view text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
    throw UsageError{std::string(flag) + ": " + quoted(text) + " is not a number"};
  }
  return v;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::optional<Color> parse_color(std::string_view s) {
  struct Named {
    std::string_view name;
    Color color;
  };
  static constexpr Named kNames[] = {
      {"black", Color::rgb8(0, 0, 0)},       {"white", Color::rgb8(255, 255, 255)},
      {"red", Color::rgb8(255, 0, 0)},       {"green", Color::rgb8(0, 128, 0)},
      {"blue", Color::rgb8(0, 0, 255)},      {"gray", Color::rgb8(128, 128, 128)},
      {"grey", Color::rgb8(128, 128, 128)},  {"transparent", Color::transparent()},
  };
  for (const auto& n : kNames) {
    if (s == n.name) return n.color;
  }
  if (s.empty() || s[0] != '#') return std::nullopt;
  s.remove_prefix(1);
  std::vector<int> d;
  for (char c : s) {
    const int v = hex_digit(c);
    if (v < 0) return std::nullopt;
    d.push_back(v);
  }
  if (d.size() == 3 || d.size() == 4) {
    const int a = d.size() == 4 ? d[3] * 17 : 255;
    return Color::rgb8(d[0] * 17, d[1] * 17, d[2] * 17, a);
  }
  if (d.size() == 6 || d.size() == 8) {
    const int a = d.size() == 8 ? d[6] * 16 + d[7] : 255;
    return Color::rgb8(d[0] * 16 + d[1], d[2] * 16 + d[3], d[4] * 16 + d[5], a);
  }
  return std::nullopt;
}

struct TextArgs {
  std::string text;
  bool have_text = false;
  std::string output;
  std::vector<std::string> fonts;
  std::vector<std::string> font_dirs;
  bool system_fonts = true;
  int face_index = 0;
  TextStyle style;
  LayoutOptions layout;
  GlyphRenderOptions render;
  AntiAliasMethod aa;  ///< --aa: render.aa is its coverage mode
  Color color = Color::rgb8(0, 0, 0);
  Color background = Color::transparent();
  double margin = 8;
};

TextArgs parse_args(int argc, char** argv) {
  TextArgs a;
  std::vector<std::string_view> args(argv + 2, argv + argc);
  std::size_t i = 0;
  auto value = [&](std::string_view flag) -> std::string_view {
    if (i >= args.size()) throw UsageError{std::string(flag) + " needs a value"};
    return args[i++];
  };
  while (i < args.size()) {
    const std::string_view arg = args[i++];
    if (arg == "-o" || arg == "--output") {
      a.output = value(arg);
    } else if (arg == "--font") {
      a.fonts.emplace_back(value(arg));
    } else if (arg == "--font-dir") {
      a.font_dirs.emplace_back(value(arg));
    } else if (arg == "--no-system-fonts") {
      a.system_fonts = false;
    } else if (arg == "--face-index") {
      const double v = parse_number(arg, value(arg));
      if (!(v >= 0 && v <= 65535) || v != std::floor(v)) throw UsageError{"--face-index must be 0 to 65535"};
      a.face_index = static_cast<int>(v);
    } else if (arg == "--size") {
      a.style.size = parse_number(arg, value(arg));
    } else if (arg == "--width") {
      a.layout.max_width = parse_number(arg, value(arg));
      if (!(a.layout.max_width >= 0 && a.layout.max_width <= kMaxImageSide)) {
        throw UsageError{"--width must be between 0 and " + std::to_string(kMaxImageSide)};
      }
    } else if (arg == "--line-height") {
      a.layout.line_height = parse_number(arg, value(arg));
      if (!(a.layout.line_height >= 0 && a.layout.line_height <= kMaxImageSide)) {
        throw UsageError{"--line-height must be between 0 and " + std::to_string(kMaxImageSide)};
      }
    } else if (arg == "--margin") {
      a.margin = parse_number(arg, value(arg));
      if (!(a.margin >= 0 && a.margin <= 4096)) throw UsageError{"--margin must be between 0 and 4096"};
    } else if (arg == "--align") {
      const auto v = value(arg);
      if (v == "left") a.layout.align = Align::Left;
      else if (v == "center" || v == "centre") a.layout.align = Align::Center;
      else if (v == "right") a.layout.align = Align::Right;
      else throw UsageError{"--align: expected left, center or right, got " + quoted(v)};
    } else if (arg == "--dir") {
      const auto v = value(arg);
      if (v == "auto") a.style.direction = Direction::Auto;
      else if (v == "ltr") a.style.direction = Direction::LeftToRight;
      else if (v == "rtl") a.style.direction = Direction::RightToLeft;
      else throw UsageError{"--dir: expected auto, ltr or rtl, got " + quoted(v)};
    } else if (arg == "--hinting") {
      const auto v = value(arg);
      if (v == "none") a.render.hinting = Hinting::None;
      else if (v == "light") a.render.hinting = Hinting::Light;
      else throw UsageError{"--hinting: expected none or light, got " + quoted(v)};
    } else if (arg == "--color" || arg == "--background") {
      const auto v = value(arg);
      const auto c = parse_color(v);
      if (!c) throw UsageError{std::string(arg) + ": " + quoted(v) + " is not a colour"};
      (arg == "--color" ? a.color : a.background) = *c;
    } else if (arg == "--aa") {
      const auto v = value(arg);
      if (!parse_anti_alias_method(v, a.aa)) throw UsageError{"--aa: unknown mode " + quoted(v)};
      a.render.aa = a.aa.coverage;
    } else if (arg == "--features") {
      a.style.features = value(arg);
    } else if (arg == "--lang") {
      a.style.language = value(arg);
    } else if (arg == "--script") {
      a.style.script = value(arg);
    } else if (arg.size() > 1 && arg[0] == '-' ) {
      throw UsageError{"text: unknown option " + quoted(arg)};
    } else if (!a.have_text) {
      a.text = arg;
      a.have_text = true;
    } else {
      throw UsageError{"text: more than one text argument (quote the text)"};
    }
  }
  if (!a.have_text) throw UsageError{"text: no text given"};
  if (a.output.empty()) throw UsageError{"text: no output file (-o OUT.png)"};
  return a;
}

}  // namespace

std::string_view text_command_usage() { return kUsage; }

int run_text_command(int argc, char** argv) {
  try {
    if (argc < 2 || std::string_view(argv[1]) != "text") throw UsageError{"run_text_command: expected 'text'"};
    const TextArgs a = parse_args(argc, argv);
    FontList fonts;
    for (const std::string& f : a.fonts) fonts.add(Font::load_file(f, a.face_index));
    fonts.add(Font::load_default());
    // Fallbacks for what these fonts lack, from the same font database `vraster render` uses for SVG text.
    FontDb db;
    for (const std::string& dir : a.font_dirs) db.add_directory(dir);
    if (a.system_fonts) db.add_system_fonts();
    if (!db.faces().empty()) {
      const std::u32string text = decode_utf8(a.text);
      std::u32string missing;
      for (const char32_t c : text) {
        if (c >= 0x20 && std::none_of(fonts.fonts.begin(), fonts.fonts.end(), [&](const auto& f) { return f->has_glyph(c); }))
          missing.push_back(c);
      }
      if (!missing.empty()) {
        const FontList extra = db.fonts_for(FontQuery{}, missing);
        for (std::size_t i = 1; i < extra.fonts.size(); ++i) fonts.add(extra.fonts[i]);
        if (!extra.fonts.empty() && std::any_of(missing.begin(), missing.end(),
                                                [&](char32_t c) { return extra.fonts[0]->has_glyph(c); }))
          fonts.add(extra.fonts[0]);
      }
    }
    const TextLayout layout = layout_text(a.text, fonts, a.style, a.layout);
    // The image: the union of the logical box and the ink, plus the margin on every side.
    Rect box = layout.logical;
    if (!layout.glyphs.empty()) {
      box.include({layout.ink.x0, layout.ink.y0});
      box.include({layout.ink.x1, layout.ink.y1});
    }
    const double w = std::ceil(box.width() + 2 * a.margin), h = std::ceil(box.height() + 2 * a.margin);
    check_image_size(std::max(w, 1.0), std::max(h, 1.0));
    Image image(static_cast<int>(std::max(w, 1.0)), static_cast<int>(std::max(h, 1.0)));
    image.clear(a.background);
    TextRenderer renderer;
    // Integer translation: glyphs keep the subpixel phases layout gave them.
    const Affine place = Affine::translate(std::round(a.margin - box.x0), std::round(a.margin - box.y0));
    renderer.draw(image, layout, a.color, place, a.render);
    post_filter(a.aa, image);  // fxaa: the aliased drawing, then the filter
    write_png(a.output, image);
    return 0;
  } catch (const UsageError& e) {
    std::cerr << "vraster: " << printable(e.message, kMaxMessageBytes) << "\n" << kUsage;
    return 2;
  } catch (...) {
    std::cerr << "vraster: " << describe_current_exception() << "\n";
    return 2;
  }
}

}  // namespace vraster::text
