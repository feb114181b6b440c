// Path construction: verbs and points, implicit moves, finiteness checks, SVG arcs, shapes, transforms, bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/reference.hpp"
#include "vraster/vraster.hpp"

namespace vraster::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

std::vector<Verb> verbs_of(const Path& p) { return {p.verbs().begin(), p.verbs().end()}; }
std::vector<Point> points_of(const Path& p) { return {p.points().begin(), p.points().end()}; }

std::string verb_string(const Path& p) {
  std::string s;
  for (Verb v : p.verbs()) s += "MLQCZ"[static_cast<int>(v)];
  return s;
}

// Every point of every segment of the path, sampled at `per_segment` parameters (de Casteljau, written here),
// excluding moves. Independent of the engine's flattening.
std::vector<Point> sample_curve(const Path& path, int per_segment = 200) {
  std::vector<Point> out;
  const auto pts = path.points();
  std::size_t i = 0;
  Point last{}, start{};
  for (Verb v : path.verbs()) {
    switch (v) {
      case Verb::Move:
        last = start = pts[i++];
        break;
      case Verb::Line:
        for (int k = 0; k <= per_segment; ++k) out.push_back(lerp(last, pts[i], double(k) / per_segment));
        last = pts[i++];
        break;
      case Verb::Quad:
        for (int k = 0; k <= per_segment; ++k) {
          const double t = double(k) / per_segment;
          out.push_back(lerp(lerp(last, pts[i], t), lerp(pts[i], pts[i + 1], t), t));
        }
        last = pts[i + 1];
        i += 2;
        break;
      case Verb::Cubic:
        for (int k = 0; k <= per_segment; ++k) {
          const double t = double(k) / per_segment;
          const Point a = lerp(last, pts[i], t), b = lerp(pts[i], pts[i + 1], t), c = lerp(pts[i + 1], pts[i + 2], t);
          out.push_back(lerp(lerp(a, b, t), lerp(b, c, t), t));
        }
        last = pts[i + 2];
        i += 3;
        break;
      case Verb::Close:
        last = start;
        break;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------

TEST(Path, EachVerbRecordsItsPointsInOrder) {
  Path p;
  p.move_to({1, 2}).line_to({3, 4}).quad_to({5, 6}, {7, 8}).cubic_to({9, 10}, {11, 12}, {13, 14}).close();
  EXPECT_EQ(verb_string(p), "MLQCZ");
  const std::vector<Point> expected = {{1, 2}, {3, 4}, {5, 6}, {7, 8}, {9, 10}, {11, 12}, {13, 14}};
  EXPECT_EQ(points_of(p), expected);
  EXPECT_EQ(p.current_point(), (Point{1, 2})) << "close returns to the contour start";
  EXPECT_FALSE(p.empty());
  p.clear();
  EXPECT_TRUE(p.empty());
  EXPECT_TRUE(p.points().empty());
  EXPECT_EQ(p.current_point(), (Point{0, 0}));
}

TEST(Path, DrawingAfterCloseStartsANewContourAtTheClosedContoursStart) {
  Path p;
  p.move_to(1, 2).line_to(5, 2).line_to(5, 6).close().line_to(9, 9);
  EXPECT_EQ(verb_string(p), "MLLZML");
  const std::vector<Point> expected = {{1, 2}, {5, 2}, {5, 6}, {1, 2}, {9, 9}};
  EXPECT_EQ(points_of(p), expected);
  // Same for curves.
  Path q;
  q.move_to(3, 3).line_to(4, 3).close().cubic_to({0, 0}, {1, 1}, {2, 2});
  EXPECT_EQ(verb_string(q), "MLZMC");
  EXPECT_EQ(q.points()[2], (Point{3, 3}));
}

TEST(Path, DrawingOnAnEmptyPathStartsAtTheOrigin) {
  Path p;
  p.line_to(4, 5);
  EXPECT_EQ(verb_string(p), "ML");
  EXPECT_EQ(p.points()[0], (Point{0, 0}));
}

TEST(Path, MoveAfterMoveReplacesIt) {
  Path p;
  p.move_to(1, 1).move_to(2, 2).line_to(3, 3);
  EXPECT_EQ(verb_string(p), "ML");
  EXPECT_EQ(p.points()[0], (Point{2, 2}));
  // A second close does nothing.
  p.close().close();
  EXPECT_EQ(verb_string(p), "MLZ");
}

// ---------------------------------------------------------------------------------------------------------------
// Non-finite input: throws vraster::Error, and the path (verbs, points, current point, open contour) is as before.

Path sample_open_path() {
  Path p;
  p.move_to(1, 1).line_to(4, 1).quad_to({5, 2}, {4, 4});
  return p;
}

::testing::AssertionResult throws_and_keeps_path(const std::function<void(Path&)>& call) {
  Path p = sample_open_path();
  const auto verbs = verbs_of(p);
  const auto points = points_of(p);
  const Point current = p.current_point();
  try {
    call(p);
    return ::testing::AssertionFailure() << "did not throw";
  } catch (const Error&) {
  }
  if (verbs_of(p) != verbs) return ::testing::AssertionFailure() << "verbs changed to " << verb_string(p);
  if (points_of(p) != points) return ::testing::AssertionFailure() << "points changed";
  if (!(p.current_point() == current)) return ::testing::AssertionFailure() << "current point changed";
  // The contour is still open: the next segment continues it (no new Move).
  p.line_to(0, 0);
  if (verb_string(p) != "MLQL") return ::testing::AssertionFailure() << "contour state changed: " << verb_string(p);
  return ::testing::AssertionSuccess();
}

TEST(Path, NonFiniteCoordinateInAnySegmentCallThrowsAndLeavesThePathUnchanged) {
  for (double bad : {kNaN, kInf, -kInf}) {
    const Point b{bad, 0}, c{0, bad}, ok{2, 3};
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.move_to(b); })) << "move_to x=" << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.move_to(c); })) << "move_to y=" << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.line_to(b); })) << "line_to " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.line_to(c); })) << "line_to " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.quad_to(b, ok); })) << "quad_to control " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.quad_to(ok, c); })) << "quad_to end " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.cubic_to(b, ok, ok); })) << "cubic_to c1 " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.cubic_to(ok, c, ok); })) << "cubic_to c2 " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.cubic_to(ok, ok, b); })) << "cubic_to end " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.arc_to(bad, 1, 0, false, true, ok); })) << "arc rx " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.arc_to(1, bad, 0, false, true, ok); })) << "arc ry " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.arc_to(1, 1, bad, false, true, ok); })) << "arc rot " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.arc_to(1, 1, 0, false, true, c); })) << "arc end " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_ellipse(b, 1, 1); })) << "ellipse centre " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_ellipse(ok, bad, 1); })) << "ellipse rx " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_ellipse(ok, 1, bad); })) << "ellipse ry " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_circle(ok, bad); })) << "circle r " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_round_rect({0, 0, 4, 4}, bad, 1); })) << "rrect " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_round_rect({0, 0, 4, 4}, 1, bad); })) << "rrect " << bad;
    const std::vector<Point> poly = {{0, 0}, {1, 0}, b, {0, 1}};
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_polygon(poly); })) << "polygon, third point " << bad;
  }
}

