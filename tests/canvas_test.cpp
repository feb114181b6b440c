// The canvas (src/canvas/): state stack, current-path semantics, clips, layers, operators outside the shape,
// shadows, images, pixels and hit testing, against tiny hand-made references and properties that must hold.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "vraster/canvas.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/vraster.hpp"

namespace vraster::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Image blank(int w, int h) {
  Image image(w, h);
  image.clear(Color::transparent());
  return image;
}

int max_diff(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) return 1 << 20;
  int worst = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) worst = std::max(worst, std::abs(int(a.data[i]) - int(b.data[i])));
  return worst;
}

// Premultiplied RGBA of one pixel as text (for failure messages).
std::string px(const Image& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  std::ostringstream s;
  s << "(" << int(p[0]) << "," << int(p[1]) << "," << int(p[2]) << "," << int(p[3]) << ")";
  return s.str();
}

std::string rgba(int r, int g, int b, int a) {
  std::ostringstream s;
  s << "(" << r << "," << g << "," << b << "," << a << ")";
  return s.str();
}

// A small picture using most of the state: transform, curves, arcs, a stroke with dashes, a clip, alpha.
void draw_scene(Canvas& c) {
  c.set_fill_color({0.9f, 0.2f, 0.1f, 1});
  c.begin_path();
  c.arc(20, 20, 14, 0, 2 * kPi);
  c.fill();
  c.save();
  c.translate(30, 8);
  c.rotate(0.3);
  c.set_global_alpha(0.6);
  c.set_fill_color({0.1f, 0.4f, 0.9f, 1});
  c.begin_path();
  c.move_to(0, 0);
  c.cubic_to(20, -5, 25, 30, 5, 28);
  c.quad_to(-5, 15, 0, 0);
  c.fill();
  c.restore();
  c.set_stroke_color({0.1f, 0.6f, 0.2f, 0.8f});
  c.set_line_width(3);
  const double dash[] = {6, 3};
  c.set_line_dash(dash);
  c.begin_path();
  c.ellipse(32, 34, 20, 8, 0.4, 0, 1.5 * kPi);
  c.stroke();
}

// ---- state ----

TEST(CanvasState, SaveRestoreLeavesEveryStateAsItWas) {
  // Reference: the picture drawn with the default state.
  Image expected = blank(48, 48);
  {
    Canvas c(expected);
    draw_scene(c);
  }
  Image actual = blank(48, 48);
  Canvas c(actual);
  c.save();
  // Change every piece of state, then restore.
  c.translate(5, 7);
  c.scale(2, 0.5);
  c.set_fill_color({0, 1, 0, 1});
  c.set_stroke_paint(Paint::solid({1, 1, 0, 1}));
  c.set_line_width(9);
  c.set_line_cap(LineCap::Round);
  c.set_line_join(LineJoin::Bevel);
  c.set_miter_limit(1.5);
  const double dash[] = {1, 2, 3};
  c.set_line_dash(dash);
  c.set_line_dash_offset(4);
  c.set_global_alpha(0.25);
  c.set_composite(CompositeOp::Xor);
  c.set_fill_rule(FillRule::EvenOdd);
  c.set_anti_alias(AntiAlias::None);
  c.set_tolerance(3);
  c.set_image_smoothing(false);
  c.set_image_filter(ImageFilter::Bicubic);
  c.set_shadow({{0, 0, 0, 1}, 3, 3, 4});
  c.begin_path();
  c.rect(3, 3, 30, 11);
  c.clip();
  c.restore();
  EXPECT_TRUE(c.get_transform().is_identity());
  EXPECT_EQ(c.line_style().width, 1);
  EXPECT_EQ(c.line_style().cap, LineCap::Butt);
  EXPECT_EQ(c.line_style().join, LineJoin::Miter);
  EXPECT_EQ(c.line_style().miter_limit, 4);
  EXPECT_TRUE(c.line_style().dashes.empty());
  EXPECT_EQ(c.line_style().dash_offset, 0);
  EXPECT_EQ(c.fill_paint().kind(), Paint::Kind::Solid);
  EXPECT_EQ(c.fill_paint().color().g, 0);
  EXPECT_EQ(c.stroke_paint().color().r, 0);
  draw_scene(c);
  EXPECT_EQ(max_diff(actual, expected), 0) << "a state survived restore()";
}

TEST(CanvasState, RestoreWithoutSaveDoesNothingAndNestedSavesPopInOrder) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.restore();
  EXPECT_TRUE(c.get_transform().is_identity());
  c.translate(1, 0);
  c.save();
  c.translate(1, 0);
  c.save();
  c.translate(1, 0);
  c.restore();
  EXPECT_EQ(c.get_transform().e, 2);
  c.restore();
  EXPECT_EQ(c.get_transform().e, 1);
  c.restore();
  EXPECT_EQ(c.get_transform().e, 1);
}

TEST(CanvasState, SettersIgnoreValuesTheSpecIgnores) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.set_line_width(0);
  c.set_line_width(-1);
  c.set_miter_limit(0);
  c.set_global_alpha(1.5);
  c.set_global_alpha(-0.1);
  const double negative[] = {1, -2};
  c.set_line_dash(negative);
  EXPECT_EQ(c.line_style().width, 1);
  EXPECT_EQ(c.line_style().miter_limit, 4);
  EXPECT_TRUE(c.line_style().dashes.empty());
  const double odd[] = {1, 2, 3};
  c.set_line_dash(odd);
  EXPECT_EQ(c.line_style().dashes, (std::vector<double>{1, 2, 3, 1, 2, 3})) << "an odd list is stored twice";
  // Global alpha 0 is valid: drawing then changes nothing.
  c.set_global_alpha(0);
  c.fill_rect(0, 0, 4, 4);
  EXPECT_EQ(max_diff(image, blank(4, 4)), 0);
}

