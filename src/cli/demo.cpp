// The embedded demo: an SVG scene (fill rules, curves, arcs, transparency and fine detail in one picture) and a
// panel under it drawn through the canvas (gradients, clips, layers, blend modes, text).
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "cli/cli.hpp"
#include "svg_subset/draw.hpp"
#include "vraster/canvas.hpp"
#include "vraster/png.hpp"
#if VRASTER_WITH_TEXT
#include "vraster_text/canvas_text.hpp"
#endif

namespace vraster::cli {

std::string_view demo_svg() {
  return R"SVG(<svg xmlns="http://www.w3.org/2000/svg" width="640" height="400" viewBox="0 0 640 400">
  <!-- backdrop -->
  <path d="M0 0H640V400H0Z" fill="#f4f1ea"/>
  <path d="M0 300C160 250 320 360 640 290V400H0Z" fill="#d9e4dd"/>
  <!-- the same pentagram under both fill rules -->
  <g transform="translate(20 20)">
    <path d="M80 0L127 145L4 55H156L33 145Z" fill="#c0392b" fill-rule="evenodd"/>
  </g>
  <g transform="translate(190 20)">
    <path d="M80 0L127 145L4 55H156L33 145Z" fill="#c0392b" fill-rule="nonzero"/>
  </g>
  <!-- curves and arcs -->
  <path d="M380 40c40-40 120-40 160 0s40 120 0 160-120 40-160 0-40-120 0-160z" fill="#2e86c1" fill-opacity="0.85"/>
  <path d="M420 80a40 40 0 1 0 80 0a40 40 0 1 0-80 0zM440 80a20 20 0 1 1 40 0a20 20 0 1 1-40 0z"
        fill="#f7dc6f" fill-rule="evenodd"/>
  <path d="M560 30q60 50 0 100t0 100" fill="none"/>
  <path d="M560 40l60 0l-30 52z" fill="#8e44ad" transform="rotate(15 590 60)"/>
  <!-- translucent overlaps -->
  <path d="M40 230a60 60 0 1 0 120 0a60 60 0 1 0-120 0z" fill="#e74c3c" fill-opacity="0.5"/>
  <path d="M100 230a60 60 0 1 0 120 0a60 60 0 1 0-120 0z" fill="#27ae60" fill-opacity="0.5"/>
  <path d="M70 280a60 60 0 1 0 120 0a60 60 0 1 0-120 0z" fill="#3498db" fill-opacity="0.5"/>
  <!-- a fan of thin slivers: antialiasing keeps their area -->
  <g transform="translate(420 330)">
    <path d="M0 0L180 -100L180 -98.6Z M0 0L180 -80L180 -79.3Z M0 0L180 -60L180 -59.65Z M0 0L180 -40L180 -39.8Z
             M0 0L180 -20L180 -19.9Z M0 0L180 0L180 0.05Z" fill="#1b2631"/>
  </g>
  <!-- strokes: joins, caps, dashes, and widths below a pixel that thin out instead of vanishing -->
  <path d="M370 250l30-30 30 30 30-30 30 30" fill="none" stroke="#c0392b" stroke-width="9" stroke-linejoin="round"
        stroke-linecap="round"/>
  <path d="M370 285l30-30 30 30 30-30 30 30" fill="none" stroke="#2c3e50" stroke-width="9" stroke-linejoin="miter"
        stroke-linecap="square"/>
  <path d="M540 140c40 30-40 60 0 90s-40 60 0 90" fill="none" stroke="#8e44ad" stroke-width="4"
        stroke-dasharray="12 6 2 6" stroke-linecap="round"/>
  <path d="M20 385H250M20 390H250M20 395H250" fill="none" stroke="#1b2631" stroke-width="0.3"/>
  <!-- concentric rings -->
  <path d="M300 300m-70 0a70 70 0 1 0 140 0a70 70 0 1 0-140 0zm10 0a60 60 0 1 1 120 0a60 60 0 1 1-120 0z
           m10 0a50 50 0 1 0 100 0a50 50 0 1 0-100 0zm10 0a40 40 0 1 1 80 0a40 40 0 1 1-80 0z
           m10 0a30 30 0 1 0 60 0a30 30 0 1 0-60 0zm10 0a20 20 0 1 1 40 0a20 20 0 1 1-40 0z" fill="#117a65"/>
</svg>
)SVG";
}

}  // namespace vraster::cli

// ---- the canvas panel under the SVG scene ----