// Regression (partial rectangle): fixed in bbb3daf (all-or-nothing builders). add_rect and add_round_rect used to
// check their corners one segment at a time, so a non-finite x1/y1 threw after move_to had started a contour:
// add_rect({0, 0, NaN, 1}) left "M(0,0)" behind. Guards: a non-finite rectangle throws and leaves the path as it was.
TEST(Path, NonFiniteRectangleThrowsAndLeavesThePathUnchanged) {
  for (double bad : {kNaN, kInf}) {
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_rect({0, 0, bad, 1}); })) << "add_rect x1 " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_rect({0, 0, 1, bad}); })) << "add_rect y1 " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_rect({bad, 0, 1, 1}); })) << "add_rect x0 " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_round_rect({0, 0, bad, 4}, 1, 1); }))
        << "add_round_rect x1 " << bad;
    EXPECT_TRUE(throws_and_keeps_path([&](Path& p) { p.add_round_rect({0, 0, 4, bad}, 1, 1); }))
        << "add_round_rect y1 " << bad;
  }
}

// Regression (arc overflow left segments behind): fixed in bbb3daf (all-or-nothing builders, arcs computed from the
// start point). A finite arc whose control points overflow (radius near DBL_MAX) used to throw from inside
// arc_segments() after some cubics were appended: arc_to(1.5e308, 1.5e308, 0, false, true, {1e308, 0}) from (0,0)
// threw with 5 verbs in the path, add_ellipse({0,0}, 1.75e308, 1) with a dozen cubics added. Guards: such arcs are
// finite or throw with the path unchanged.
TEST(Path, ArcOrEllipseWithHugeRadiiIsFiniteOrThrowsAndLeavesThePathUnchanged) {
  // This arc's points are all representable (computed relative to its start point): it may succeed, but then
  // every point must be finite.
  Path arc;
  arc.move_to(0, 0);
  try {
    arc.arc_to(1.5e308, 1.5e308, 0, false, true, {1e308, 0});
    for (const Point& q : arc.points()) EXPECT_TRUE(is_finite(q));
  } catch (const vraster::Error&) {
    EXPECT_EQ(arc.points().size(), 1u);
  }
  // An ellipse whose points are representable may succeed (all finite); one reaching past the largest double throws
  // and leaves the path as it was.
  Path ellipse;
  ellipse.add_ellipse({0, 0}, 1.75e308, 1);
  for (const Point& q : ellipse.points()) EXPECT_TRUE(is_finite(q));
  EXPECT_TRUE(throws_and_keeps_path([](Path& p) { p.add_ellipse({1e308, 0}, 1e308, 1); }));
}

