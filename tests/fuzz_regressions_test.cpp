// Inputs the fuzz targets (tests/fuzz/) found to crash or to trip a sanitizer, each kept as a named test once
// fixed. Under the sanitizer build (scripts/sanitize.sh) they also check that the undefined behaviour is gone.
#include <gtest/gtest.h>

#include <string>

#include "svg_subset/svg.hpp"
#include "vraster/canvas.hpp"
#include "vraster/error.hpp"
#include "vraster/flatten.hpp"
#include "vraster/raster.hpp"
#include "vraster/image.hpp"
#include "vraster/stroke.hpp"

using namespace vraster;

// fuzz_svg: a root width of 3.9e50 px reached check_image_size's message, which cast the size to long long
// (undefined for values beyond its range; UBSan: "outside the range of representable values").
TEST(FuzzRegression, HugeFiniteImageSizeIsReportedWithoutOverflow) {
  try {
    check_image_size(3.88888888888e50, 32);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3.89e+50x32 is too large"), std::string::npos) << e.what();
  }
  try {
    svg::parse_svg(R"(<svg xmlns="http://www.w3.org/2000/svg" width="388888888888888888888888888888888888888888888888882" height="32"><rect width="1" height="1"/></svg>)",
                   "huge.svg");
    FAIL() << "no error for a 3.9e50 px wide document";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("huge.svg"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_image_size(1e300, 1e300), Error);
  EXPECT_NO_THROW(check_image_size(kMaxImageSide, 1));
}

// fuzz_canvas: a stroke through points near the double range (a scale of 1e300, then points of +-480) overflowed
// the segment directions to NaN, and the round join's segment count cast NaN to int (UBSan). Such pieces are
// dropped now; the outline never holds a non-finite point and the call does not throw.
TEST(FuzzRegression, StrokeOfPointsNearTheDoubleRangeStaysFinite) {
  StrokeStyle style;
  style.width = 4;
  style.join = LineJoin::Round;
  style.cap = LineCap::Round;
  Path far;
  far.move_to({-1.5e308, 0});
  far.line_to({1.5e308, 1});
  far.line_to({1e308, 1e308});
  far.line_to({-1e308, 3});
  Path outline;
  ASSERT_NO_THROW(outline = stroke_to_path(far, style, 0.1));
  for (const Point& p : outline.points()) EXPECT_TRUE(is_finite(p)) << p.x << ", " << p.y;

  // The same through the canvas, with an ordinary segment after it: that one still draws.
  Image image(16, 16);
  Canvas canvas(image);
  canvas.set_line_width(2);
  canvas.set_stroke_color(Color{0, 0, 0, 1});
  canvas.scale(1e300, 1e300);
  canvas.begin_path();
  canvas.move_to(-200, 0);
  canvas.line_to(200, 1e-300);
  canvas.line_to(-100, 100);
  ASSERT_NO_THROW(canvas.stroke());
  canvas.set_transform(Affine{});
  canvas.begin_path();
  canvas.move_to(2, 8);
  canvas.line_to(14, 8);
  ASSERT_NO_THROW(canvas.stroke());
  EXPECT_EQ(image.pixel(8, 8)[3], 255);
  EXPECT_EQ(image.pixel(8, 2)[3], 0);
}

// fuzz_canvas: a shadow offset of -1e300 was floored into an int (UBSan), and a blur far wider than the canvas
// made the shadow's working box exceed the image limit, which threw and dropped the shape itself. Shadows that
// cannot reach the image are not drawn; the shape always is.
// fuzz_stroke: a stroke 2000 units wide with round caps, dashed every 0.003 units along 100 units at tolerance 1/8,
// needs more outline points than the stroker's limit. That is stroke_to_path's one documented error: it must be
// thrown as such (naming the limit), soon, and not as anything else; the fuzz target now accepts exactly that.
TEST(FuzzRegression, FinelyDashedVeryWideStrokeReportsTheOutlineLimit) {
  Path line;
  line.move_to({0, 0});
  line.line_to({100, 0});
  StrokeStyle style;
  style.width = 2000;
  style.cap = LineCap::Round;
  style.dashes = {0.003};
  try {
    (void)stroke_to_path(line, style, 0.125);
    FAIL() << "expected the outline limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(kMaxStrokeOutlinePoints)), std::string::npos) << e.what();
  }
}

TEST(FuzzRegression, ShadowsFarOutOfReachLeaveTheShapeDrawn) {
  for (const Shadow shadow : {Shadow{Color{0, 0, 0, 1}, -1e300, 0, 0}, Shadow{Color{0, 0, 0, 1}, 0, 1e300, 2},
                              Shadow{Color{0, 0, 0, 1}, 3, 3, 1e300}, Shadow{Color{0, 0, 0, 1}, 3, 3, 1e6}}) {
    Image image(16, 16);
    image.clear(Color::transparent());
    Canvas canvas(image);
    canvas.set_shadow(shadow);
    canvas.set_fill_color(Color{1, 0, 0, 1});
    ASSERT_NO_THROW(canvas.fill_rect(4, 4, 8, 8));
    EXPECT_EQ(image.pixel(8, 8)[0], 255) << shadow.offset_x << " " << shadow.offset_y << " " << shadow.blur;
    EXPECT_EQ(image.pixel(8, 8)[3], 255);
  }
}

// fuzz_canvas (a 10 s timeout under the sanitizers): a quadratic with its control point at 1e300, filled
// non-exterior in exact mode on a 2 x 2 canvas. Non-exterior flattens all of the path (what connects to infinity
// depends on geometry far outside the image): millions of points. Past kMaxNonExteriorPoints it takes the
// non-zero fallback, counted like the crossing budget's.
TEST(FuzzRegression, NonExteriorFillOfAnAstronomicalCurveTakesTheFallback) {
  Path path;
  path.add_rect(Rect{4, 5.98438, 4 + 1e-07, 5.98438 + 14});
  path.move_to({4, 5.98438});
  path.quad_to({1e300, 28}, {-439.531, -403.984});
  Polylines lines;
  FlattenOptions options;  // no clip: what non-exterior fills get
  flatten(path, Affine{}, options, lines);
  ASSERT_GT(lines.points.size(), Rasterizer::kMaxNonExteriorPoints);
  struct Nothing final : CoverageSink {
    void span(int, int, int, float) override {}
    void row(int, int, int, const float*) override {}
  } sink;
  Rasterizer rasterizer;
  rasterizer.fill(lines, FillRule::NonExterior, AntiAlias::Exact, 2, 2, sink);
  EXPECT_EQ(rasterizer.exact_fallbacks(), 1u);
}
