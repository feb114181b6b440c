// Text on the canvas: placement by alignment and baseline against the font's own metrics and the layout, pixels
// equal to filling the layout's outlines directly, paint and transform applied, bad numbers ignored.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "vraster/canvas.hpp"
#include "vraster/renderer.hpp"
#include "vraster_text/canvas_text.hpp"
#include "vraster_text/render.hpp"

using namespace vraster;
using namespace vraster::text;

namespace {

CanvasFont font_of(double size, TextAlign align = TextAlign::Start, TextBaseline baseline = TextBaseline::Alphabetic) {
  CanvasFont f;
  f.style.size = size;
  f.align = align;
  f.baseline = baseline;
  return f;
}

// Alpha sum and the first / last columns and rows holding any ink.
struct Ink {
  long sum = 0;
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
};
Ink ink_of(const Image& image) {
  Ink ink;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const int a = image.pixel(x, y)[3];
      if (a == 0) continue;
      ink.sum += a;
      ink.x0 = std::min(ink.x0, x), ink.x1 = std::max(ink.x1, x);
      ink.y0 = std::min(ink.y0, y), ink.y1 = std::max(ink.y1, y);
    }
  }
  return ink;
}

int max_diff(const Image& a, const Image& b) {
  int m = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) m = std::max(m, std::abs(a.data[i] - b.data[i]));
  return m;
}

}  // namespace

TEST(CanvasText, MeasureMatchesTheLayoutAndTheFontMetrics) {
  const CanvasFont f = font_of(32);
  const CanvasTextMetrics m = measure_text(f, "Typography");
  const TextMetrics layout = text::measure_text("Typography", f.fonts, f.style);
  const FontMetrics fm = f.fonts.fonts[0]->metrics(32);
  EXPECT_DOUBLE_EQ(m.width, layout.advance);
  EXPECT_GT(m.width, 100);
  EXPECT_DOUBLE_EQ(m.font_ascent, -fm.ascender);
  EXPECT_DOUBLE_EQ(m.font_descent, fm.descender);
  EXPECT_DOUBLE_EQ(m.actual_ascent, -layout.ink.y0);  // "T" and "h" reach up, "y" "p" "g" down
  EXPECT_DOUBLE_EQ(m.actual_descent, layout.ink.y1);
  EXPECT_GT(m.actual_descent, 0);
}

TEST(CanvasText, BaselinesMoveTheAnchorToTheirLine) {
  const FontMetrics fm = FontList::default_list().fonts[0]->metrics(20);
  auto at = [](TextBaseline b) { return measure_text(font_of(20, TextAlign::Start, b), "Hx"); };
  EXPECT_NEAR(at(TextBaseline::Top).font_ascent, 0, 1e-9);      // the anchor is on the ascender line
  EXPECT_NEAR(at(TextBaseline::Bottom).font_descent, 0, 1e-9);  // ... on the descender line
  EXPECT_NEAR(at(TextBaseline::Ideographic).font_descent, 0, 1e-9);
  const CanvasTextMetrics middle = at(TextBaseline::Middle);
  EXPECT_NEAR(middle.font_ascent, middle.font_descent, 1e-9);  // half way between them
  EXPECT_NEAR(at(TextBaseline::Hanging).font_ascent, -0.2 * fm.ascender, 1e-9);
  EXPECT_NEAR(at(TextBaseline::Alphabetic).font_ascent, -fm.ascender, 1e-9);
}

TEST(CanvasText, AlignmentsMoveTheAnchorAlongTheAdvance) {
  auto at = [](TextAlign a, Direction d = Direction::Auto) {
    CanvasFont f = font_of(24, a);
    f.style.direction = d;
    return measure_text(f, "Wavy");
  };
  const CanvasTextMetrics left = at(TextAlign::Left);
  const double w = left.width;
  EXPECT_NEAR(at(TextAlign::Start).actual_left, left.actual_left, 1e-9);
  EXPECT_NEAR(at(TextAlign::Right).actual_left, left.actual_left + w, 1e-9);
  EXPECT_NEAR(at(TextAlign::End).actual_right, left.actual_right - w, 1e-9);
  EXPECT_NEAR(at(TextAlign::Center).actual_right, left.actual_right - w / 2, 1e-9);
  EXPECT_NEAR(at(TextAlign::Start, Direction::RightToLeft).actual_right, left.actual_right - w, 1e-6);
}