// ---------------------------------------------------------------------------------------------------------------
// SVG arcs. From (0,0) to (10,0) with r = 10 the centre is (5, +-sqrt(75)); with y down, sweep = 1 runs
// clockwise on screen, so the small clockwise arc passes above the chord (y < 0) around the centre below it.

struct ArcCase {
  bool large, sweep;
  double cy;             // centre y
  double y_min, y_max;   // expected vertical extent
  double x_min, x_max;   // expected horizontal extent
};

TEST(PathArc, AllFourFlagCombinationsPickTheRightCentreAndSide) {
  const double h = std::sqrt(75.0);
  const ArcCase cases[] = {
      {false, true, h, h - 10, 0, 0, 10},     // small arc above the chord
      {false, false, -h, 0, 10 - h, 0, 10},   // small arc below
      {true, true, -h, -h - 10, 0, -5, 15},   // large arc above, centre above
      {true, false, h, 0, h + 10, -5, 15},    // large arc below, centre below
  };
  for (const ArcCase& c : cases) {
    Path p;
    p.move_to(0, 0).arc_to(10, 10, 0, c.large, c.sweep, {10, 0});
    SCOPED_TRACE(::testing::Message() << "large=" << c.large << " sweep=" << c.sweep);
    EXPECT_EQ(p.current_point(), (Point{10, 0}));
    EXPECT_EQ(p.points().back(), (Point{10, 0}));
    // Every point of the curve is on the circle (cubic arcs of <= 30 degrees: radial error below 4e-7 r).
    const std::vector<Point> curve = sample_curve(p);
    double max_err = 0;
    for (Point q : curve) max_err = std::max(max_err, std::abs(length(q - Point{5, c.cy}) - 10));
    EXPECT_LT(max_err, 4e-6);
    // ... on the expected side: its extent is the expected arc's.
    const Rect b = p.bounds();
    EXPECT_NEAR(b.y0, c.y_min, 1e-5);
    EXPECT_NEAR(b.y1, c.y_max, 1e-5);
    EXPECT_NEAR(b.x0, c.x_min, 1e-5);
    EXPECT_NEAR(b.x1, c.x_max, 1e-5);
    // The arc's midpoint (x = 5) is at the extreme y.
    const double mid_y = c.y_min < -1e-9 ? c.y_min : c.y_max;
    bool found = false;
    for (Point q : curve) found |= std::abs(q.x - 5) < 0.05 && std::abs(q.y - mid_y) < 1e-3;
    EXPECT_TRUE(found) << "no curve point near (5, " << mid_y << ")";
    // Arcs are stored as cubics of at most 30 degrees: 60 degrees -> 2, 300 degrees -> 10.
    EXPECT_EQ(p.verbs().size(), c.large ? 11u : 3u);
  }
}

