// The stroker and hairlines: exact coverage of small strokes against hand-built polygons, the hard cases by
// name, and random strokes against an independent point-in-stroke reference.
//
// "Equal" means: coverage within 1e-4 of the exact area of a hand-computed polygon (the analytic rasterizer is
// exact for such shapes), within the stated tolerance of a supersampled reference where circles are involved,
// or identical pixel-centre inside/outside decisions away from a 0.02 px band around the reference boundary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "support/capture.hpp"
#include "vraster/lines.hpp"
#include "vraster/stroke.hpp"

namespace vraster {
namespace {

using test::CoverageGrid;
constexpr double kPi = 3.14159265358979323846;

CoverageGrid stroke_grid(const Path& path, const StrokeStyle& style, int w, int h, AntiAlias aa = AntiAlias::Analytic) {
  return test::rasterize(stroke_to_path(path, style, 0.01), FillRule::NonZero, aa, w, h, 0.005);
}

// Exact area of polygon ∩ pixel square (Sutherland-Hodgman against the square, then the shoelace formula).
double pixel_area(const std::vector<Point>& poly, int px, int py) {
  std::vector<Point> cur = poly, next;
  auto clip = [&](auto inside, auto cut) {
    next.clear();
    for (std::size_t i = 0; i < cur.size(); ++i) {
      const Point a = cur[i], b = cur[(i + 1) % cur.size()];
      const bool ia = inside(a), ib = inside(b);
      if (ia) next.push_back(a);
      if (ia != ib) next.push_back(cut(a, b));
    }
    cur.swap(next);
  };
  const double x0 = px, x1 = px + 1, y0 = py, y1 = py + 1;
  clip([&](Point p) { return p.x >= x0; }, [&](Point a, Point b) { return lerp(a, b, (x0 - a.x) / (b.x - a.x)); });
  clip([&](Point p) { return p.x <= x1; }, [&](Point a, Point b) { return lerp(a, b, (x1 - a.x) / (b.x - a.x)); });
  clip([&](Point p) { return p.y >= y0; }, [&](Point a, Point b) { return lerp(a, b, (y0 - a.y) / (b.y - a.y)); });
  clip([&](Point p) { return p.y <= y1; }, [&](Point a, Point b) { return lerp(a, b, (y1 - a.y) / (b.y - a.y)); });
  double s = 0;
  for (std::size_t i = 0; i < cur.size(); ++i) s += cross(cur[i], cur[(i + 1) % cur.size()]);
  return std::fabs(s) / 2;
}

void expect_polygon_coverage(const CoverageGrid& g, const std::vector<Point>& poly, double tol = 1e-4) {
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      ASSERT_NEAR(g.at(x, y), pixel_area(poly, x, y), tol) << "pixel " << x << "," << y << "\n" << g.to_string();
    }
  }
  EXPECT_TRUE(g.violations().empty());
}

// Supersampled reference coverage of a point predicate (n x n samples per pixel).
template <class Inside>
void expect_supersampled(const CoverageGrid& g, Inside&& inside, int n, double tol) {
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      int hits = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) hits += inside(Point{x + (i + 0.5) / n, y + (j + 0.5) / n});
      ASSERT_NEAR(g.at(x, y), double(hits) / (n * n), tol) << "pixel " << x << "," << y << "\n" << g.to_string();
    }
  }
}

double dist_to_segment(Point p, Point a, Point b) {
  const Point d = b - a;
  const double l2 = dot(d, d);
  double t = l2 > 0 ? dot(p - a, d) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return length(p - (a + d * t));
}

// ---- independent reference: is q inside the stroke of an open polyline? (union of convex pieces) ----
struct RefStroke {
  std::vector<Point> pts;
  StrokeStyle style;

  bool inside(Point q) const {
    const double hw = style.width / 2;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const Point a = pts[i], b = pts[i + 1];
      const double len = length(b - a);
      if (len == 0) continue;
      const Point d = (b - a) * (1 / len);
      const double t = dot(q - a, d), s = cross(d, q - a);
      if (t >= 0 && t <= len && std::fabs(s) <= hw) return true;
    }
    // Joins.
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
      const Point p = pts[i];
      const Point d0 = (p - pts[i - 1]) * (1 / length(p - pts[i - 1])), d1 = (pts[i + 1] - p) * (1 / length(pts[i + 1] - p));
      const double c = cross(d0, d1);
      if (style.join == LineJoin::Round) {
        // The pie slice on the outer side (as Cairo, Skia and the SVG "arc around the join point" draw it).
        const Point v = q - p;
        if (length(v) > hw) continue;
        if (c == 0) {
          if (dot(d0, d1) < 0 && dot(v, d0) >= 0) return true;  // reversal: the half disc ahead
          continue;
        }
        const double sgn = c > 0 ? -1 : 1;
        const Point a = Point{-d0.y, d0.x} * sgn, b = Point{-d1.y, d1.x} * sgn;
        const double ab = cross(a, b);
        if (cross(a, v) * ab >= 0 && cross(v, b) * ab >= 0) return true;
        continue;
      }
      if (c == 0) continue;
      const double sgn = c > 0 ? -1 : 1;  // outer side normal sign (normal = (-d.y, d.x))
      const Point a = p + Point{-d0.y, d0.x} * (sgn * hw), b = p + Point{-d1.y, d1.x} * (sgn * hw);
      if (in_triangle(q, p, a, b)) return true;
      const double theta = std::atan2(c, dot(d0, d1));
      const double cs = std::cos(std::fabs(theta) / 2);
      if (style.join == LineJoin::Miter && cs * style.miter_limit >= 1) {
        // Miter tip: intersection of the two outer offset lines.
        const double tt = cross(b - a, d1) / cross(d0, d1);
        const Point tip = a + d0 * tt;
        if (in_triangle(q, a, tip, b)) return true;
      }
    }
    // Caps.
    for (int e = 0; e < 2; ++e) {
      const Point p = e == 0 ? pts.front() : pts.back();
      const Point o = e == 0 ? pts[1] : pts[pts.size() - 2];
      const Point d = (p - o) * (1 / length(p - o));  // outward
      if (style.cap == LineCap::Round && length(q - p) <= hw) return true;
      if (style.cap == LineCap::Square) {
        const double t = dot(q - p, d), s = cross(d, q - p);
        if (t >= 0 && t <= hw && std::fabs(s) <= hw) return true;
      }
    }
    return false;
  }
  static bool in_triangle(Point q, Point a, Point b, Point c) {
    const double d1 = cross(b - a, q - a), d2 = cross(c - b, q - b), d3 = cross(a - c, q - c);
    const bool neg = d1 < 0 || d2 < 0 || d3 < 0, pos = d1 > 0 || d2 > 0 || d3 > 0;
    return !(neg && pos);
  }
};