// ---- NaN and infinity ----

TEST(CanvasNumbers, NonFiniteArgumentsChangeNothing) {
  using Call = std::function<void(Canvas&, double)>;
  const Image pattern = [] {
    Image p(2, 2);
    p.clear({1, 0, 0, 1});
    return p;
  }();
  const std::vector<std::pair<const char*, Call>> calls = {
      {"translate", [](Canvas& c, double v) { c.translate(v, 1); }},
      {"scale", [](Canvas& c, double v) { c.scale(1, v); }},
      {"rotate", [](Canvas& c, double v) { c.rotate(v); }},
      {"transform", [](Canvas& c, double v) { c.transform({1, 0, 0, 1, v, 0}); }},
      {"set_transform", [](Canvas& c, double v) { c.set_transform({v, 0, 0, 1, 0, 0}); }},
      {"set_fill_color", [](Canvas& c, double v) { c.set_fill_color({float(v), 0, 0, 1}); }},
      {"set_stroke_color", [](Canvas& c, double v) { c.set_stroke_color({0, 0, 0, float(v)}); }},
      {"set_line_width", [](Canvas& c, double v) { c.set_line_width(v); }},
      {"set_miter_limit", [](Canvas& c, double v) { c.set_miter_limit(v); }},
      {"set_line_dash", [](Canvas& c, double v) { const double d[] = {2, v}; c.set_line_dash(d); }},
      {"set_line_dash_offset", [](Canvas& c, double v) { c.set_line_dash_offset(v); }},
      {"set_global_alpha", [](Canvas& c, double v) { c.set_global_alpha(v); }},
      {"set_tolerance", [](Canvas& c, double v) { c.set_tolerance(v); }},
      {"set_shadow", [](Canvas& c, double v) { c.set_shadow({{0, 0, 0, 1}, v, 2, 2}); }},
      {"move_to", [](Canvas& c, double v) { c.move_to(v, 3); }},
      {"line_to", [](Canvas& c, double v) { c.line_to(3, v); }},
      {"quad_to", [](Canvas& c, double v) { c.quad_to(1, 2, v, 4); }},
      {"cubic_to", [](Canvas& c, double v) { c.cubic_to(1, 2, 3, 4, 5, v); }},
      {"arc", [](Canvas& c, double v) { c.arc(10, 10, 5, 0, v); }},
      {"arc radius", [](Canvas& c, double v) { c.arc(10, 10, v, 0, 1); }},
      {"arc_to", [](Canvas& c, double v) { c.arc_to(20, 2, 20, v, 3); }},
      {"ellipse", [](Canvas& c, double v) { c.ellipse(10, 10, 5, 4, v, 0, 1); }},
      {"rect", [](Canvas& c, double v) { c.rect(1, 1, v, 4); }},
      {"round_rect", [](Canvas& c, double v) { c.round_rect(1, 1, 8, 8, v); }},
      {"fill_rect", [](Canvas& c, double v) { c.fill_rect(1, 1, v, 4); }},
      {"stroke_rect", [](Canvas& c, double v) { c.stroke_rect(v, 1, 5, 4); }},
      {"clear_rect", [](Canvas& c, double v) { c.clear_rect(0, 0, 20, v); }},
      {"draw_image", [&](Canvas& c, double v) { c.draw_image(pattern, v, 0); }},
      {"draw_image scaled", [&](Canvas& c, double v) { c.draw_image(pattern, 0, 0, 4, v); }},
      {"draw_image source", [&](Canvas& c, double v) { c.draw_image(pattern, 0, v, 1, 1, 0, 0, 5, 5); }},
  };
  auto base = [](Canvas& c) {
    c.set_fill_color({0.2f, 0.3f, 0.8f, 1});
    c.fill_rect(2, 2, 10, 10);
    c.begin_path();
    c.move_to(4, 4);
    c.line_to(16, 6);
    c.line_to(9, 17);
  };
  auto finish = [](Canvas& c) {
    // Whatever the call could have changed shows in a fill, a stroke and a clipped fill of the current path.
    c.set_line_width(c.line_style().width);
    c.fill();
    c.stroke();
    c.clip();
    c.fill_rect(0, 0, 20, 20);
  };
  Image expected = blank(20, 20);
  {
    Canvas c(expected);
    base(c);
    finish(c);
  }
  for (const auto& [name, call] : calls) {
    for (double bad : {kNaN, kInf, -kInf}) {
      Image image = blank(20, 20);
      Canvas c(image);
      base(c);
      call(c, bad);
      finish(c);
      EXPECT_EQ(max_diff(image, expected), 0) << name << "(" << bad << ") changed something";
      EXPECT_FALSE(c.is_point_in_path(bad, 5)) << name;
      EXPECT_FALSE(c.is_point_in_stroke(5, bad)) << name;
    }
  }
}

// ---- the current path ----

TEST(CanvasPath, PointsAreMappedByTheTransformCurrentWhenAdded) {
  Image image = blank(20, 20);
  Canvas c(image);
  c.begin_path();
  c.move_to(0, 0);
  c.translate(10, 0);
  c.line_to(0, 10);  // device (10, 10)
  c.reset_transform();
  c.line_to(0, 10);
  // The triangle (0,0) (10,10) (0,10): (2, 8) inside, (8, 2) outside.
  EXPECT_TRUE(c.is_point_in_path(2, 8));
  EXPECT_FALSE(c.is_point_in_path(8, 2));
}