TEST(PathArc, RadiiTooSmallAreScaledUpToAHalfEllipse) {
  for (bool large : {false, true}) {
    Path p;
    p.move_to(0, 0).arc_to(1, 1, 0, large, true, {10, 0});
    for (Point q : sample_curve(p)) ASSERT_NEAR(length(q - Point{5, 0}), 5, 2e-6) << "large=" << large;
    const Rect b = p.bounds();
    EXPECT_NEAR(b.y0, -5, 1e-6);
    EXPECT_NEAR(b.y1, 0, 1e-9);
    EXPECT_NEAR(b.x0, 0, 1e-9);
    EXPECT_NEAR(b.x1, 10, 1e-9);
  }
  // An ellipse scaled up keeps its aspect ratio: rx = 2, ry = 1 from (0,0) to (0,10) -> rx = 10, ry = 5.
  Path e;
  e.move_to(0, 0).arc_to(2, 1, 0, false, true, {0, 10});
  for (Point q : sample_curve(e)) {
    const double u = q.x / 10, v = (q.y - 5) / 5;
    ASSERT_NEAR(u * u + v * v, 1, 2e-6);
  }
  EXPECT_NEAR(e.bounds().x1, 10, 1e-6);  // sweep = 1 from top to bottom: to the right
}

TEST(PathArc, RotatedEllipseFollowsItsRotatedAxes) {
  // rx = 10, ry = 5 turned 90 degrees: semi-axis 5 horizontal, 10 vertical; the chord (0,0)-(10,0) is its
  // horizontal diameter, so the centre is (5, 0) and the sweep-1 half bulges up to y = -10.
  Path p;
  p.move_to(0, 0).arc_to(10, 5, 90, false, true, {10, 0});
  for (Point q : sample_curve(p)) {
    const double u = (q.x - 5) / 5, v = q.y / 10;
    ASSERT_NEAR(u * u + v * v, 1, 2e-6);
  }
  EXPECT_NEAR(p.bounds().y0, -10, 1e-5);
}

TEST(PathArc, ZeroRadiusIsAStraightLine) {
  for (auto [rx, ry] : {std::pair{0.0, 5.0}, std::pair{5.0, 0.0}, std::pair{0.0, 0.0}}) {
    Path p;
    p.move_to(0, 0).arc_to(rx, ry, 30, true, false, {10, 3});
    EXPECT_EQ(verb_string(p), "ML");
    EXPECT_EQ(p.points()[1], (Point{10, 3}));
  }
}

TEST(PathArc, ArcToTheCurrentPointAddsNothing) {
  Path p;
  p.move_to(0, 0).line_to(10, 0);
  p.arc_to(5, 5, 0, true, true, {10, 0});
  EXPECT_EQ(verb_string(p), "ML");
  EXPECT_EQ(p.current_point(), (Point{10, 0}));
}

TEST(PathArc, NegativeRadiiActAsTheirAbsoluteValues) {
  Path a, b;
  a.move_to(0, 0).arc_to(-10, -10, 0, false, true, {10, 0});
  b.move_to(0, 0).arc_to(10, 10, 0, false, true, {10, 0});
  EXPECT_EQ(points_of(a), points_of(b));
}