// Aliased fill at pixel centres vs the reference, ignoring centres within `band` of the reference boundary.
void expect_matches_reference(const Path& path, const StrokeStyle& style, const RefStroke& ref, int w, int h,
                              double band = 0.03) {
  const CoverageGrid g = stroke_grid(path, style, w, h, AntiAlias::None);
  int checked = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Point c{x + 0.5, y + 0.5};
      const bool in = ref.inside(c);
      bool near = false;
      for (Point o : {Point{band, 0}, Point{-band, 0}, Point{0, band}, Point{0, -band}, Point{band, band},
                      Point{-band, -band}, Point{band, -band}, Point{-band, band}}) {
        if (ref.inside(c + o) != in) near = true;
      }
      if (near) continue;
      ++checked;
      ASSERT_EQ(g.at(x, y) > 0.5f, in) << "pixel " << x << "," << y << "\n" << g.to_string();
    }
  }
  EXPECT_GT(checked, w * h / 2);
}

Path polyline(std::initializer_list<Point> pts) {
  Path p;
  bool first = true;
  for (Point q : pts) {
    if (first) p.move_to(q); else p.line_to(q);
    first = false;
  }
  return p;
}

StrokeStyle style_of(double width, LineCap cap, LineJoin join, double limit = 4) {
  StrokeStyle s;
  s.width = width;
  s.cap = cap;
  s.join = join;
  s.miter_limit = limit;
  return s;
}

// ---- caps and joins at 8-16 px, exact ----

TEST(StrokeCaps, ButtIsTheExactRectangle) {
  const auto g = stroke_grid(polyline({{2, 5}, {10, 5.5}}), style_of(2, LineCap::Butt, LineJoin::Miter), 12, 10);
  const Point d = Point{8, 0.5} * (1 / std::hypot(8, 0.5)), n{-d.y, d.x};
  expect_polygon_coverage(g, {Point{2, 5} + n, Point{10, 5.5} + n, Point{10, 5.5} - n, Point{2, 5} - n});
}

TEST(StrokeCaps, SquareExtendsByHalfWidth) {
  const auto g = stroke_grid(polyline({{2, 5}, {10, 5}}), style_of(2, LineCap::Square, LineJoin::Miter), 12, 10);
  expect_polygon_coverage(g, {{1, 4}, {11, 4}, {11, 6}, {1, 6}});
}

TEST(StrokeCaps, RoundIsAStadium) {
  const auto g = stroke_grid(polyline({{4, 8}, {12, 8}}), style_of(4, LineCap::Round, LineJoin::Miter), 16, 16);
  expect_supersampled(g, [](Point q) { return dist_to_segment(q, {4, 8}, {12, 8}) <= 2; }, 32, 0.03);
  EXPECT_NEAR(g.total(), 8 * 4 + kPi * 4, 0.05);
}

TEST(StrokeJoins, MiterIsTheExactLShape) {
  const auto g = stroke_grid(polyline({{2, 10}, {8, 10}, {8, 2}}), style_of(2, LineCap::Butt, LineJoin::Miter), 12, 13);
  expect_polygon_coverage(g, {{2, 9}, {7, 9}, {7, 2}, {9, 2}, {9, 11}, {2, 11}});
}

TEST(StrokeJoins, BevelCutsTheCorner) {
  const auto g = stroke_grid(polyline({{2, 10}, {8, 10}, {8, 2}}), style_of(2, LineCap::Butt, LineJoin::Bevel), 12, 13);
  expect_polygon_coverage(g, {{2, 9}, {7, 9}, {7, 2}, {9, 2}, {9, 10}, {8, 11}, {2, 11}});
}

TEST(StrokeJoins, RoundAddsAQuarterDisc) {
  const auto g = stroke_grid(polyline({{2, 10}, {8, 10}, {8, 2}}), style_of(4, LineCap::Butt, LineJoin::Round), 14, 14);
  expect_supersampled(g, [](Point q) {
    return (q.x >= 2 && q.x <= 8 && std::fabs(q.y - 10) <= 2) || (q.y >= 2 && q.y <= 10 && std::fabs(q.x - 8) <= 2) ||
           length(q - Point{8, 10}) <= 2;
  }, 32, 0.03);
}