TEST(CanvasPath, ArcFullTurnRuleAndDirection) {
  Image image = blank(4, 4);
  Canvas c(image);
  // Clockwise from 0 to pi/2: the quarter towards +x +y, closed by its chord x + y = 110.
  c.begin_path();
  c.arc(50, 50, 10, 0, kPi / 2);
  EXPECT_TRUE(c.is_point_in_path(56.5, 56.5));
  EXPECT_FALSE(c.is_point_in_path(54, 54));
  EXPECT_FALSE(c.is_point_in_path(46, 46));
  // Counterclockwise over the same angles: the other three quarters, centre included.
  c.begin_path();
  c.arc(50, 50, 10, 0, kPi / 2, true);
  EXPECT_FALSE(c.is_point_in_path(56.5, 56.5));
  EXPECT_TRUE(c.is_point_in_path(46, 46));
  EXPECT_TRUE(c.is_point_in_path(50, 50));
  // A difference of 2 pi or more in the drawing direction is the whole circle.
  c.begin_path();
  c.arc(50, 50, 10, 1, 1 + 2 * kPi + 0.5);
  EXPECT_TRUE(c.is_point_in_path(45, 50));
  EXPECT_TRUE(c.is_point_in_path(55, 50));
  EXPECT_TRUE(c.is_point_in_path(50, 55));
  // ... but against the drawing direction it is reduced modulo 2 pi: from 1 + 2pi + 0.5 back to 1 ccw is 0.5 rad.
  c.begin_path();
  c.arc(50, 50, 10, 1 + 2 * kPi + 0.5, 1);
  // cw from 1.5 (mod 2pi) to 1: nearly the whole circle, missing the segment between angles 1 and 1.5 (its chord
  // is 10 cos(0.25) = 9.69 from the centre).
  EXPECT_TRUE(c.is_point_in_path(50 + 8 * std::cos(3.0), 50 + 8 * std::sin(3.0)));
  EXPECT_TRUE(c.is_point_in_path(50 + 9.5 * std::cos(1.25), 50 + 9.5 * std::sin(1.25)));
  EXPECT_FALSE(c.is_point_in_path(50 + 9.85 * std::cos(1.25), 50 + 9.85 * std::sin(1.25)));
  EXPECT_TRUE(c.is_point_in_path(50 + 9.85 * std::cos(2.25), 50 + 9.85 * std::sin(2.25)));
  // Equal angles: an empty arc (just its start point).
  c.begin_path();
  c.arc(50, 50, 10, 2, 2);
  EXPECT_FALSE(c.is_point_in_path(50, 50));
}

TEST(CanvasPath, ArcStartsWithALineFromTheCurrentPoint) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.begin_path();
  c.move_to(0, 0);
  c.arc(20, 0, 5, kPi / 2, kPi, false);  // line (0,0) -> (20,5), then the arc to (15,0)
  // The closed outline (0,0) (20,5) arc (15,0): the thin triangle near (12, 2) is inside.
  EXPECT_TRUE(c.is_point_in_path(12, 2));
  EXPECT_FALSE(c.is_point_in_path(12, -1));
}

TEST(CanvasPath, ArcToTangentPointsAndDegenerateCases) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.set_line_width(0.5);
  // Corner (10,10) -> (50,10) -> (50,50) with radius 20: line to (30,10), quarter circle centred at (30,30) to
  // (50,30). The corner point itself is not on the path.
  c.begin_path();
  c.move_to(10, 10);
  c.arc_to(50, 10, 50, 50, 20);
  EXPECT_TRUE(c.is_point_in_stroke(20, 10));
  EXPECT_TRUE(c.is_point_in_stroke(30 + 20 * std::cos(-kPi / 4), 30 + 20 * std::sin(-kPi / 4)));
  EXPECT_TRUE(c.is_point_in_stroke(50, 30));
  EXPECT_FALSE(c.is_point_in_stroke(50, 10));
  EXPECT_FALSE(c.is_point_in_stroke(50, 40)) << "arc_to ends at the second tangent point";
  // Collinear points: a straight line to (x1, y1).
  c.begin_path();
  c.move_to(0, 0);
  c.arc_to(10, 0, 20, 0, 5);
  EXPECT_TRUE(c.is_point_in_stroke(5, 0));
  EXPECT_TRUE(c.is_point_in_stroke(10, 0));
  EXPECT_FALSE(c.is_point_in_stroke(15, 0));
  // Radius 0: a line to (x1, y1).
  c.begin_path();
  c.move_to(0, 0);
  c.arc_to(10, 0, 10, 10, 0);
  EXPECT_TRUE(c.is_point_in_stroke(10, 0));
  EXPECT_FALSE(c.is_point_in_stroke(10, 5));
  // An empty path: arc_to only moves to (x1, y1).
  c.begin_path();
  c.arc_to(10, 0, 10, 10, 3);
  c.line_to(20, 0);
  EXPECT_TRUE(c.is_point_in_stroke(15, 0));
  EXPECT_FALSE(c.is_point_in_stroke(5, 0));
  // Negative radius: nothing at all.
  c.begin_path();
  c.move_to(0, 0);
  c.arc_to(10, 0, 10, 10, -1);
  c.line_to(0, 10);
  EXPECT_TRUE(c.is_point_in_stroke(0, 5));
  EXPECT_FALSE(c.is_point_in_stroke(10, 0));
}