// Regression (arc radius overflow): fixed in bbb3daf (overflow-free arcs). For radii above ~1e77, rx^2 * ry^2 used to
// overflow in the centre computation (F.6.5.2): the square-root factor became NaN -> 0 and the centre landed on the
// chord's midpoint, so arc_to(1e200, 1e200, 0, false, true, {10, 0}) from (0,0) drew a half ellipse reaching
// y = -1e200 instead of an all but straight arc (sagitta 25 / 2r). Guards: huge radii give a nearly straight arc.
TEST(PathArc, HugeRadiusGivesANearlyStraightArc) {
  for (double r : {1e10, 1e100, 1e200, 1e300}) {
    Path p;
    p.move_to(0, 0).arc_to(r, r, 0, false, true, {10, 0});
    const Rect b = p.bounds();
    EXPECT_NEAR(b.y0, 0, 1e-6) << "r=" << r;
    EXPECT_NEAR(b.x0, 0, 1e-6) << "r=" << r;
    EXPECT_NEAR(b.x1, 10, 1e-6) << "r=" << r;
  }
}

TEST(PathArc, LargeButSafeRadiusGivesANearlyStraightArc) {
  Path p;
  p.move_to(0, 0).arc_to(1e10, 1e10, 0, false, true, {10, 0});
  const Rect b = p.bounds();
  EXPECT_NEAR(b.y0, -25 / 2e10, 1e-12);  // sagitta ~ chord^2 / (8 r)
  EXPECT_EQ(b.y1, 0);
  EXPECT_NEAR(b.x1, 10, 1e-9);
}

// ---------------------------------------------------------------------------------------------------------------
// Shapes.

Polygon flattened_polygon(const Path& p, double tol = 1e-6) {
  Polylines lines;
  FlattenOptions o;
  o.tolerance = tol;
  flatten(p, Affine{}, o, lines);
  EXPECT_EQ(lines.contour_count(), 1u);
  const auto c = lines.contour(0);
  return {c.begin(), c.end()};
}

TEST(PathShapes, RectIsClosedClockwiseFromItsTopLeftCorner) {
  Path p;
  p.add_rect({1, 2, 4, 7});
  EXPECT_EQ(verb_string(p), "MLLLZ");
  const std::vector<Point> expected = {{1, 2}, {4, 2}, {4, 7}, {1, 7}};
  EXPECT_EQ(points_of(p), expected);
  EXPECT_DOUBLE_EQ(shoelace_area(expected), 15.0);  // positive: clockwise on screen
  EXPECT_EQ(p.current_point(), (Point{1, 2}));
}

TEST(PathShapes, RoundRectHasStraightSidesAndEllipticalCorners) {
  Path p;
  p.add_round_rect({0, 0, 10, 6}, 2, 1);
  EXPECT_EQ(p.points()[0], (Point{2, 0}));
  EXPECT_EQ(p.verbs().front(), Verb::Move);
  EXPECT_EQ(p.verbs().back(), Verb::Close);
  const Rect b = p.bounds();
  EXPECT_NEAR(b.x0, 0, 1e-12);
  EXPECT_NEAR(b.y0, 0, 1e-12);
  EXPECT_NEAR(b.x1, 10, 1e-12);
  EXPECT_NEAR(b.y1, 6, 1e-12);
  EXPECT_NEAR(shoelace_area(flattened_polygon(p)), 60 - (4 - kPi) * 2 * 1, 1e-3);
  // Every curve point lies on a side or on the quarter ellipse around its corner's centre.
  for (Point q : sample_curve(p)) {
    const double cx = q.x < 2 ? 2 : (q.x > 8 ? 8 : q.x), cy = q.y < 1 ? 1 : (q.y > 5 ? 5 : q.y);
    if (cx == q.x || cy == q.y) {  // on a straight side
      ASSERT_TRUE(std::abs(q.x) < 1e-12 || std::abs(q.x - 10) < 1e-12 || std::abs(q.y) < 1e-12 ||
                  std::abs(q.y - 6) < 1e-12)
          << "(" << q.x << "," << q.y << ")";
    } else {
      const double u = (q.x - cx) / 2, v = (q.y - cy) / 1;
      ASSERT_NEAR(u * u + v * v, 1, 2e-6) << "(" << q.x << "," << q.y << ")";
    }
  }
}