TEST(StrokeJoins, MiterClipCutsTheMiterAtTheLimit) {
  // A right angle (miter ratio sqrt(2)) under limit 1.2: SVG 2's miter-clip cuts the miter square to the
  // bisector at 1.2 * width / 2 from the vertex (8, 10): the line x + y = 18 + 1.2 sqrt(2), which leaves the
  // corner pixel [8, 9] x [10, 11] all but the triangle beyond it (legs 2 - 1.2 sqrt(2)).
  const Path p = polyline({{2, 10}, {8, 10}, {8, 2}});
  const auto clip = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::MiterClip, 1.2), 12, 13);
  const auto bevel = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::Bevel), 12, 13);
  const double leg = 2 - 1.2 * std::sqrt(2.0);
  EXPECT_NEAR(clip.at(8, 10), 1 - leg * leg / 2, 1e-4);
  EXPECT_NEAR(clip.total() - bevel.total(), 0.5 - leg * leg / 2, 1e-4);  // only the corner pixel differs
  // Under a limit the miter fits, miter-clip is the miter.
  const auto miter = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::Miter, 1.5), 12, 13);
  const auto unclipped = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::MiterClip, 1.5), 12, 13);
  for (int y = 0; y < 13; ++y)
    for (int x = 0; x < 12; ++x) ASSERT_NEAR(miter.at(x, y), unclipped.at(x, y), 1e-5);
  // A reversal has an infinite miter: clipped, it runs on limit * width / 2 = 3 past the vertex (14, 6).
  const auto reversal = stroke_grid(polyline({{2, 6}, {14, 6}, {4, 6}}), style_of(2, LineCap::Butt, LineJoin::MiterClip, 3),
                                    20, 12);
  EXPECT_NEAR(reversal.at(16, 5), 1.0, 1e-4);
  EXPECT_NEAR(reversal.at(16, 6), 1.0, 1e-4);
  EXPECT_NEAR(reversal.at(17, 5), 0.0, 1e-4);
  EXPECT_NEAR(reversal.total(), 2 * 15, 1e-3);  // (2..17) x (5..7)
  LineJoin parsed = LineJoin::Miter;
  EXPECT_TRUE(parse_line_join("miter-clip", parsed));
  EXPECT_EQ(parsed, LineJoin::MiterClip);
}

TEST(StrokeJoins, MiterLimitFallsBackToBevelAtTheDocumentedRatio) {
  // A right angle has miter ratio sqrt(2) = 1.414...: limit 1.5 keeps the miter, 1.4 bevels.
  const Path p = polyline({{2, 10}, {8, 10}, {8, 2}});
  const auto miter = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::Miter, 1.5), 12, 13);
  const auto bevel = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::Miter, 1.4), 12, 13);
  EXPECT_NEAR(miter.at(8, 10), 1.0, 1e-4);
  EXPECT_NEAR(bevel.at(8, 10), 0.5, 1e-4);
  EXPECT_NEAR(miter.total() - bevel.total(), 0.5, 1e-4);
  // A sharp turn (about 170 degrees) bevels under the default limit 4.
  const Path sharp = polyline({{2, 6}, {14, 6}, {2, 8}});
  const auto m = stroke_grid(sharp, style_of(2, LineCap::Butt, LineJoin::Miter), 24, 14);
  const auto b = stroke_grid(sharp, style_of(2, LineCap::Butt, LineJoin::Bevel), 24, 14);
  for (int y = 0; y < 14; ++y)
    for (int x = 0; x < 24; ++x) ASSERT_NEAR(m.at(x, y), b.at(x, y), 1e-5);
  const auto big = stroke_grid(sharp, style_of(2, LineCap::Butt, LineJoin::Miter, 100), 24, 14);
  EXPECT_GT(big.total(), b.total() + 1.0);
}

// ---- the hard cases ----

TEST(StrokeHardCases, ZeroLengthSubpaths) {
  for (bool closed : {false, true}) {
    Path p;
    p.move_to(6, 6);
    if (closed) p.close(); else p.line_to(6, 6);
    const auto round = stroke_grid(p, style_of(4, LineCap::Round, LineJoin::Miter), 12, 12);
    // Chords inside the circle with sagitta <= tolerance/2 = 0.005 lose at most perimeter * 0.005 = 0.063.
    EXPECT_NEAR(round.total(), kPi * 4 - 0.03, 0.035) << closed;
    expect_supersampled(round, [](Point q) { return length(q - Point{6, 6}) <= 2; }, 32, 0.03);
    const auto square = stroke_grid(p, style_of(4, LineCap::Square, LineJoin::Miter), 12, 12);
    expect_polygon_coverage(square, {{4, 4}, {8, 4}, {8, 8}, {4, 8}});
    EXPECT_TRUE(stroke_to_path(p, style_of(4, LineCap::Butt, LineJoin::Miter), 0.01).empty());
  }
  Path lone;
  lone.move_to(6, 6);
  EXPECT_TRUE(stroke_to_path(lone, style_of(4, LineCap::Round, LineJoin::Round), 0.01).empty());
}

TEST(StrokeHardCases, Reversal180Degrees) {
  const Path p = polyline({{2, 5}, {10, 5}, {4, 5}});
  // Miter (limit exceeded at 180 degrees) and bevel: exactly the rectangle, covered once.
  for (LineJoin j : {LineJoin::Miter, LineJoin::Bevel}) {
    const auto g = stroke_grid(p, style_of(2, LineCap::Butt, j), 14, 10);
    expect_polygon_coverage(g, {{2, 4}, {10, 4}, {10, 6}, {2, 6}});
  }
  // Round: plus a half disc beyond the turn.
  const auto g = stroke_grid(p, style_of(2, LineCap::Butt, LineJoin::Round), 14, 10);
  expect_supersampled(g, [](Point q) { return (q.x >= 2 && q.x <= 10 && std::fabs(q.y - 5) <= 1) || length(q - Point{10, 5}) <= 1; }, 32, 0.03);
}