TEST(CanvasPath, EllipseWithRotation) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.begin_path();
  c.ellipse(50, 50, 20, 4, kPi / 2, 0, 2 * kPi);  // long axis vertical after the rotation
  EXPECT_TRUE(c.is_point_in_path(50, 68));
  EXPECT_FALSE(c.is_point_in_path(68, 50));
  c.begin_path();
  c.ellipse(50, 50, 20, 4, 0, 0, 2 * kPi);
  EXPECT_FALSE(c.is_point_in_path(50, 68));
  EXPECT_TRUE(c.is_point_in_path(68, 50));
}

TEST(CanvasPath, RectAndRoundRectAndCloseStartNewSubpaths) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.begin_path();
  c.rect(10, 10, 20, 10);
  c.line_to(40, 40);  // from (10, 10): rect() leaves a subpath at its first corner
  c.set_line_width(1);
  EXPECT_TRUE(c.is_point_in_stroke(25, 25));
  EXPECT_TRUE(c.is_point_in_path(20, 15));
  c.begin_path();
  c.round_rect(10, 10, 40, 20, 8);
  EXPECT_TRUE(c.is_point_in_path(30, 20));
  EXPECT_TRUE(c.is_point_in_path(11, 20));
  EXPECT_FALSE(c.is_point_in_path(11, 11)) << "the corner is rounded";
  EXPECT_TRUE(c.is_point_in_path(10 + 8 - 8 * std::cos(kPi / 4) + 0.5, 10 + 8 - 8 * std::sin(kPi / 4) + 0.5));
  // Negative sizes cover the mirrored rectangle; radii larger than half a side are clamped.
  c.begin_path();
  c.round_rect(50, 30, -40, -20, 100);
  EXPECT_TRUE(c.is_point_in_path(30, 20));
  EXPECT_FALSE(c.is_point_in_path(11, 11));
  // close_path goes back to the subpath's start, and the next segment starts there.
  c.begin_path();
  c.move_to(0, 0);
  c.line_to(10, 0);
  c.line_to(10, 10);
  c.close_path();
  c.line_to(0, 20);
  EXPECT_TRUE(c.is_point_in_stroke(0, 10));
}

TEST(CanvasPath, LineToWithoutSubpathOnlyMoves) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.begin_path();
  c.line_to(10, 10);
  c.line_to(20, 10);
  EXPECT_TRUE(c.is_point_in_stroke(15, 10));
  EXPECT_FALSE(c.is_point_in_stroke(5, 5)) << "no line from the origin";
}

// ---- hit testing ----

TEST(CanvasHitTest, FillRulesAndPointsOnTheOutline) {
  Image image = blank(4, 4);
  Canvas c(image);
  // Two nested squares, same direction: winding 2 in the inner one.
  Path p;
  p.add_rect({0, 0, 30, 30});
  p.add_rect({10, 10, 20, 20});
  EXPECT_TRUE(c.is_point_in_path(p, 15, 15, FillRule::NonZero));
  EXPECT_FALSE(c.is_point_in_path(p, 15, 15, FillRule::EvenOdd));
  EXPECT_TRUE(c.is_point_in_path(p, 5, 5, FillRule::EvenOdd));
  EXPECT_TRUE(c.is_point_in_path(p, 15, 15, FillRule::AbsGeq2));
  EXPECT_FALSE(c.is_point_in_path(p, 5, 5, FillRule::AbsGeq2));
  EXPECT_FALSE(c.is_point_in_path(p, 35, 5, FillRule::NonZero));
  // Points on the outline are inside, on every side.
  EXPECT_TRUE(c.is_point_in_path(p, 0, 15, FillRule::NonZero));
  EXPECT_TRUE(c.is_point_in_path(p, 30, 15, FillRule::NonZero));
  EXPECT_TRUE(c.is_point_in_path(p, 15, 30, FillRule::NonZero));
  // The point is mapped by the current transform, like the path.
  c.translate(100, 0);
  EXPECT_TRUE(c.is_point_in_path(p, 5, 5, FillRule::NonZero));
  // Stroke: the outline's non-zero winding, width in user units.
  c.reset_transform();
  c.set_line_width(4);
  EXPECT_TRUE(c.is_point_in_stroke(p, 31.5, 15));
  EXPECT_FALSE(c.is_point_in_stroke(p, 32.5, 15));
  c.scale(2, 2);  // the pen scales with the transform: width 8 device pixels around device x = 60
  EXPECT_TRUE(c.is_point_in_stroke(p, 31.5, 15));
  EXPECT_TRUE(c.is_point_in_stroke(p, 30.9, 15));
}

// ---- operators outside the shape ----

// A 4 x 4 canvas, opaque red, then a blue 2 x 2 square at (1, 1) with `op`, inside a clip of the left three
// columns. Returns the picture.
Image operator_case(CompositeOp op) {
  Image image(4, 4);
  image.clear({1, 0, 0, 1});
  Canvas c(image);
  c.begin_path();
  c.rect(0, 0, 3, 4);
  c.clip();
  c.set_composite(op);
  c.set_fill_color({0, 0, 1, 1});
  c.fill_rect(1, 1, 2, 2);
  return image;
}

TEST(CanvasOperators, BoundedOperatorsTouchOnlyTheShape) {
  const Image over = operator_case(CompositeOp::SourceOver);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const bool in = x >= 1 && x < 3 && y >= 1 && y < 3;
      EXPECT_EQ(px(over, x, y), in ? rgba(0, 0, 255, 255) : rgba(255, 0, 0, 255)) << x << "," << y;
    }
  }
  const Image atop = operator_case(CompositeOp::SourceAtop);
  EXPECT_EQ(max_diff(atop, over), 0);
  const Image dout = operator_case(CompositeOp::DestinationOut);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const bool in = x >= 1 && x < 3 && y >= 1 && y < 3;
      EXPECT_EQ(px(dout, x, y), in ? rgba(0, 0, 0, 0) : rgba(255, 0, 0, 255)) << x << "," << y;
    }
  }
}