TEST(PathShapes, RoundRectClampsRadiiToHalfTheSides) {
  // rx 7 -> 5 and ry 3 -> 2 on a 10 x 4 rectangle: the outline is the ellipse centred (5, 2) with radii 5, 2.
  Path p;
  p.add_round_rect({0, 0, 10, 4}, 7, 3);
  EXPECT_EQ(p.points()[0], (Point{5, 0}));
  for (Point q : sample_curve(p)) {
    const double u = (q.x - 5) / 5, v = (q.y - 2) / 2;
    ASSERT_NEAR(u * u + v * v, 1, 2e-6) << "(" << q.x << "," << q.y << ")";
  }
  EXPECT_NEAR(shoelace_area(flattened_polygon(p)), kPi * 10, 1e-3);
  // Zero radius: a plain rectangle.
  Path plain, rect;
  plain.add_round_rect({1, 1, 5, 3}, 0, 2);
  rect.add_rect({1, 1, 5, 3});
  EXPECT_EQ(points_of(plain), points_of(rect));
  EXPECT_EQ(verbs_of(plain), verbs_of(rect));
}

TEST(PathShapes, EllipseIsClosedClockwiseWithTheRightSizeAndArea) {
  Path p;
  p.add_ellipse({10, 20}, 6, 3);
  EXPECT_EQ(p.points()[0], (Point{16, 20}));
  EXPECT_EQ(p.points().back(), (Point{16, 20}));
  EXPECT_EQ(p.verbs().front(), Verb::Move);
  EXPECT_EQ(p.verbs().back(), Verb::Close);
  EXPECT_EQ(p.verbs().size(), 14u);  // M + 12 cubics of 30 degrees + Z
  const Rect b = p.bounds();
  EXPECT_NEAR(b.x0, 4, 1e-9);
  EXPECT_NEAR(b.x1, 16, 1e-9);
  EXPECT_NEAR(b.y0, 17, 1e-5);
  EXPECT_NEAR(b.y1, 23, 1e-5);
  for (Point q : sample_curve(p)) {
    const double u = (q.x - 10) / 6, v = (q.y - 20) / 3;
    ASSERT_NEAR(u * u + v * v, 1, 2e-6);
  }
  const double area = shoelace_area(flattened_polygon(p));
  EXPECT_GT(area, 0) << "clockwise on screen";
  EXPECT_NEAR(area, kPi * 18, 1e-3);
  // Going clockwise on screen (y down) from the rightmost point means going down first.
  EXPECT_GT(p.points()[1].y, 20);
}

TEST(PathShapes, PolygonClosedOrOpen) {
  const std::vector<Point> pts = {{0, 0}, {3, 0}, {3, 2}};
  Path closed, open, none;
  closed.add_polygon(pts);
  open.add_polygon(pts, false);
  none.add_polygon(std::vector<Point>{});
  EXPECT_EQ(verb_string(closed), "MLLZ");
  EXPECT_EQ(verb_string(open), "MLL");
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(points_of(closed), pts);
  EXPECT_EQ(closed.current_point(), (Point{0, 0}));
  EXPECT_EQ(open.current_point(), (Point{3, 2}));
}

TEST(PathShapes, AddPathAppendsEveryContour) {
  Path a, b;
  a.move_to(0, 0).line_to(1, 0).close();
  b.move_to(5, 5).quad_to({6, 5}, {6, 6}).cubic_to({7, 7}, {8, 8}, {9, 9});
  a.add_path(b);
  EXPECT_EQ(verb_string(a), "MLZMQC");
  EXPECT_EQ(a.points().back(), (Point{9, 9}));
}

// ---------------------------------------------------------------------------------------------------------------