TEST(StrokeHardCases, CuspInACubic) {
  // B'(1/2) = 0 for these control points: a cusp at (25, 32.5).
  Path p;
  p.move_to(10, 20).cubic_to({30, 40}, {10, 40}, {30, 20});
  // The stroke of a curve with round joins is every point within w/2 of the curve (a cusp included).
  std::vector<Point> dense;
  for (int i = 0; i <= 4000; ++i) {
    const double t = i / 4000.0, u = 1 - t;
    dense.push_back(Point{10, 20} * (u * u * u) + Point{30, 40} * (3 * u * u * t) + Point{10, 40} * (3 * u * t * t) +
                    Point{30, 20} * (t * t * t));
  }
  for (double width : {3.0, 12.0}) {
    const auto g = stroke_grid(p, style_of(width, LineCap::Round, LineJoin::Round), 40, 48, AntiAlias::None);
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 40; ++x) {
        const Point c{x + 0.5, y + 0.5};
        double d = 1e9;
        for (std::size_t i = 0; i + 1 < dense.size(); ++i) d = std::min(d, dist_to_segment(c, dense[i], dense[i + 1]));
        if (std::fabs(d - width / 2) < 0.03) continue;
        ASSERT_EQ(g.at(x, y) > 0.5f, d < width / 2) << "width " << width << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(StrokeCurves, OffsetWithinTolerance) {
  // A circle of radius 20 (stored as cubics) stroked 10 wide is the ring 15 <= r <= 25. For several tolerances:
  // no outline point lies outside the ring by more than the tolerance, and pixel centres deeper than the
  // tolerance inside the ring are filled, those farther than the tolerance outside are not.
  for (double tol : {0.5, 0.1, 0.02}) {
    Path c;
    c.add_circle({30, 30}, 20);
    const Path o = stroke_to_path(c, style_of(10, LineCap::Butt, LineJoin::Miter), tol);
    ASSERT_GT(o.points().size(), 8u);
    for (Point q : o.points()) {
      const double r = length(q - Point{30, 30});
      ASSERT_GE(r, 15 - tol) << "tol " << tol;
      ASSERT_LE(r, 25 + tol) << "tol " << tol;
    }
    const auto g = test::rasterize(o, FillRule::NonZero, AntiAlias::None, 60, 60, 0.001);
    for (int y = 0; y < 60; ++y) {
      for (int x = 0; x < 60; ++x) {
        const double r = length(Point{x + 0.5, y + 0.5} - Point{30, 30});
        if (r > 15 + tol && r < 25 - tol) {
          ASSERT_EQ(g.at(x, y), 1.0f) << "tol " << tol << " r " << r;
        }
        if (r < 15 - tol || r > 25 + tol) {
          ASSERT_EQ(g.at(x, y), 0.0f) << "tol " << tol << " r " << r;
        }
      }
    }
  }
}

TEST(StrokeHardCases, VeryShortSegmentsUnderVeryWideStrokes) {
  // A zigzag of 0.05 px steps stroked 16 px wide: the result is the reference union, no holes.
  for (LineJoin j : {LineJoin::Miter, LineJoin::Bevel, LineJoin::Round}) {
    RefStroke ref;
    ref.style = style_of(16, LineCap::Butt, j);
    for (int i = 0; i < 40; ++i) ref.pts.push_back({20 + 0.05 * i, 20 + (i % 2 ? 0.05 : 0.0)});
    Path p;
    p.move_to(ref.pts[0]);
    for (std::size_t i = 1; i < ref.pts.size(); ++i) p.line_to(ref.pts[i]);
    expect_matches_reference(p, ref.style, ref, 40, 40);
  }
}

TEST(StrokeHardCases, CollinearPointsChangeNothing) {
  const auto a = stroke_grid(polyline({{1, 5}, {5, 5}, {9, 5}, {13.5, 5}}), style_of(3, LineCap::Square, LineJoin::Miter), 16, 10);
  expect_polygon_coverage(a, {{-0.5, 3.5}, {15, 3.5}, {15, 6.5}, {-0.5, 6.5}});
}

TEST(StrokeHardCases, HugeWidthCoversEverything) {
  for (LineCap cap : {LineCap::Butt, LineCap::Round, LineCap::Square}) {
    const Path p = stroke_to_path(polyline({{0, 10}, {20, 10}, {25, 30}}), style_of(1e6, cap, LineJoin::Round), 0.01);
    EXPECT_LT(p.points().size(), 200000u);
    const auto g = test::rasterize(p, FillRule::NonZero, AntiAlias::Analytic, 20, 20, 0.01);
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x) ASSERT_NEAR(g.at(x, y), 1.0, 1e-4);
  }
}

TEST(StrokeHardCases, TinyWidthsNeverVanish) {
  // Geometry: a 0.001-wide stroke is a valid sliver of the right area.
  const auto g = stroke_grid(polyline({{2, 5}, {12, 5}}), style_of(0.001, LineCap::Butt, LineJoin::Miter), 14, 10);
  EXPECT_NEAR(g.total(), 0.01, 1e-5);
  // Rendering: below one device pixel the stroke becomes a coverage-scaled hairline.
  Image img(16, 10);
  img.clear(Color::transparent());
  stroke_path(img, polyline({{2, 5.5}, {12, 5.5}}), Affine{}, style_of(0.1, LineCap::Butt, LineJoin::Miter), Color{0, 0, 0, 1});
  for (int x = 2; x < 12; ++x) EXPECT_NEAR(img.pixel(x, 5)[3], 26, 1) << x;  // 0.1 * 255
  EXPECT_EQ(img.pixel(1, 5)[3], 0);
  EXPECT_EQ(img.pixel(5, 4)[3], 0);
}

// ---- dashes ----

std::vector<StrokePolyline> dashes_of(const Path& p, std::vector<double> pattern, double offset) {
  std::vector<StrokePolyline> in, out;
  flatten_for_stroke(p, 0.01, in);
  dash_polylines(in, pattern, offset, out);
  return out;
}

double piece_length(const StrokePolyline& pl) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < pl.points.size(); ++i) s += length(pl.points[i + 1] - pl.points[i]);
  return s;
}