TEST(CanvasOperators, UnboundedOperatorsReachTheWholeClipRegion) {
  struct Expect {
    CompositeOp op;
    std::string inside, outside;  // inside the shape / inside the clip but outside the shape
  };
  const std::string red = rgba(255, 0, 0, 255), blue = rgba(0, 0, 255, 255), none = rgba(0, 0, 0, 0);
  const Expect cases[] = {
      {CompositeOp::Copy, blue, none},
      {CompositeOp::SourceIn, blue, none},
      {CompositeOp::SourceOut, none, none},
      {CompositeOp::DestinationIn, red, none},
      {CompositeOp::DestinationAtop, red, none},
      {CompositeOp::Clear, none, none},
  };
  for (const Expect& e : cases) {
    const Image image = operator_case(e.op);
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 4; ++x) {
        const bool in_shape = x >= 1 && x < 3 && y >= 1 && y < 3;
        const std::string want = x == 3 ? red : in_shape ? e.inside : e.outside;
        EXPECT_EQ(px(image, x, y), want) << to_string(e.op) << " at " << x << "," << y;
      }
    }
  }
}

TEST(CanvasOperators, UnboundedOperatorWithAHalfCoveredPixel) {
  // Copy with a shape covering half of pixel 1: source scaled by coverage (the shape as an image whose alpha is
  // its coverage), so the pixel holds half-transparent blue; the rest of the canvas (the clip) is cleared.
  Image image(3, 1);
  image.clear({1, 0, 0, 1});
  Canvas c(image);
  c.set_composite(CompositeOp::Copy);
  c.set_fill_color({0, 0, 1, 1});
  c.fill_rect(1, 0, 0.5, 1);
  EXPECT_EQ(px(image, 0, 0), rgba(0, 0, 0, 0));
  EXPECT_EQ(px(image, 1, 0), rgba(0, 0, 128, 128));
  EXPECT_EQ(px(image, 2, 0), rgba(0, 0, 0, 0));
}

// ---- clips ----

TEST(CanvasClip, AntialiasedClipEdgesHandMade) {
  // Clip to x in [0.5, 2.25) (every row), fill everything opaque white over transparency: the clip's coverage
  // shows in alpha: 1/2, 1, 1/4, 0.
  Image image = blank(4, 2);
  Canvas c(image);
  c.begin_path();
  c.rect(0.5, 0, 1.75, 2);
  c.clip();
  c.set_fill_color({1, 1, 1, 1});
  c.fill_rect(0, 0, 4, 2);
  for (int y = 0; y < 2; ++y) {
    EXPECT_EQ(px(image, 0, y), rgba(128, 128, 128, 128));
    EXPECT_EQ(px(image, 1, y), rgba(255, 255, 255, 255));
    EXPECT_EQ(px(image, 2, y), rgba(64, 64, 64, 64));
    EXPECT_EQ(px(image, 3, y), rgba(0, 0, 0, 0));
  }
}

TEST(CanvasClip, ClipMultipliesCoverage) {
  // A half-covered clip pixel meets a half-covered fill pixel: the result has a quarter of the alpha.
  Image image = blank(2, 1);
  Canvas c(image);
  c.begin_path();
  c.rect(0, 0, 0.5, 1);
  c.clip();
  c.set_fill_color({1, 1, 1, 1});
  c.fill_rect(0, 0, 1, 0.5);
  EXPECT_EQ(px(image, 0, 0), rgba(64, 64, 64, 64));
  EXPECT_EQ(px(image, 1, 0), rgba(0, 0, 0, 0));
}

TEST(CanvasClip, ClipsIntersectAndRestorePopsThem) {
  Image image = blank(10, 10);
  Canvas c(image);
  c.save();
  c.begin_path();
  c.rect(0, 0, 6, 10);
  c.clip();
  c.begin_path();
  c.rect(3, 0, 7, 10);
  c.clip();
  c.set_fill_color({1, 1, 1, 1});
  c.fill_rect(0, 0, 10, 10);
  for (int x = 0; x < 10; ++x) {
    EXPECT_EQ(image.pixel(x, 5)[3], x >= 3 && x < 6 ? 255 : 0) << x;
  }
  c.restore();
  c.fill_rect(0, 0, 10, 10);
  for (int x = 0; x < 10; ++x) EXPECT_EQ(image.pixel(x, 5)[3], 255) << x;
}

TEST(CanvasClip, PixelAlignedRectangleClipEqualsTheSamePathClip) {
  // The rectangle clip (no mask) against the same region given as a path that takes the mask route (a rectangle
  // with an extra point on one side), under every antialiasing mode and a rotated, semi-transparent fill.
  for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact, AntiAlias::Ssaa4}) {
    for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd, FillRule::Positive, FillRule::NonExterior}) {
      Image a = blank(40, 40), b = blank(40, 40);
      for (int k = 0; k < 2; ++k) {
        Canvas c(k == 0 ? a : b);
        c.set_anti_alias(aa);
        c.begin_path();
        // Counterclockwise on screen: winding +1, inside under Positive too.
        c.move_to(5, 7);
        c.line_to(5, 33);
        c.line_to(31, 33);
        if (k == 1) c.line_to(31, 20);
        c.line_to(31, 7);
        c.close_path();
        c.clip(rule);
        c.set_fill_color({0.2f, 0.5f, 0.9f, 0.7f});
        c.translate(20, 20);
        c.rotate(0.5);
        c.fill_rect(-18, -9, 36, 18);
      }
      EXPECT_EQ(max_diff(a, b), 0) << to_string(aa) << " " << to_string(rule);
    }
  }
}