TEST(PathTransform, TransformedMapsEveryPointAndKeepsTheOriginal) {
  Path p;
  p.move_to(1, 2).line_to(3, 4).quad_to({5, 6}, {7, 8}).cubic_to({9, 10}, {11, 12}, {13, 14});
  const Affine m{2, 1, -1, 3, 10, 20};  // x' = 2x - y + 10, y' = x + 3y + 20
  const Path q = p.transformed(m);
  ASSERT_EQ(q.points().size(), p.points().size());
  EXPECT_EQ(verbs_of(q), verbs_of(p));
  for (std::size_t i = 0; i < p.points().size(); ++i) {
    const Point a = p.points()[i];
    EXPECT_EQ(q.points()[i], (Point{2 * a.x - a.y + 10, a.x + 3 * a.y + 20})) << "point " << i;
  }
  EXPECT_EQ(q.current_point(), (Point{2 * 13 - 14 + 10, 13 + 3 * 14 + 20}));
  EXPECT_EQ(p.points()[0], (Point{1, 2}));  // original untouched
  // The transformed path continues from the mapped current point; after close, from the mapped contour start.
  Path r = p.transformed(Affine::translate(100, 0));
  r.close().line_to(0, 0);
  EXPECT_EQ(r.points()[r.points().size() - 2], (Point{101, 2}));
}

TEST(PathTransform, TransformedThrowsOnNonFiniteResultAndKeepsTheOriginal) {
  Path p;
  p.move_to(1, 1).line_to(1e300, 0);
  const auto before = points_of(p);
  EXPECT_THROW((void)p.transformed(Affine::scale(1e10)), Error);
  EXPECT_EQ(points_of(p), before);
}

// Regression (half-transformed path): fixed in bbb3daf (all-or-nothing transform). Path::transform() used to assign
// each mapped point before checking it, so move_to(1,1).line_to(1e300,0); transform(scale(1e10)) threw with the
// points now (1e10,1e10) (inf,0), breaking the "every coordinate is finite" invariant later stages trust. Guards: a
// failed transform leaves the path unchanged and finite.
TEST(PathTransform, FailedTransformInPlaceLeavesThePathUnchanged) {
  Path p;
  p.move_to(1, 1).line_to(1e300, 0);
  const auto before = points_of(p);
  EXPECT_THROW(p.transform(Affine::scale(1e10)), Error);
  EXPECT_EQ(points_of(p), before);
  for (Point q : p.points()) EXPECT_TRUE(is_finite(q));
}

// ---------------------------------------------------------------------------------------------------------------

TEST(PathBounds, BoundsAreTightForCurvesWhileControlBoundsIncludeControlPoints) {
  Path cubic;
  cubic.move_to(0, 0).cubic_to({0, -10}, {10, -10}, {10, 0});  // y(t) = -30 t (1 - t): minimum -7.5
  EXPECT_NEAR(cubic.bounds().y0, -7.5, 1e-12);
  EXPECT_EQ(cubic.bounds().y1, 0);
  EXPECT_EQ(cubic.control_bounds().y0, -10);
  Path quad;
  quad.move_to(0, 0).quad_to({5, 10}, {10, 0});  // y(t) = 20 t (1 - t): maximum 5
  EXPECT_NEAR(quad.bounds().y1, 5, 1e-12);
  EXPECT_EQ(quad.control_bounds().y1, 10);
  EXPECT_EQ(quad.bounds().x0, 0);
  EXPECT_EQ(quad.bounds().x1, 10);
}

TEST(PathBounds, CubicBulgingBeyondItsEndpointsMatchesDenseSampling) {
  const Point curves[][4] = {
      {{0, 0}, {-10, 10}, {20, 10}, {10, 0}},      // bulges left of 0 and right of 10
      {{0, 10}, {-10, 10}, {180, 10}, {60, 10}},  // collinear, doubles back
      {{0, 0}, {100, 100}, {-100, 100}, {0, 0}},  // a loop
      {{3, 3}, {3, 3}, {3, 3}, {3, 3}},           // a point
      {{0, 0}, {30, -20}, {-20, 40}, {50, 5}},
  };
  for (const auto& c : curves) {
    Path p;
    p.move_to(c[0]).cubic_to(c[1], c[2], c[3]);
    Rect sampled = Rect::from_point(c[0]);
    for (Point q : sample_curve(p, 200000)) sampled.include(q);
    const Rect b = p.bounds();
    const double tol = 1e-6 * (1 + std::max(sampled.width(), sampled.height()));
    EXPECT_NEAR(b.x0, sampled.x0, tol) << "curve from (" << c[0].x << "," << c[0].y << ")";
    EXPECT_NEAR(b.y0, sampled.y0, tol);
    EXPECT_NEAR(b.x1, sampled.x1, tol);
    EXPECT_NEAR(b.y1, sampled.y1, tol);
    const Rect cb = p.control_bounds();
    EXPECT_TRUE(cb.x0 <= b.x0 && cb.y0 <= b.y0 && cb.x1 >= b.x1 && cb.y1 >= b.y1);
  }
}