TEST(StrokeDashes, ContinueAcrossSegmentBoundaries) {
  const Path p = polyline({{0, 0}, {6, 0}, {6, 10}});
  auto d = dashes_of(p, {4, 2}, 0);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].points, (std::vector<Point>{{0, 0}, {4, 0}}));
  EXPECT_EQ(d[1].points, (std::vector<Point>{{6, 0}, {6, 4}}));
  EXPECT_EQ(d[2].points, (std::vector<Point>{{6, 6}, {6, 10}}));
  d = dashes_of(p, {4, 2}, 1);  // the second dash now turns the corner
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].points, (std::vector<Point>{{0, 0}, {3, 0}}));
  EXPECT_EQ(d[1].points, (std::vector<Point>{{5, 0}, {6, 0}, {6, 3}}));
  EXPECT_EQ(d[1].corner[1], 1);
  EXPECT_EQ(d[2].points, (std::vector<Point>{{6, 5}, {6, 9}}));
  // A negative offset is the same as offset + pattern length.
  const auto neg = dashes_of(p, {4, 2}, -5);
  ASSERT_EQ(neg.size(), d.size());
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(neg[i].points, d[i].points);
}

TEST(StrokeDashes, ContinueAlongCurves) {
  Path c;
  c.add_circle({20, 20}, 10);
  const auto d = dashes_of(c, {5, 5}, 0);
  double on = 0;
  for (const auto& pl : d) on += piece_length(pl);
  EXPECT_NEAR(on, kPi * 10, 5.01);  // half the circumference, up to one partial dash
  // The circle starts "on": the last dash (from 60 to 2*pi*10) is joined to the first, which is kept first.
  EXPECT_NEAR(piece_length(d[0]), 5 + (2 * kPi * 10 - 60), 0.03);  // the 0.01 polygon is a bit shorter
  for (std::size_t i = 1; i < d.size(); ++i) EXPECT_NEAR(piece_length(d[i]), 5, 0.01);
}

TEST(StrokeDashes, ClosedSubpathJoinsLastDashToFirst) {
  Path r;
  r.add_rect({0, 0, 10, 10});  // perimeter 40
  const auto d = dashes_of(r, {6, 4}, 2);
  ASSERT_EQ(d.size(), 4u);
  bool through_start = false;
  for (const auto& pl : d) {
    EXPECT_NEAR(piece_length(pl), 6, 1e-9);
    EXPECT_FALSE(pl.closed);
    for (std::size_t i = 1; i + 1 < pl.points.size(); ++i) through_start |= pl.points[i] == Point{0, 0};
  }
  EXPECT_TRUE(through_start);
}

TEST(StrokeDashes, OddArraysRepeatAndAllZeroIsSolid) {
  const Path p = polyline({{1, 5}, {30, 5}, {30, 20}});
  StrokeStyle a = style_of(2, LineCap::Butt, LineJoin::Miter), b = a, solid = a, zeros = a;
  a.dashes = {3};
  b.dashes = {3, 3};
  EXPECT_EQ(stroke_to_path(p, a, 0.01).points().size(), stroke_to_path(p, b, 0.01).points().size());
  const auto ga = stroke_grid(p, a, 34, 24), gb = stroke_grid(p, b, 34, 24);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 34; ++x) ASSERT_EQ(ga.at(x, y), gb.at(x, y));
  a.dashes = {1, 2, 3};
  b.dashes = {1, 2, 3, 1, 2, 3};
  EXPECT_EQ(stroke_to_path(p, a, 0.01).points().size(), stroke_to_path(p, b, 0.01).points().size());
  zeros.dashes = {0, 0, 0};
  const auto gs = stroke_grid(p, solid, 34, 24), gz = stroke_grid(p, zeros, 34, 24);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 34; ++x) ASSERT_EQ(gs.at(x, y), gz.at(x, y));
  zeros.dashes = {1e-9, 1e-9};  // 10^10 dashes: bounded work, drawn solid
  EXPECT_EQ(stroke_to_path(p, zeros, 0.01).points().size(), stroke_to_path(p, solid, 0.01).points().size());
  zeros.dashes = {4, -1};  // invalid: solid, as SVG says
  EXPECT_EQ(stroke_to_path(p, zeros, 0.01).points().size(), stroke_to_path(p, solid, 0.01).points().size());
}

TEST(StrokeDashes, ZeroLengthDashesAreDotsWithRoundCaps) {
  StrokeStyle s = style_of(2, LineCap::Round, LineJoin::Miter);
  s.dashes = {0, 4};
  const auto g = stroke_grid(polyline({{2, 5}, {22, 5}}), s, 26, 10);
  // Dots at x = 2, 6, ..., 22: six unit discs.
  // Chord error <= tolerance/2 = 0.005 loses at most perimeter * 0.005 per dot.
  EXPECT_LE(g.total(), 6 * kPi);
  EXPECT_GE(g.total(), 6 * kPi - 6 * 2 * kPi * 0.005);
  expect_supersampled(g, [](Point q) {
    for (int k = 0; k <= 5; ++k)
      if (length(q - Point{2.0 + 4 * k, 5}) <= 1) return true;
    return false;
  }, 32, 0.03);
  s.cap = LineCap::Butt;
  EXPECT_TRUE(stroke_to_path(polyline({{2, 5}, {22, 5}}), s, 0.01).empty());
}