TEST(CanvasClip, RectangleClipOrientationDecidesSignedRules) {
  // Clockwise on screen: winding -1, so a Positive clip is empty and a Negative one is the rectangle.
  for (FillRule rule : {FillRule::Positive, FillRule::Negative}) {
    Image image = blank(8, 8);
    Canvas c(image);
    c.begin_path();
    c.rect(2, 2, 4, 4);  // clockwise on screen
    c.clip(rule);
    c.fill_rect(0, 0, 8, 8);
    EXPECT_EQ(image.pixel(3, 3)[3], rule == FillRule::Negative ? 255 : 0) << to_string(rule);
    EXPECT_EQ(image.pixel(1, 1)[3], 0);
  }
}

TEST(CanvasClip, ClipOutsideTheCanvasOrEmptyClipsEverything) {
  Image image = blank(8, 8);
  Canvas c(image);
  c.begin_path();
  c.rect(20, 20, 5, 5);
  c.clip();
  c.fill_rect(0, 0, 8, 8);
  c.set_composite(CompositeOp::Copy);
  c.fill_rect(0, 0, 8, 8);
  EXPECT_EQ(max_diff(image, blank(8, 8)), 0);
}

// ---- layers ----

TEST(CanvasLayer, OpacityOneSourceOverEqualsDrawingDirectly) {
  Image direct(48, 48), layered(48, 48);
  direct.clear({0.5f, 0.5f, 0.5f, 0.5f});
  layered.clear({0.5f, 0.5f, 0.5f, 0.5f});
  {
    Canvas c(direct);
    draw_scene(c);
  }
  {
    Canvas c(layered);
    c.begin_layer();
    draw_scene(c);
    c.end_layer();
  }
  // Over the same backdrop the layer composites its content once more: equal up to 8-bit rounding of the
  // intermediate layer (premultiplied over is associative).
  EXPECT_LE(max_diff(direct, layered), 1);
  // Over transparency it is the same pixels exactly.
  Image d2 = blank(48, 48), l2 = blank(48, 48);
  {
    Canvas c(d2);
    draw_scene(c);
  }
  {
    Canvas c(l2);
    c.begin_layer();
    draw_scene(c);
    c.end_layer();
  }
  EXPECT_EQ(max_diff(d2, l2), 0);
  // Inside an antialiased clip: the clip applies once (when the layer is composited), as it does to direct drawing.
  Image d3 = blank(48, 48), l3 = blank(48, 48);
  for (Image* image : {&d3, &l3}) {
    Canvas c(*image);
    c.begin_path();
    c.arc(24.3, 23.8, 17.6, 0, 2 * kPi);
    c.clip();
    if (image == &l3) c.begin_layer();
    draw_scene(c);
    if (image == &l3) c.end_layer();
  }
  EXPECT_EQ(max_diff(d3, l3), 0);
}

TEST(CanvasLayer, OpacityScalesTheWholeLayerOnce) {
  // Two overlapping opaque squares in a layer of opacity 1/2: the overlap is not darker than the rest.
  Image image = blank(6, 2);
  Canvas c(image);
  c.begin_layer(0.5f);
  c.set_fill_color({0, 0, 0, 1});
  c.fill_rect(0, 0, 4, 2);
  c.fill_rect(2, 0, 4, 2);
  c.end_layer();
  for (int x = 0; x < 6; ++x) EXPECT_EQ(image.pixel(x, 0)[3], 128) << x;
}

TEST(CanvasLayer, LayerCoversOnlyTheClipAndStateInsideIsBalanced) {
  Image image = blank(10, 10);
  Canvas c(image);
  c.begin_path();
  c.rect(2, 2, 4, 4);
  c.clip();
  c.set_global_alpha(0.5);
  c.begin_layer();
  c.translate(1, 1);
  c.save();  // left open: end_layer() balances it
  c.set_fill_color({1, 1, 1, 1});
  c.fill_rect(-1, -1, 10, 10);  // alpha 1 inside the layer
  c.end_layer();
  EXPECT_TRUE(c.get_transform().is_identity());
  EXPECT_EQ(image.pixel(3, 3)[3], 255) << "the layer ignores the alpha outside it (its own opacity is 1)";
  EXPECT_EQ(image.pixel(1, 1)[3], 0) << "clipped";
  EXPECT_EQ(image.pixel(7, 7)[3], 0) << "clipped";
  c.fill_rect(0, 0, 10, 10);
  EXPECT_EQ(image.pixel(3, 3)[3], 255);
  EXPECT_EQ(image.pixel(1, 1)[3], 0) << "the clip of before the layer is back";
}

