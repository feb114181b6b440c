// vraster fill-rules: the same drawing under every fill rule, side by side, optionally tinted by winding number.
//
//   1. read the SVG (svg_subset), scale it to a panel
//   2. per rule: render every item with that rule into a panel image (--aa fxaa: then the FXAA post-filter)
//   3. with --winding: tint each pixel by the winding number at its centre, and add a legend
//   4. paste the panels into one sheet with labels drawn in the built-in bitmap font
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "cli/bitmap_font.hpp"
#include "cli/cli.hpp"
#include "svg_subset/svg.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/vraster.hpp"

namespace vraster::cli {

void warn_about_exact_fallbacks(Renderer& renderer) { warn_about_exact_fallbacks(renderer.rasterizer().exact_fallbacks()); }
void warn_about_exact_fallbacks(std::uint64_t n, std::ostream& out) {
  if (n > 0) {
    out << "vraster: warning: " << n << " fill(s) had more than " << Rasterizer::kMaxExactCrossings
              << " edge crossings inside pixel rows (the exact-mode work limit) and were drawn with --aa analytic "
                 "(non-exterior as non-zero) instead\n";
  }
}
namespace {

constexpr FillRule kRules[] = {FillRule::EvenOdd,  FillRule::NonZero,  FillRule::NonExterior,
                               FillRule::Positive, FillRule::Negative, FillRule::AbsGeq2};
constexpr Color kInk = {0.12f, 0.16f, 0.22f, 1.f};

Color tint_for(int w) {
  switch (w) {
    case 1: return Color::rgb8(158, 202, 255);
    case 2: return Color::rgb8(152, 226, 160);
    case 3: return Color::rgb8(255, 230, 128);
    case -1: return Color::rgb8(255, 186, 140);
    case -2: return Color::rgb8(240, 160, 210);
    case -3: return Color::rgb8(200, 170, 255);
    default: return w > 0 ? Color::rgb8(210, 210, 210) : Color::rgb8(170, 170, 170);
  }
}

// Winding number at every pixel centre (half-open rule on y, as the aliased rasterizer uses).
std::vector<int> winding_map(const Polylines& lines, int width, int height) {
  std::vector<int> map(static_cast<std::size_t>(width) * height, 0);
  std::vector<std::pair<double, int>> crossings;
  for (int y = 0; y < height; ++y) {
    const double sy = y + 0.5;
    crossings.clear();
    lines.for_each_segment([&](Point p, Point q) {
      const bool down = p.y <= sy && sy < q.y, up = q.y <= sy && sy < p.y;
      if (down || up) crossings.emplace_back(p.x + (sy - p.y) * (q.x - p.x) / (q.y - p.y), down ? 1 : -1);
    });
    std::sort(crossings.begin(), crossings.end());
    int w = 0;
    std::size_t ci = 0;
    for (int x = 0; x < width; ++x) {
      while (ci < crossings.size() && crossings[ci].first <= x + 0.5) w += crossings[ci++].second;
      map[static_cast<std::size_t>(y) * width + x] = w;
    }
  }
  return map;
}

void paste(Image& sheet, const Image& panel, int ox, int oy) {
  for (int y = 0; y < panel.height; ++y) {
    std::copy(panel.pixel(0, y), panel.pixel(0, y) + panel.width * 4, sheet.pixel(ox, oy + y));
  }
}

void frame(Image& sheet, int x0, int y0, int w, int h) {
  const std::uint8_t grey[4] = {150, 150, 150, 255};
  for (int x = x0 - 1; x <= x0 + w; ++x) {
    std::copy(grey, grey + 4, sheet.pixel(x, y0 - 1));
    std::copy(grey, grey + 4, sheet.pixel(x, y0 + h));
  }
  for (int y = y0 - 1; y <= y0 + h; ++y) {
    std::copy(grey, grey + 4, sheet.pixel(x0 - 1, y));
    std::copy(grey, grey + 4, sheet.pixel(x0 + w, y));
  }
}

}  // namespace

int run_fill_rules(int argc, char** argv) {
  std::string input, output;
  bool winding = false;
  AntiAliasMethod aa{AntiAlias::Exact, false};
  int panel_size = 240;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw UsageError{std::string(arg) + " needs a value"};
      return argv[++i];
    };
    if (arg == "-o" || arg == "--output") {
      output = value();
    } else if (arg == "--winding") {
      winding = true;
    } else if (arg == "--aa") {
      const auto v = value();
      if (!parse_anti_alias_method(v, aa)) throw UsageError{"--aa: unknown mode " + quoted(v)};
    } else if (arg == "--panel") {
      const std::string v(value());
      panel_size = std::atoi(v.c_str());
      if (panel_size < 32 || panel_size > 2048) throw UsageError{"--panel must be from 32 to 2048 pixels"};
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError{"fill-rules: unknown option " + quoted(arg)};
    } else if (input.empty()) {
      input = arg;
    } else {
      throw UsageError{"fill-rules: more than one input file given"};
    }
  }
  if (input.empty()) throw UsageError{"fill-rules: no input file"};
  if (output.empty()) throw UsageError{"fill-rules: no output file (-o SHEET.png)"};

  const svg::Document doc = svg::load_svg(input);
  for (const std::string& w : doc.warnings) std::cerr << printable(input, 1024) << ":" << w << "\n";
  const double scale = static_cast<double>(panel_size) / std::max(doc.width, doc.height);
  const int pw = std::max(1, static_cast<int>(std::lround(doc.width * scale)));
  const int ph = std::max(1, static_cast<int>(std::lround(doc.height * scale)));
  const Affine to_panel = Affine::scale(scale);

  // Winding numbers of all items together, for the tint and the legend.
  std::vector<int> wmap;
  std::map<int, bool> windings_seen;
  if (winding) {
    Polylines all;
    for (const svg::DrawItem& item : doc.items) {
      if (item.is_fill()) flatten(item.path, to_panel * item.transform, FlattenOptions{}, all);
    }
    wmap = winding_map(all, pw, ph);
    for (int w : wmap) {
      if (w != 0) windings_seen[w] = true;
    }
  }

  const int margin = 12, label_h = 22, columns = 3;
  const int legend_h = winding ? 26 : 0;
  const int cell_w = pw + margin, cell_h = ph + label_h + margin;
  Image sheet(columns * cell_w + margin, 2 * cell_h + margin + legend_h);
  sheet.clear(Color{1, 1, 1, 1});
  Renderer renderer;
  for (int k = 0; k < 6; ++k) {
    Image panel(pw, ph);
    panel.clear(Color{1, 1, 1, 1});
    if (winding) {
      for (int y = 0; y < ph; ++y) {
        for (int x = 0; x < pw; ++x) {
          const int w = wmap[static_cast<std::size_t>(y) * pw + x];
          if (w == 0) continue;
          const Color c = tint_for(w);
          std::uint8_t* p = panel.pixel(x, y);
          p[0] = static_cast<std::uint8_t>(c.r * 255);
          p[1] = static_cast<std::uint8_t>(c.g * 255);
          p[2] = static_cast<std::uint8_t>(c.b * 255);
        }
      }
    }
    FillOptions options;
    options.rule = kRules[k];
    options.aa = aa.coverage;
    for (const svg::DrawItem& item : doc.items) {
      if (!item.is_fill()) continue;  // the sheet compares fill rules: strokes are left out
      const Color color = winding ? kInk.with_alpha(0.55f) : item.color;
      renderer.fill(panel, item.path, to_panel * item.transform, color, options);
    }
    post_filter(aa, panel);  // fxaa: each panel is a finished image (its frame and label are drawn after)
    const int ox = margin + (k % columns) * cell_w, oy = margin + (k / columns) * cell_h;
    paste(sheet, panel, ox, oy);
    frame(sheet, ox, oy, pw, ph);
    const std::string_view name = to_string(kRules[k]);
    draw_label(sheet, ox + (pw - label_width(name, 2)) / 2, oy + ph + 5, name, kInk, 2);
  }
  if (winding) {
    int x = margin;
    const int y = 2 * cell_h + margin;
    draw_label(sheet, x, y + 4, "winding:", kInk, 1);
    x += label_width("winding:") + 8;
    for (const auto& [w, seen] : windings_seen) {
      const Color c = tint_for(w);
      for (int dy = 0; dy < 12; ++dy) {
        for (int dx = 0; dx < 12; ++dx) {
          if (x + dx >= sheet.width) continue;
          std::uint8_t* p = sheet.pixel(x + dx, y + 2 + dy);
          p[0] = static_cast<std::uint8_t>(c.r * 255);
          p[1] = static_cast<std::uint8_t>(c.g * 255);
          p[2] = static_cast<std::uint8_t>(c.b * 255);
        }
      }
      const std::string label = std::to_string(w);
      draw_label(sheet, x + 16, y + 4, label, kInk, 1);
      x += 16 + label_width(label) + 10;
    }
  }
  warn_about_exact_fallbacks(renderer);
  write_png(output, sheet);
  std::cout << "vraster fill-rules: wrote " << output << "\n";
  return 0;
}

}  // namespace vraster::cli