// control_bounds takes the points two at a time (src/geometry/point_bounds.hpp): every count of points, odd and even,
// the extremes anywhere among them, gives the box of a one-by-one pass.
TEST(PathBounds, ControlBoundsAreTheBoxOfEveryPointForEveryCount) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> coord(-1e3, 1e3);
  for (int n = 1; n <= 40; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      Path p;
      Rect want{};
      for (int i = 0; i < n; ++i) {
        const Point q{coord(rng), coord(rng)};
        if (i == 0) {
          p.move_to(q);
          want = Rect::from_point(q);
        } else {
          p.line_to(q);
        }
        want.include(q);
      }
      const Rect got = p.control_bounds();
      ASSERT_TRUE(got.x0 == want.x0 && got.y0 == want.y0 && got.x1 == want.x1 && got.y1 == want.y1) << n;
    }
  }
}

TEST(PathBounds, EmptyPathHasZeroBounds) {
  const Path p;
  const Rect b = p.bounds(), cb = p.control_bounds();
  EXPECT_TRUE(b.x0 == 0 && b.y0 == 0 && b.x1 == 0 && b.y1 == 0);
  EXPECT_TRUE(cb.x0 == 0 && cb.y0 == 0 && cb.x1 == 0 && cb.y1 == 0);
}

}  // namespace
TEST(PathBounds, RandomCurvesAreBoundedTightly) {
  // The exact bounds of random quads and cubics (control points often far outside the end points, so the extrema
  // count): every sampled curve point lies inside, and each side is reached by some sample (within what 4096
  // samples per curve resolve).
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> coord(-100, 100);
  for (int round = 0; round < 200; ++round) {
    Path p;
    p.move_to(coord(rng), coord(rng));
    for (int k = 0; k < 3; ++k) {
      if (rng() % 2) {
        p.quad_to({coord(rng), coord(rng)}, {coord(rng), coord(rng)});
      } else {
        p.cubic_to({coord(rng), coord(rng)}, {coord(rng), coord(rng)}, {coord(rng), coord(rng)});
      }
    }
    const Rect b = p.bounds();
    Rect sampled = Rect::from_point(p.points()[0]);
    Point last = p.points()[0];
    std::size_t i = 1;
    for (const Verb v : p.verbs()) {
      if (v == Verb::Move) continue;
      const int n = v == Verb::Quad ? 2 : 3;
      for (int s = 0; s <= 4096; ++s) {
        const double t = s / 4096.0, u = 1 - t;
        const Point q = n == 2 ? last * (u * u) + p.points()[i] * (2 * u * t) + p.points()[i + 1] * (t * t)
                               : last * (u * u * u) + p.points()[i] * (3 * u * u * t) +
                                     p.points()[i + 1] * (3 * u * t * t) + p.points()[i + 2] * (t * t * t);
        sampled.include(q);
      }
      last = p.points()[i + n - 1];
      i += n;
    }
    ASSERT_LE(b.x0, sampled.x0 + 1e-9);
    ASSERT_LE(b.y0, sampled.y0 + 1e-9);
    ASSERT_GE(b.x1, sampled.x1 - 1e-9);
    ASSERT_GE(b.y1, sampled.y1 - 1e-9);
    ASSERT_NEAR(b.x0, sampled.x0, 1e-3);
    ASSERT_NEAR(b.y0, sampled.y0, 1e-3);
    ASSERT_NEAR(b.x1, sampled.x1, 1e-3);
    ASSERT_NEAR(b.y1, sampled.y1, 1e-3);
  }
}

}  // namespace vraster::test