TEST(CanvasLayer, OperatorAndMasks) {
  // A layer composited with destination-out punches its shape out of the backdrop.
  Image image(4, 1);
  image.clear({1, 0, 0, 1});
  {
    Canvas c(image);
    LayerOptions options;
    options.op = CompositeOp::DestinationOut;
    c.begin_layer(options);
    c.fill_rect(1, 0, 2, 1);
    c.end_layer();
  }
  EXPECT_EQ(px(image, 0, 0), rgba(255, 0, 0, 255));
  EXPECT_EQ(px(image, 1, 0), rgba(0, 0, 0, 0));
  EXPECT_EQ(px(image, 3, 0), rgba(255, 0, 0, 255));

  // Alpha and luminance masks, placed at (1, 0); outside the mask nothing is drawn.
  auto mask = std::make_shared<Image>(2, 1);
  mask->clear(Color::transparent());
  const std::uint8_t m0[4] = {255, 255, 255, 255}, m1[4] = {0, 0, 128, 128};  // opaque white; half blue
  std::copy(m0, m0 + 4, mask->pixel(0, 0));
  std::copy(m1, m1 + 4, mask->pixel(1, 0));
  for (MaskMode mode : {MaskMode::Alpha, MaskMode::Luminance}) {
    Image out = blank(4, 1);
    Canvas c(out);
    LayerOptions options;
    options.mask = mask;
    options.mask_x = 1;
    options.mask_mode = mode;
    c.begin_layer(options);
    c.set_fill_color({1, 1, 1, 1});
    c.fill_rect(0, 0, 4, 1);
    c.end_layer();
    EXPECT_EQ(out.pixel(0, 0)[3], 0);
    EXPECT_EQ(out.pixel(1, 0)[3], 255);
    // Alpha: 128/255; luminance: 0.0721 * 128/255 (premultiplied blue).
    const int want = mode == MaskMode::Alpha ? 128 : static_cast<int>(std::lround(0.0721 * 128));
    EXPECT_NEAR(out.pixel(2, 0)[3], want, 1) << (mode == MaskMode::Alpha ? "alpha" : "luminance");
    EXPECT_EQ(out.pixel(3, 0)[3], 0);
  }
}

TEST(CanvasLayer, EndWithoutBeginAndRestoreCannotPopTheLayerState) {
  Image image = blank(4, 4);
  Canvas c(image);
  c.end_layer();  // nothing to end
  c.translate(1, 0);
  c.begin_layer();
  c.restore();  // would pop the state begin_layer saved: ignored
  c.translate(1, 0);
  EXPECT_EQ(c.get_transform().e, 2);
  c.end_layer();
  EXPECT_EQ(c.get_transform().e, 1);
}

// ---- shadows ----

TEST(CanvasShadow, OffsetShadowWithoutBlurIsTheShapeMoved) {
  Image with = blank(20, 20), manual = blank(20, 20);
  {
    Canvas c(with);
    c.set_shadow({{0, 0, 0, 0.5f}, 3, 4, 0});
    c.set_fill_color({1, 0, 0, 1});
    c.fill_rect(2, 2, 8, 8);
  }
  {
    Canvas c(manual);
    c.set_fill_color({0, 0, 0, 0.5f});
    c.fill_rect(5, 6, 8, 8);
    c.set_fill_color({1, 0, 0, 1});
    c.fill_rect(2, 2, 8, 8);
  }
  EXPECT_LE(max_diff(with, manual), 1);
}

TEST(CanvasShadow, BlurredShadowIsAGaussianOfSigmaHalfTheBlur) {
  // The shape covers x >= 40 of rows [-100, 20); its shadow (offset 50 down, blur 6: sigma 3) covers rows
  // [-50, 70), far from row 10's vertical edges. Left of x = 40 only the shadow shows, and across its edge the
  // alpha is the Gaussian's integral, 1/2 (1 + erf(d / (sigma sqrt 2))) at distance d from the edge.
  Image image = blank(80, 20);
  Canvas c(image);
  c.set_shadow({{0, 0, 0, 1}, 0, 50, 6});
  c.set_fill_color({0, 0, 0, 1});
  c.fill_rect(40, -100, 100, 120);
  for (int x = 28; x < 40; ++x) {
    const double d = (x + 0.5) - 40;
    const double want = 255 * 0.5 * (1 + std::erf(d / (3 * std::sqrt(2.0))));
    EXPECT_NEAR(image.pixel(x, 10)[3], want, 2.5) << x;
  }
  EXPECT_EQ(image.pixel(45, 10)[3], 255);
}

// ---- images ----

TEST(CanvasImage, DrawImageAtIntegerPositionCopiesPixels) {
  Image src(3, 2);
  for (int i = 0; i < 6; ++i) {
    std::uint8_t* p = src.pixel(i % 3, i / 3);
    p[0] = static_cast<std::uint8_t>(40 * i);
    p[1] = static_cast<std::uint8_t>(200 - 30 * i);
    p[2] = 7;
    p[3] = 255;
  }
  for (bool smooth : {false, true}) {
    Image image = blank(6, 5);
    Canvas c(image);
    c.set_image_smoothing(smooth);
    c.draw_image(src, 2, 1);
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 6; ++x) {
        const bool in = x >= 2 && x < 5 && y >= 1 && y < 3;
        EXPECT_EQ(px(image, x, y), in ? px(src, x - 2, y - 1) : rgba(0, 0, 0, 0)) << x << "," << y << " " << smooth;
      }
    }
  }
}

TEST(CanvasImage, NearestScalingRepeatsPixelsAndSourceRectanglePicksPart) {
  Image src(2, 2);
  src.clear({0, 0, 0, 1});
  src.pixel(1, 0)[0] = 255;  // top-right red
  Image image = blank(8, 8);
  Canvas c(image);
  c.set_image_smoothing(false);
  c.draw_image(src, 0, 0, 8, 8);
  EXPECT_EQ(px(image, 5, 2), rgba(255, 0, 0, 255));
  EXPECT_EQ(px(image, 2, 2), rgba(0, 0, 0, 255));
  // Source rectangle: only the red pixel, stretched over 4 x 4 at (0, 4).
  c.draw_image(src, 1, 0, 1, 1, 0, 4, 4, 4);
  EXPECT_EQ(px(image, 1, 6), rgba(255, 0, 0, 255));
  EXPECT_EQ(px(image, 5, 6), rgba(0, 0, 0, 255));
}

// ---- masks, pixels, FXAA ----