// ---- transforms, random shapes, hairlines ----

TEST(StrokeTransform, NonUniformScaleStrokesInUserSpace) {
  Image img(40, 24);
  img.clear(Color::transparent());
  // Vertical line at user x = 5, width 1 -> device x in [18, 22] under scale(4, 1).
  stroke_path(img, polyline({{5, 2}, {5, 18}}), Affine::scale(4, 1), style_of(1, LineCap::Butt, LineJoin::Miter), Color{0, 0, 0, 1});
  for (int x = 18; x < 22; ++x) EXPECT_EQ(img.pixel(x, 10)[3], 255) << x;
  EXPECT_EQ(img.pixel(17, 10)[3], 0);
  EXPECT_EQ(img.pixel(22, 10)[3], 0);
  // Horizontal line at user y = 21: device thickness stays 1 (rows 20 and 21 half each).
  Image h(40, 24);
  h.clear(Color::transparent());
  stroke_path(h, polyline({{1, 21}, {8, 21}}), Affine::scale(4, 1), style_of(1, LineCap::Butt, LineJoin::Miter), Color{0, 0, 0, 1});
  EXPECT_NEAR(h.pixel(10, 20)[3], 128, 1);
  EXPECT_NEAR(h.pixel(10, 21)[3], 128, 1);
  EXPECT_EQ(h.pixel(10, 22)[3], 0);
  EXPECT_EQ(h.pixel(3, 20)[3], 0);  // starts at device x = 4
  EXPECT_NEAR(h.pixel(4, 20)[3], 128, 1);
}

TEST(StrokeRandom, MatchesUnionOfPiecesReference) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(4, 44), wdist(0.5, 9);
  for (int iter = 0; iter < 60; ++iter) {
    RefStroke ref;
    const int n = 2 + iter % 5;
    for (int i = 0; i < n; ++i) ref.pts.push_back({coord(rng), coord(rng)});
    if (iter % 7 == 3) ref.pts.push_back(ref.pts[ref.pts.size() - 2]);  // an exact reversal
    ref.style = style_of(wdist(rng), static_cast<LineCap>(iter % 3), static_cast<LineJoin>((iter / 3) % 3),
                         1 + 6 * std::uniform_real_distribution<double>(0, 1)(rng));
    Path p;
    p.move_to(ref.pts[0]);
    for (std::size_t i = 1; i < ref.pts.size(); ++i) p.line_to(ref.pts[i]);
    SCOPED_TRACE(iter);
    expect_matches_reference(p, ref.style, ref, 48, 48);
  }
}

TEST(StrokeRandom, AntialiasedCoverageNeverExceedsOneAndConservesArea) {
  // For a stroke whose pieces do not self-overlap (a gentle arc), the analytic coverage sums to the stroke area.
  Path p;
  p.move_to(5, 30).quad_to({25, 10}, {45, 30});
  const double width = 4;
  const auto g = stroke_grid(p, style_of(width, LineCap::Butt, LineJoin::Miter), 50, 40);
  // Arc length by dense sampling.
  double len = 0;
  Point prev{5, 30};
  for (int i = 1; i <= 10000; ++i) {
    const double t = i / 10000.0, u = 1 - t;
    const Point q = Point{5, 30} * (u * u) + Point{25, 10} * (2 * u * t) + Point{45, 30} * (t * t);
    len += length(q - prev);
    prev = q;
  }
  EXPECT_NEAR(g.total(), len * width, len * width * 0.002);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 50; ++x) ASSERT_LE(g.at(x, y), 1.0f + 1e-6f);
}

TEST(Hairlines, BresenhamPolylineDrawsJointsOnce) {
  Image img(32, 32);
  img.clear(Color::transparent());
  Path p = polyline({{1.5, 1.5}, {20.5, 6.5}, {25.5, 28.5}, {3.5, 20.5}});
  p.close();
  draw_hairlines(img, p, Affine{}, Color{0, 0, 0, 0.5f}, HairlineMode::Bresenham);
  int lit = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const int a = img.pixel(x, y)[3];
      if (a) {
        ++lit;
        ASSERT_EQ(a, 128) << "pixel " << x << "," << y << " drawn twice";
      }
    }
  // Each segment contributes max(|dx|, |dy|) pixels (half-open), closed polygon: 19 + 22 + 22 + 19.
  EXPECT_EQ(lit, 19 + 22 + 22 + 19);
}

TEST(Hairlines, SelfCrossingPolylineCoversTheCrossingOnce) {
  // Hairlines hand the compositor each pixel's summed coverage (clamped to 1), so a pixel two segments of one
  // contour pass through is drawn once: with alpha 0.5 it is 128 like every other pixel, not 192.
  Image img(16, 16);
  img.clear(Color::transparent());
  draw_hairlines(img, polyline({{2.5, 2.5}, {12.5, 12.5}, {12.5, 2.5}, {2.5, 12.5}}), Affine{}, Color{0, 0, 0, 0.5f},
                 HairlineMode::Bresenham);
  EXPECT_EQ(img.pixel(7, 7)[3], 128);
  int lit = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const int a = img.pixel(x, y)[3];
      if (a) {
        ++lit;
        ASSERT_EQ(a, 128) << x << "," << y;
      }
    }
  // Three half-open segments of 10 pixels and the last pixel, minus the crossing counted twice.
  EXPECT_EQ(lit, 10 + 10 + 10 + 1 - 1);
}

