// Sample: the poster of samples/poster.c drawn through the C++ canvas (vraster/canvas.hpp) and canvas text
// (vraster_text/canvas_text.hpp): the same calls, the same pixels.
//
//   poster_cpp [OUT.png]
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "vraster/canvas.hpp"
#include "vraster/error.hpp"
#include "vraster/png.hpp"
#include "vraster_text/canvas_text.hpp"

using namespace vraster;

namespace {

constexpr int kWidth = 480, kHeight = 320;
constexpr double kPi = std::numbers::pi;

Color rgb(double r, double g, double b, double a = 1) {
  return {static_cast<float>(r), static_cast<float>(g), static_cast<float>(b), static_cast<float>(a)};
}

void draw(Canvas& c) {
  // Sky: a vertical gradient over everything.
  Paint sky = Paint::linear({0, 0}, {0, kHeight});
  sky.add_stop(0, rgb(20 / 255.0, 30 / 255.0, 60 / 255.0));
  sky.add_stop(1, rgb(90 / 255.0, 30 / 255.0, 90 / 255.0));
  c.set_fill_paint(sky);
  c.fill_rect(0, 0, kWidth, kHeight);

  // The frame: sun and hills clipped to a rounded rectangle (the sun reaches past its right edge).
  c.save();
  c.begin_path();
  c.round_rect(40, 40, 400, 200, 24);
  c.clip(FillRule::NonZero);
  c.set_fill_color(rgb(1, 1, 1, 0.08));  // the frame itself, faintly
  c.fill(FillRule::NonZero);
  Paint sun = Paint::radial({420, 70}, 0, {420, 70}, 80);
  sun.add_stop(0, rgb(1, 0.95, 0.6));
  sun.add_stop(0.6, rgb(1, 0.6, 0.2));
  sun.add_stop(1, rgb(1, 0.3, 0.1, 0));
  c.set_fill_paint(sun);
  c.begin_path();
  c.arc(420, 70, 80, 0, 2 * kPi);
  c.fill(FillRule::NonZero);
  Paint hills = Paint::linear({0, 150}, {0, 240});
  hills.add_stop(0, rgb(0.2, 0.5, 0.3));
  hills.add_stop(1, rgb(0.05, 0.2, 0.1));
  c.set_fill_paint(hills);
  c.begin_path();
  c.move_to(40, 240);
  c.cubic_to(120, 120, 200, 230, 280, 170);
  c.cubic_to(340, 130, 400, 190, 440, 160);
  c.line_to(440, 240);
  c.close_path();
  c.fill(FillRule::NonZero);
  c.restore();

  // A layer at 70% opacity: three discs blended with "screen" among themselves, then composited as one.
  c.begin_layer(0.7f);
  c.set_composite(CompositeOp::Screen);
  const double disc_x[3] = {190, 226, 208}, disc_y[3] = {92, 92, 123};
  for (int i = 0; i < 3; ++i) {
    c.set_fill_color(rgb(i == 0, i == 1, i == 2));
    c.begin_path();
    c.arc(disc_x[i], disc_y[i], 34, 0, 2 * kPi);
    c.fill(FillRule::NonZero);
  }
  c.end_layer();

  // A conic-gradient ring.
  Paint ring = Paint::conic(0, {100, 200});
  ring.add_stop(0, rgb(1, 0.2, 0.2));
  ring.add_stop(0.33, rgb(1, 0.9, 0.2));
  ring.add_stop(0.66, rgb(0.2, 0.6, 1));
  ring.add_stop(1, rgb(1, 0.2, 0.2));
  c.set_stroke_paint(ring);
  c.set_line_width(12);
  c.begin_path();
  c.arc(100, 200, 26, 0, 2 * kPi);
  c.stroke();

  // A dashed border with round caps.
  c.set_stroke_color(rgb(1, 1, 1, 0.8));
  c.set_line_width(3);
  c.set_line_cap(LineCap::Round);
  const double dashes[2] = {12, 6};
  c.set_line_dash(dashes);
  c.set_line_dash_offset(0);
  c.stroke_rect(10, 10, kWidth - 20, kHeight - 20);
  c.set_line_dash({});

  // The title: centred on its alphabetic baseline, a gradient fill, a soft shadow.
  Paint title = Paint::linear({120, 0}, {360, 0});
  title.add_stop(0, rgb(1, 1, 1));
  title.add_stop(1, rgb(1, 0.8, 0.4));
  text::CanvasFont font;
  font.style.size = 40;
  font.align = text::TextAlign::Center;
  c.set_shadow({rgb(0, 0, 0, 0.6), 2, 3, 4});
  c.set_fill_paint(title);
  text::fill_text(c, font, "vraster canvas", kWidth / 2.0, 292);
  c.set_shadow({});
}

void probe(const Image& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  std::printf("pixel %d,%d = %d %d %d %d\n", x, y, p[0], p[1], p[2], p[3]);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "poster.png";
  try {
    Image image(kWidth, kHeight);
    {
      Canvas canvas(image);
      draw(canvas);
    }
    write_png(out, image);
    probe(image, 2, 160);
    probe(image, 2, 70);
    probe(image, 450, 70);
    probe(image, 420, 70);
    std::printf("wrote %s\n", out.c_str());
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "poster_cpp: %s\n", e.what());
    return 2;
  }
}