TEST(CanvasMask, FillMaskPaintsThroughCoverage) {
  const std::uint8_t mask[] = {0, 128, 255, 0, 255, 64};  // 3 x 2, stride 3
  Image image = blank(6, 4);
  Canvas c(image);
  c.set_fill_color({1, 1, 1, 1});
  c.fill_mask(mask, 3, 2, 3, 2, 1);
  EXPECT_EQ(image.pixel(2, 1)[3], 0);
  EXPECT_EQ(image.pixel(3, 1)[3], 128);
  EXPECT_EQ(image.pixel(4, 1)[3], 255);
  EXPECT_EQ(image.pixel(3, 2)[3], 255);
  EXPECT_EQ(image.pixel(4, 2)[3], 64);
  EXPECT_EQ(image.pixel(1, 1)[3], 0);
}

TEST(CanvasPixels, GetAndPutPixels) {
  Image image = blank(4, 4);
  Canvas c(image);
  Image patch(2, 2);
  patch.clear({0, 0, 0, 0});
  patch.pixel(0, 0)[3] = 10;
  patch.pixel(1, 1)[0] = 9;
  patch.pixel(1, 1)[3] = 20;
  c.set_global_alpha(0.1);
  c.set_composite(CompositeOp::Xor);
  c.put_pixels(patch, 3, 3);  // only the top-left pixel lands; alpha and operator do not apply
  EXPECT_EQ(image.pixel(3, 3)[3], 10);
  const Image got = c.get_pixels(2, 2, 3, 3);
  EXPECT_EQ(got.pixel(1, 1)[3], 10);
  EXPECT_EQ(got.pixel(2, 2)[3], 0) << "outside the canvas: transparent";
}

TEST(CanvasPixels, ApplyFxaaIsTheFxaaPostFilter) {
  Image a = blank(32, 32), b = blank(32, 32);
  for (Image* image : {&a, &b}) {
    Canvas c(*image);
    c.set_anti_alias(AntiAlias::None);
    c.set_fill_color({1, 1, 1, 1});
    c.begin_path();
    c.arc(16, 16, 11, 0, 2 * kPi);
    c.fill();
    if (image == &a) c.apply_fxaa();
  }
  fxaa(b);
  EXPECT_EQ(max_diff(a, b), 0);
}

// ---- 16 bits ----

// One draw call from the same backdrop (8-bit values, widened exactly to 16 bits). The 8-bit compositor is within
// 1.5 levels of the formula (it quantizes the premultiplied colour, coverage x alpha and the clip to 1/255 before
// its one exact rounding: docs/design.md, "Paint and compositing"); 16 bits is within a 1/65535 level of it. So
// they agree within 2/255, and within 1/255 on almost every pixel.
TEST(Canvas16, OneDrawCallAgreesWithEightBits) {
  Image backdrop(40, 40);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      std::uint8_t* p = backdrop.pixel(x, y);
      p[3] = static_cast<std::uint8_t>(100 + (x * 7 + y * 3) % 156);
      p[0] = static_cast<std::uint8_t>(p[3] * ((x * 13) % 256) / 255);
      p[1] = static_cast<std::uint8_t>(p[3] * ((y * 29) % 256) / 255);
      p[2] = static_cast<std::uint8_t>(p[3] / 2);
    }
  }
  for (CompositeOp op : {CompositeOp::SourceOver, CompositeOp::Multiply, CompositeOp::Xor, CompositeOp::Copy,
                         CompositeOp::SourceIn, CompositeOp::Screen}) {
    Image a(40, 40);
    Image16 b(40, 40);
    auto draw = [&](Canvas& c) {
      c.put_pixels(backdrop, 0, 0);
      c.begin_path();
      c.arc(20.3, 19.6, 15.2, 0, 2 * kPi);
      c.clip();  // an antialiased clip mask
      c.set_composite(op);
      c.set_global_alpha(0.8);
      c.set_fill_color({0.3f, 0.9f, 0.4f, 0.7f});
      c.translate(20, 20);
      c.rotate(0.4);
      c.fill_rect(-17.5, -9.25, 35, 18.5);
    };
    {
      Canvas c(a);
      draw(c);
    }
    Canvas c(b);
    draw(c);
    const Image b8 = c.get_pixels(0, 0, 40, 40);
    EXPECT_LE(max_diff(a, b8), 2) << to_string(op);
    int beyond_one = 0;
    for (std::size_t i = 0; i < a.data.size(); ++i) beyond_one += std::abs(int(a.data[i]) - int(b8.data[i])) > 1;
    EXPECT_LE(beyond_one, static_cast<int>(a.data.size() / 100)) << to_string(op) << ": over 1% of channels off by 2";
  }
}

// A whole picture: every step rounds in 8 bits, so the difference may grow with the steps that touch a pixel (up
// to four here: circle, shape, stroke, layer); in practice it stays within 3 levels.
TEST(Canvas16, PictureAgreesWithEightBitsWithinOneLevelPerStep) {
  Image a = blank(48, 48);
  Image16 b(48, 48);
  b.clear(Color::transparent());
  auto draw = [](Canvas& c) {
    draw_scene(c);
    c.begin_layer(0.7f);
    c.set_composite(CompositeOp::Multiply);
    c.set_fill_color({0.3f, 0.9f, 0.4f, 0.8f});
    c.fill_rect(5, 5, 30, 20);
    c.end_layer();
  };
  {
    Canvas c(a);
    draw(c);
  }
  Canvas c(b);
  draw(c);
  EXPECT_LE(max_diff(a, c.get_pixels(0, 0, 48, 48)), 3);
}

}  // namespace
}  // namespace vraster::test