TEST(CanvasText, FillTextEqualsFillingTheLayoutOutlines) {
  const CanvasFont f = font_of(28);
  Image through_canvas(200, 60), direct(200, 60);
  {
    Canvas canvas(through_canvas);
    canvas.set_fill_color(Color::rgb8(10, 20, 200));
    fill_text(canvas, f, "Hello, AVA", 12, 40);
  }
  const TextLayout layout = layout_text("Hello, AVA", f.fonts, f.style, {}, {12, 40});
  Path outlines;
  TextRenderer::append_outlines(layout, outlines);
  Renderer().fill(direct, outlines, {}, Color::rgb8(10, 20, 200), {});
  EXPECT_GT(ink_of(direct).sum, 255 * 100);
  EXPECT_LE(max_diff(through_canvas, direct), 1);
}

TEST(CanvasText, CenteredTopTextSitsOnItsAnchor) {
  Image image(200, 80);
  Canvas canvas(image);
  const CanvasFont f = font_of(30, TextAlign::Center, TextBaseline::Top);
  const CanvasTextMetrics m = measure_text(f, "MIM");  // symmetric letters: ink centred on the advance
  fill_text(canvas, f, "MIM", 100, 20);
  const Ink ink = ink_of(image);
  EXPECT_NEAR((ink.x0 + ink.x1 + 1) / 2.0, 100, 1.5);
  EXPECT_NEAR(ink.y0, 20 - m.actual_ascent, 1.0);  // the ink's top is where measure_text said
  EXPECT_GE(ink.y0, 20);                           // and below the ascender line (capitals are shorter)
}

TEST(CanvasText, StrokeTextOutlinesTheGlyphs) {
  Image filled(120, 60), stroked(120, 60);
  const CanvasFont f = font_of(40);
  {
    Canvas canvas(filled);
    fill_text(canvas, f, "O", 20, 45);
  }
  Canvas canvas(stroked);
  canvas.set_line_width(1);
  stroke_text(canvas, f, "O", 20, 45);
  const Ink a = ink_of(filled), b = ink_of(stroked);
  EXPECT_GT(b.sum, 0);
  EXPECT_LT(b.sum, a.sum);  // a thin outline holds less ink than the solid letter
  EXPECT_NEAR(a.x0, b.x0, 1);
  EXPECT_NEAR(a.x1, b.x1, 1);
}

TEST(CanvasText, PaintTransformAndBadNumbers) {
  Image image(200, 60);
  Canvas canvas(image);
  Paint gradient = Paint::linear({0, 0}, {200, 0});
  gradient.add_stop(0, Color::rgb8(255, 0, 0));
  gradient.add_stop(1, Color::rgb8(0, 0, 255));
  canvas.set_fill_paint(gradient);
  const CanvasFont f = font_of(40);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  fill_text(canvas, f, "IIIIIIIIIIIIIII", nan, 40);
  fill_text(canvas, f, "IIIIIIIIIIIIIII", 0, std::numeric_limits<double>::infinity());
  fill_text(canvas, f, "IIIIIIIIIIIIIII", 0, 40, -5);
  EXPECT_EQ(ink_of(image).sum, 0);
  fill_text(canvas, f, "IIIIIIIIIIIIIII", 4, 45);
  // Opaque ink on the left is red, on the right blue: the fill paint colours text as any shape.
  int reddest = 0, bluest = 0;
  for (int x = 0; x < 200; ++x) {
    const std::uint8_t* p = image.pixel(x, 30);
    if (p[3] == 255 && x < 40) reddest = std::max(reddest, p[0] - p[2]);
    if (p[3] == 255 && x > 120) bluest = std::max(bluest, p[2] - p[0]);
  }
  EXPECT_GT(reddest, 100);
  EXPECT_GT(bluest, 50);
  // max_width squeezes: the same text limited to 50 px has its ink within about 50 px of the anchor.
  Image squeezed(200, 60);
  Canvas narrow(squeezed);
  fill_text(narrow, f, "IIIIIIIIIIIIIII", 10, 45, 50);
  const Ink ink = ink_of(squeezed);
  EXPECT_GE(ink.x0, 10);
  EXPECT_LE(ink.x1, 61);
  // Under a transform: scaled 2x, the ink is twice as tall.
  Image big(200, 120);
  Canvas scaled(big);
  scaled.scale(2, 2);
  fill_text(scaled, f, "I", 10, 50);
  Image small(200, 120);
  Canvas plain(small);
  fill_text(plain, f, "I", 10, 50);
  const Ink s = ink_of(small), l = ink_of(big);
  EXPECT_NEAR(l.y1 - l.y0 + 1, 2 * (s.y1 - s.y0 + 1), 2);
}