TEST(Hairlines, AntialiasedModesCoverAHorizontalLineFully) {
  for (HairlineMode mode : {HairlineMode::Wu, HairlineMode::Analytic}) {
    Image img(16, 12);
    img.clear(Color::transparent());
    draw_hairlines(img, polyline({{2, 5.5}, {12, 5.5}}), Affine{}, Color{0, 0, 0, 1}, mode);
    for (int x = 2; x < 12; ++x) EXPECT_EQ(img.pixel(x, 5)[3], 255) << to_string(mode) << " " << x;
    EXPECT_EQ(img.pixel(6, 4)[3], 0);
    EXPECT_EQ(img.pixel(6, 6)[3], 0);
    // Half a pixel down, the line splits evenly between two rows.
    Image half(16, 12);
    half.clear(Color::transparent());
    draw_hairlines(half, polyline({{2, 6}, {12, 6}}), Affine{}, Color{0, 0, 0, 1}, mode);
    EXPECT_NEAR(half.pixel(6, 5)[3], 128, 1) << to_string(mode);
    EXPECT_NEAR(half.pixel(6, 6)[3], 128, 1) << to_string(mode);
  }
}

TEST(Hairlines, FarGeometryIsClippedNotWalked) {
  for (HairlineMode mode : {HairlineMode::Bresenham, HairlineMode::Dda, HairlineMode::Wu, HairlineMode::Analytic}) {
    Image img(20, 20);
    img.clear(Color::transparent());
    draw_hairlines(img, polyline({{-1e9, 10.5}, {1e9, 10.5}}), Affine{}, Color{0, 0, 0, 1}, mode);
    for (int x = 0; x < 20; ++x) EXPECT_EQ(img.pixel(x, 10)[3], 255) << to_string(mode) << " " << x;
  }
  Image img(20, 20);
  img.clear(Color::transparent());
  stroke_path(img, polyline({{-1e7, 10}, {1e7, 10}}), Affine{}, style_of(2, LineCap::Round, LineJoin::Round), Color{0, 0, 0, 1});
  for (int x = 0; x < 20; ++x) EXPECT_EQ(img.pixel(x, 9)[3], 255);
}

TEST(Hairlines, WuVersusAnalyticOnADiagonal) {
  // The documented difference: Wu gives every column a total weight of 1, the analytic 1-px stroke gives the
  // area of a 1-px band, 1/cos(45 deg) = sqrt(2) per column on a diagonal.
  double wu = 0, analytic = 0;
  for (HairlineMode mode : {HairlineMode::Wu, HairlineMode::Analytic}) {
    Image img(40, 40);
    img.clear(Color::transparent());
    draw_hairlines(img, polyline({{5, 5}, {35, 35}}), Affine{}, Color{0, 0, 0, 1}, mode);
    double sum = 0;
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x) sum += img.pixel(x, y)[3] / 255.0;
    (mode == HairlineMode::Wu ? wu : analytic) = sum;
  }
  EXPECT_NEAR(wu, 30, 0.3);
  EXPECT_NEAR(analytic, 30 * std::sqrt(2.0), 0.3);
}

TEST(StrokeRender, Image16AndReusedRendererGiveTheSameCoverage) {
  const Path p = polyline({{3, 4}, {20, 9}, {6, 18}});
  StrokeStyle s = style_of(3, LineCap::Round, LineJoin::Round);
  Image a(24, 24), b(24, 24);
  Image16 c(24, 24);
  a.clear(Color::transparent());
  b.clear(Color::transparent());
  c.clear(Color::transparent());
  stroke_path(a, p, Affine{}, s, Color{0, 0, 0, 1});
  Renderer shared;
  StrokeRenderOptions o;
  o.renderer = &shared;
  stroke_path(b, p, Affine{}, s, Color{0, 0, 0, 1}, o);
  stroke_path(b, p, Affine{}, s, Color{0, 0, 0, 0}, o);  // invisible: changes nothing
  stroke_path(c, p, Affine{}, s, Color{0, 0, 0, 1}, o);
  int lit = 0;
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 24; ++x) {
      ASSERT_EQ(a.pixel(x, y)[3], b.pixel(x, y)[3]);
      ASSERT_NEAR(c.pixel(x, y)[3] / 257.0, a.pixel(x, y)[3], 1.0);
      lit += a.pixel(x, y)[3] > 0;
    }
  }
  EXPECT_GT(lit, 60);
  // A thin stroke on a 16-bit image: coverage-scaled analytic hairline.
  Image16 t(16, 10);
  t.clear(Color::transparent());
  stroke_path(t, polyline({{2, 5.5}, {12, 5.5}}), Affine{}, style_of(0.25, LineCap::Butt, LineJoin::Miter), Color{0, 0, 0, 1});
  EXPECT_NEAR(t.pixel(6, 5)[3], 0.25 * 65535, 65535 * 0.01);
  EXPECT_EQ(t.pixel(6, 4)[3], 0);
}

TEST(Hairlines, CoverageSinkMatchesDrawnPixels) {
  // hairline_coverage hands the same pixels as draw_hairlines to any CoverageSink, in row order.
  Path p = polyline({{1.5, 1.5}, {20.5, 6.5}, {25.5, 28.5}, {3.5, 20.5}});
  p.close();
  for (HairlineMode mode : {HairlineMode::Bresenham, HairlineMode::Dda, HairlineMode::Wu, HairlineMode::Analytic}) {
    Image img(32, 32);
    img.clear(Color::transparent());
    draw_hairlines(img, p, Affine{}, Color{0, 0, 0, 1}, mode);
    test::CoverageGrid g(32, 32);
    hairline_coverage(p, Affine{}, mode, 32, 32, g);
    EXPECT_TRUE(g.violations().empty()) << to_string(mode);
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x) {
        // draw_hairlines composites exactly the coverage the sink gets (each pixel once, min(1, sum c_i)), so the
        // alpha is that coverage to within the 8-bit rounding.
        ASSERT_NEAR(img.pixel(x, y)[3] / 255.0, std::min(1.0f, g.at(x, y)), 0.6 / 255)
            << to_string(mode) << " " << x << "," << y;
        if (img.pixel(x, y)[3] > 0) {
          ASSERT_GT(g.at(x, y), 0.0f) << to_string(mode) << " " << x << "," << y;
        }
        if (g.at(x, y) > 1.0f / 255) {
          ASSERT_GT(img.pixel(x, y)[3], 0) << to_string(mode) << " " << x << "," << y;
        }
      }
    }
  }
}