namespace vraster::cli {
namespace {

constexpr double kTau = 2 * std::numbers::pi;

Color hex(unsigned rgb, float alpha = 1) {
  return Color::rgb8(static_cast<int>(rgb >> 16), static_cast<int>(rgb >> 8 & 255), static_cast<int>(rgb & 255))
      .with_alpha(alpha);
}

// Text in the current fill paint, left-aligned at x or centred on it (nothing when the text library is not built).
#if VRASTER_WITH_TEXT
void label(Canvas& c, std::string_view text, double x, double y, double size, bool centred) {
  static const text::FontList fonts = text::FontList::default_list();
  text::CanvasFont font;
  font.fonts = fonts;
  font.style.size = size;
  font.align = centred ? text::TextAlign::Center : text::TextAlign::Left;
  text::fill_text(c, font, text, x, y);
}
#else
void label(Canvas&, std::string_view, double, double, double, bool) {}
#endif

}  // namespace

void draw_canvas_panel(Canvas& c, double top, double width, double height) {
  c.save();
  c.translate(0, top);
  // A banner with a horizontal gradient.
  Paint banner = Paint::linear({0, 0}, {width, 0});
  banner.add_stop(0, hex(0x1b2631));
  banner.add_stop(0.5, hex(0x2e4053));
  banner.add_stop(1, hex(0x512e5f));
  c.set_fill_paint(banner);
  c.fill_rect(0, 0, width, height);
  c.set_fill_color(hex(0xffffff));
  label(c, "drawn through vraster::Canvas: gradients, clips, layers, blend modes, text", 20, 26, 15,
        false);

  // Blend modes: each swatch is a layer holding a blue square and an orange disc drawn with the operator.
  static constexpr CompositeOp kOps[] = {CompositeOp::SourceOver, CompositeOp::Multiply, CompositeOp::Screen,
                                         CompositeOp::Difference, CompositeOp::Xor, CompositeOp::DestinationOut};
  for (int i = 0; i < 6; ++i) {
    const double x = 20 + i * 72;
    c.begin_layer();
    c.set_fill_color(hex(0x2e86c1));
    c.fill_rect(x, 46, 44, 44);
    c.set_composite(kOps[i]);
    c.set_fill_color(hex(0xf39c12));
    c.begin_path();
    c.arc(x + 44, 90, 24, 0, kTau);
    c.fill();
    c.end_layer();
    c.set_fill_color(hex(0xecf0f1));
    label(c, to_string(kOps[i]), x + 34, 134, 11, true);
  }

  // A clip: a conic gradient seen through a star, with a radial highlight.
  c.save();
  c.begin_path();
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 ? 24 : 60, a = k * kTau / 10 - kTau / 4;
    const double px = 510 + r * std::cos(a), py = 100 + r * std::sin(a);
    k == 0 ? c.move_to(px, py) : c.line_to(px, py);
  }
  c.close_path();
  c.clip(FillRule::NonZero);
  Paint sweep = Paint::conic(0, {510, 100});
  sweep.add_stop(0, hex(0xe74c3c));
  sweep.add_stop(0.33, hex(0xf1c40f));
  sweep.add_stop(0.66, hex(0x27ae60));
  sweep.add_stop(1, hex(0xe74c3c));
  c.set_fill_paint(sweep);
  c.fill_rect(440, 30, 140, 140);
  Paint glow = Paint::radial({500, 85}, 0, {510, 100}, 60);
  glow.add_stop(0, hex(0xffffff, 0.8f));
  glow.add_stop(1, hex(0xffffff, 0));
  c.set_fill_paint(glow);
  c.fill_rect(440, 30, 140, 140);
  c.restore();

  // A layer at 50% opacity over a dashed outline: overlapping shapes inside it do not darken each other.
  c.set_stroke_color(hex(0xecf0f1));
  c.set_line_width(2);
  const double dashes[] = {8, 5};
  c.set_line_dash(dashes);
  c.stroke_rect(20.5, 150.5, 420, 56);
  c.set_line_dash({});
  c.begin_layer(0.5f);
  c.set_fill_color(hex(0xf7dc6f));
  c.begin_path();
  c.round_rect(30, 158, 200, 40, 12);
  c.fill();
  c.begin_path();
  c.ellipse(230, 178, 90, 20, 0, 0, kTau);
  c.fill();
  c.set_fill_color(hex(0x1b2631));
  label(c, "a layer at 50%", 130, 184, 16, true);
  c.end_layer();
  c.restore();
}

int run_demo(int argc, char** argv) {
  std::string output = "vraster-demo.png";
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "-o" || arg == "--output") {
      if (i + 1 >= argc) throw UsageError{std::string(arg) + " needs a value"};
      output = argv[++i];
    } else {
      throw UsageError{"demo: unknown argument " + quoted(arg)};
    }
  }
  const svg::Tree tree = svg::parse_svg_tree(demo_svg(), "<demo>");
  const auto [width, height] = svg::tree_output_size(tree);
  Image image(width, height + kDemoPanelHeight);
  image.clear(Color{1, 1, 1, 1});
  {
    Canvas canvas(image);
    svg::draw_tree(tree, canvas);
    draw_canvas_panel(canvas, height, width, kDemoPanelHeight);
  }
  write_png(output, image);
  std::cout << "vraster demo: wrote " << output << " (" << image.width << "x" << image.height << ")\n";
  return 0;
}

}  // namespace vraster::cli