TEST(StrokeRender, RendererStrokeHandsTheDrawnCoverageToAnySink) {
  // stroke_path is Renderer::stroke into a solid compositor: the sink sees exactly the coverage that gets drawn,
  // for wide strokes (outline filled non-zero) and thin ones (hairlines scaled by the width), at both depths.
  const Path p = polyline({{3, 4}, {20, 9}, {6, 18}});
  Renderer renderer;
  for (double width : {3.0, 0.4}) {
    for (AntiAlias aa : {AntiAlias::Analytic, AntiAlias::None}) {
      const StrokeStyle s = style_of(width, LineCap::Round, LineJoin::Round);
      StrokeRenderOptions o;
      o.aa = aa;
      CoverageGrid g(24, 24);
      renderer.stroke(p, Affine{}, s, o, 24, 24, g);
      EXPECT_TRUE(g.violations().empty());
      Image a(24, 24);
      Image16 b(24, 24);
      a.clear(Color::transparent());
      b.clear(Color::transparent());
      o.renderer = &renderer;
      stroke_path(a, p, Affine{}, s, Color{0, 0, 0, 1}, o);
      stroke_path(b, p, Affine{}, s, Color{0, 0, 0, 1}, o);
      double total = 0;
      for (int y = 0; y < 24; ++y) {
        for (int x = 0; x < 24; ++x) {
          ASSERT_NEAR(a.pixel(x, y)[3] / 255.0, g.at(x, y), 0.6 / 255) << width << " " << x << "," << y;
          ASSERT_NEAR(b.pixel(x, y)[3] / 65535.0, g.at(x, y), 1.0 / 65535) << width << " " << x << "," << y;
          total += g.at(x, y);
        }
      }
      // About the stroke's area: length (17.7 + 16.6) times the width (the hairline's share for thin strokes).
      EXPECT_NEAR(total, 34.3 * width, 34.3 * width * 0.25) << width << " " << to_string(aa);
    }
  }
}

TEST(StrokeRender, ThinStrokeModeIsOneDecision) {
  EXPECT_EQ(thin_stroke_mode(AntiAlias::None, HairlineMode::Analytic), HairlineMode::Bresenham);
  EXPECT_EQ(thin_stroke_mode(AntiAlias::None, HairlineMode::Wu), HairlineMode::Bresenham);
  EXPECT_EQ(thin_stroke_mode(AntiAlias::None, HairlineMode::Dda), HairlineMode::Dda);
  EXPECT_EQ(thin_stroke_mode(AntiAlias::Analytic, HairlineMode::Bresenham), HairlineMode::Analytic);
  EXPECT_EQ(thin_stroke_mode(AntiAlias::Exact, HairlineMode::Dda), HairlineMode::Analytic);
  EXPECT_EQ(thin_stroke_mode(AntiAlias::Ssaa4, HairlineMode::Wu), HairlineMode::Wu);
  // The same decision at every depth: an aliased thin stroke on a 16-bit image lights Bresenham's pixels, each at
  // the width's share of full coverage, like the 8-bit image.
  const Path p = polyline({{2.5, 2.5}, {17.5, 9.5}});
  const StrokeStyle s = style_of(0.5, LineCap::Butt, LineJoin::Miter);
  StrokeRenderOptions o;
  o.aa = AntiAlias::None;
  Image a(20, 12);
  Image16 b(20, 12);
  a.clear(Color::transparent());
  b.clear(Color::transparent());
  stroke_path(a, p, Affine{}, s, Color{0, 0, 0, 1}, o);
  stroke_path(b, p, Affine{}, s, Color{0, 0, 0, 1}, o);
  int lit = 0;
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool on = a.pixel(x, y)[3] != 0;
      ASSERT_EQ(on, b.pixel(x, y)[3] != 0) << x << "," << y;
      if (on) {
        ++lit;
        ASSERT_EQ(a.pixel(x, y)[3], 128);
        ASSERT_EQ(b.pixel(x, y)[3], 32768);
      }
    }
  }
  EXPECT_EQ(lit, 16);  // Bresenham from pixel (2, 2) to (17, 9), both ends drawn: 16 columns
}

TEST(StrokeNames, ParseAndPrint) {
  LineCap c{};
  LineJoin j{};
  HairlineMode m{};
  EXPECT_TRUE(parse_line_cap("square", c) && c == LineCap::Square);
  EXPECT_FALSE(parse_line_cap("flat", c));
  EXPECT_TRUE(parse_line_join("bevel", j) && j == LineJoin::Bevel);
  EXPECT_FALSE(parse_line_join("arcs", j));
  EXPECT_TRUE(parse_hairline_mode("wu", m) && m == HairlineMode::Wu);
  EXPECT_EQ(to_string(HairlineMode::Analytic), "analytic");
  EXPECT_FALSE(parse_hairline_mode("fast", m));
}

}  // namespace
}  // namespace vraster
