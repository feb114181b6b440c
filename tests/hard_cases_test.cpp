// Named hard cases for the scan converter. Each test states the property it checks; expectations come from closed
// forms, the shoelace formula of simple polygons, or the exact reference (tests/support/exact_reference.hpp).
// Always checked as well: no NaN, coverage in [0, 1], the sink contract (engine_coverage reports violations).
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <ctime>
#include <numbers>
#include <random>

#include "support/capture.hpp"
#include "support/exact_reference.hpp"
#include "support/reference.hpp"

namespace vraster::test {
namespace {

using exact::engine_coverage;
using exact::grids_near;

constexpr AntiAlias kAllAa[] = {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact};
constexpr FillRule kAllRules[] = {FillRule::EvenOdd, FillRule::NonZero,  FillRule::NonExterior,
                                  FillRule::Positive, FillRule::Negative, FillRule::AbsGeq2};

Polygon ccw_box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}}; }

std::string name_of(FillRule r, AntiAlias a) { return std::string(to_string(r)) + "/" + std::string(to_string(a)); }

// No NaN, every pixel in [0, 1].
::testing::AssertionResult sane(const std::vector<double>& g) {
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (!(g[i] >= 0.0 && g[i] <= 1.0)) return ::testing::AssertionFailure() << "pixel " << i << " = " << g[i];
  }
  return ::testing::AssertionSuccess();
}

// Winding at p with the aliased sampler's conventions (top-left rule): an edge counts when min y <= p.y < max y and
// it crosses the sample line at x <= p.x. Exact for the dyadic inputs used with it.
int winding_top_left(const std::vector<Polygon>& contours, Point p) {
  int w = 0;
  for (const Polygon& poly : contours) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Point a = poly[i], b = poly[(i + 1) % poly.size()];
      if (a.y == b.y || p.y < std::min(a.y, b.y) || p.y >= std::max(a.y, b.y)) continue;
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x <= p.x) w += b.y > a.y ? 1 : -1;
    }
  }
  return w;
}

// ------------------------------------------------------------------------------------------------------------
// Huge and far-away coordinates.

TEST(HardCase, HugeDyadicCoordinatesAreExact) {
  // Property: with coordinates of 2^50 (~1.1e15) that are exactly representable, clipping is exact, so a diagonal
  // half-plane y > x gives exactly 1 below the diagonal, 1/2 on it, 0 above, in every mode and rule.
  const double big = std::ldexp(1.0, 50);
  const std::vector<Polygon> tri{{{-big, -big}, {big, big}, {-big, big}}};
  std::vector<double> want(256), want_aliased(256);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      want[y * 16 + x] = y > x ? 1.0 : y == x ? 0.5 : 0.0;
      want_aliased[y * 16 + x] = y > x ? 1.0 : 0.0;  // centre on the diagonal: it is the right edge, pixel outside
    }
  }
  for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::NonExterior, FillRule::Negative}) {
    EXPECT_TRUE(grids_near(engine_coverage(tri, rule, AntiAlias::Exact, 16, 16), want, 16, 1e-12)) << to_string(rule);
    EXPECT_TRUE(grids_near(engine_coverage(tri, rule, AntiAlias::Analytic, 16, 16), want, 16, 1e-12))
        << to_string(rule);
    const auto aliased = engine_coverage(tri, rule, AntiAlias::None, 16, 16);
    EXPECT_TRUE(grids_near(aliased, want_aliased, 16, 0)) << to_string(rule);
  }
}

TEST(HardCase, CoordinatesOf1e15) {
  // Property: a triangle with vertices at +-1e15 that contains the canvas covers every pixel fully; a half-plane
  // bounded by x = 8.5 gives 1 / 0.5 / 0 per column; shapes entirely off-canvas (left, right, above, below, at
  // 1e15) leave it empty, including a band left of the canvas spanning all its rows (its clipped edges cancel).
  const std::vector<Polygon> around{{{-1e15, -1e15}, {-1e15, 1e15}, {1e15, 0}}};
  const std::vector<Polygon> half{{{-1e15, -1e15}, {-1e15, 1e15}, {8.5, 1e15}, {8.5, -1e15}}};
  std::vector<double> full(256, 1.0), none(256, 0.0), cols(256), cols_aliased(256);
  for (int i = 0; i < 256; ++i) {
    cols[i] = i % 16 < 8 ? 1.0 : i % 16 == 8 ? 0.5 : 0.0;
    cols_aliased[i] = i % 16 < 8 ? 1.0 : 0.0;  // centre 8.5 on the right edge: outside
  }
  const std::vector<std::vector<Polygon>> off{{ccw_box(1e15, 1e15, 1e15 + 10, 1e15 + 10)},
                                              {ccw_box(-1e15, 2, -1e15 + 10, 9)},
                                              {ccw_box(-1e15, -1e15, -5, 1e15)},
                                              {ccw_box(3, -1e15, 9, -1)},
                                              {ccw_box(3, 17, 9, 1e15)},
                                              {ccw_box(17, -1e15, 1e15, 1e15)}};
  for (FillRule rule : kAllRules) {
    for (AntiAlias aa : kAllAa) {
      const bool filled = rule != FillRule::Negative && rule != FillRule::AbsGeq2;  // winding +1
      const auto a = engine_coverage(around, rule, aa, 16, 16);
      EXPECT_TRUE(sane(a));
      EXPECT_TRUE(grids_near(a, filled ? full : none, 16, 1e-9)) << name_of(rule, aa);
      const bool half_filled = rule != FillRule::Negative && rule != FillRule::AbsGeq2;
      EXPECT_TRUE(grids_near(engine_coverage(half, rule, aa, 16, 16),
                             half_filled ? (aa == AntiAlias::None ? cols_aliased : cols) : none, 16, 1e-9))
          << name_of(rule, aa);
      for (std::size_t k = 0; k < off.size(); ++k) {
        EXPECT_TRUE(grids_near(engine_coverage(off[k], rule, aa, 16, 16), none, 16, 0))
            << "off-canvas shape " << k << " " << name_of(rule, aa);
      }
    }
  }
}

TEST(HardCase, ShapeBeyondRightEdgeKeepsCoverageToTheEdge) {
  // Property: a box [2.5, 20] x [2.5, 5.5] on a 10-wide canvas covers every pixel right of x = 3 in its rows fully
  // (its right side is dropped by clipping; coverage must still run to the canvas edge).
  const std::vector<Polygon> box{ccw_box(2.5, 2.5, 20, 5.5)};
  const auto want = reference_coverage(box, 10, 8);
  for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd, FillRule::NonExterior, FillRule::Positive}) {
    for (AntiAlias aa : {AntiAlias::Analytic, AntiAlias::Exact}) {
      EXPECT_TRUE(grids_near(engine_coverage(box, rule, aa, 10, 8), want, 10, 1e-9)) << name_of(rule, aa);
    }
  }
}

// ------------------------------------------------------------------------------------------------------------
// Tiny shapes, special vertex positions, extreme slopes.

TEST(HardCase, MicroPixelShapesConserveArea) {
  // Property: a right triangle with legs of 1e-6 px has area 5e-13; a 1e-6 square centred on a pixel corner puts
  // 2.5e-13 in each of four pixels. No NaN, exact and analytic agree with those areas to 1e-18; aliased sees nothing.
  const std::vector<Polygon> tri{{{3.3, 4.7}, {3.3, 4.7 + 1e-6}, {3.3 + 1e-6, 4.7}}};
  const double h = 0.5e-6;
  const std::vector<Polygon> corner{ccw_box(5 - h, 5 - h, 5 + h, 5 + h)};
  for (FillRule rule : kAllRules) {
    if (rule == FillRule::AbsGeq2 || rule == FillRule::Negative) continue;
    for (AntiAlias aa : {AntiAlias::Analytic, AntiAlias::Exact}) {
      const auto t = engine_coverage(tri, rule, aa, 8, 8);
      EXPECT_TRUE(sane(t));
      EXPECT_NEAR(t[4 * 8 + 3], 5e-13, 1e-18) << name_of(rule, aa);
      EXPECT_NEAR(exact::sum(t), 5e-13, 1e-18) << name_of(rule, aa);
      const auto c = engine_coverage(corner, rule, aa, 8, 8);
      for (int p : {4 * 8 + 4, 4 * 8 + 5, 5 * 8 + 4, 5 * 8 + 5}) EXPECT_NEAR(c[p], 2.5e-13, 1e-18) << name_of(rule, aa);
      EXPECT_NEAR(exact::sum(c), 1e-12, 1e-18);
    }
    EXPECT_EQ(exact::sum(engine_coverage(tri, rule, AntiAlias::None, 8, 8)), 0.0);
  }
}

TEST(HardCase, VerticesOnScanlinesCornersAndCentres) {
  // Property: vertices exactly on pixel corners, on scanlines (integer y) and on pixel centres do not disturb the
  // area: exact and analytic match the reference per pixel (1e-9), and aliased matches the top-left rule.
  const std::vector<std::vector<Polygon>> shapes{
      {{{4, 1}, {7, 4}, {4, 7}, {1, 4}}},                                   // diamond, corners on pixel corners
      {{{4.5, 0.5}, {7.5, 3.5}, {4.5, 6.5}, {1.5, 3.5}}},                   // diamond, corners on pixel centres
      {{{1, 1}, {2.5, 6}, {4, 2}, {5.5, 6}, {7, 1}, {4, 0}}},               // zigzag with vertices on scanlines
      {{{0.5, 0.5}, {0.5, 7.5}, {7.5, 7.5}, {7.5, 0.5}}, {{2, 2}, {6, 2}, {6, 6}, {2, 6}}},  // ring on centres
      {{{1, 1}, {7, 7}, {7, 1}, {1, 7}}},                                   // bow-tie crossing on a corner (4,4)
      {{{1.5, 1.5}, {6.5, 6.5}, {6.5, 1.5}, {1.5, 6.5}}},                   // bow-tie crossing at a centre
  };
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative}) {
      const auto want = exact::scan_coverage(shapes[k], rule, 8, 8);
      EXPECT_TRUE(grids_near(engine_coverage(shapes[k], rule, AntiAlias::Exact, 8, 8), want, 8, 1e-9))
          << "shape " << k << " " << to_string(rule);
      if (k < 4) {  // no crossings: analytic is exact too
        EXPECT_TRUE(grids_near(engine_coverage(shapes[k], rule, AntiAlias::Analytic, 8, 8), want, 8, 1e-9))
            << "shape " << k << " " << to_string(rule);
      }
      const auto aliased = engine_coverage(shapes[k], rule, AntiAlias::None, 8, 8);
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
          const int w = winding_top_left(shapes[k], {x + 0.5, y + 0.5});
          EXPECT_EQ(aliased[y * 8 + x], rule_inside(rule, w) ? 1.0 : 0.0)
              << "shape " << k << " " << to_string(rule) << " pixel " << x << "," << y;
        }
      }
    }
  }
}

TEST(HardCase, NearHorizontalAndNearVerticalEdges) {
  // Property: slopes of 1e-12 (edges tilted by 1e-11 over 10 px) give the same areas as the reference to 1e-9, for
  // simple shapes (exact == analytic) and for a thin bow-tie whose near-horizontal edges cross.
  const double e = 1e-12;
  const std::vector<std::vector<Polygon>> shapes{
      {{{1, 2}, {1.3, 9}, {11.7, 9 + 10 * e}, {11.4, 2 - 10 * e}}},     // near-horizontal top and bottom
      {{{2.25, 1}, {2.25 + 10 * e, 11}, {9.5, 11}, {9.5 - 10 * e, 1}}},  // near-vertical sides
      {{{0.5, 5 - 5 * e}, {12.5, 5 + 7 * e}, {12.5, 6}, {0.5, 6 - 3 * e}}},
      {{{0.5, 4.5}, {12.5, 4.5 + 12 * e}, {12.5, 4.5}, {0.5, 4.5 + 12 * e}}},  // bow-tie of two flat slivers
  };
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative}) {
      const auto want = exact::scan_coverage(shapes[k], rule, 13, 12);
      EXPECT_TRUE(grids_near(engine_coverage(shapes[k], rule, AntiAlias::Exact, 13, 12), want, 13, 1e-9))
          << "shape " << k << " " << to_string(rule);
      if (k < 3) {
        EXPECT_TRUE(grids_near(engine_coverage(shapes[k], rule, AntiAlias::Analytic, 13, 12), want, 13, 1e-9))
            << "shape " << k << " " << to_string(rule);
      }
    }
    const auto ne = engine_coverage(shapes[k], FillRule::NonExterior, AntiAlias::Exact, 13, 12);
    EXPECT_TRUE(grids_near(ne, exact::trapezoid_coverage(shapes[k], FillRule::NonExterior, 13, 12), 13, 1e-9))
        << "shape " << k;
  }
}

// The pentagram whose "horizontal" bar is tilted by exactly one ulp (as sin(198deg) vs sin(342deg) produce):
// the bar's crossings with the two edges from the top point can only round to its two end heights.
std::vector<Polygon> one_ulp_pentagram() {
  return {{{4, 0.5}, {6.25, 7.25}, {0.5, 3.25}, {7.5, std::nextafter(3.25, 0.0)}, {2, 7.25}}};
}

// Regression (boundary sweep): fixed in 309ac62 (crossings before vertices at equal height). An edge tilted by one
// ulp that crosses other edges used to lose the left arm of the star in AntiAlias::Exact for every winding rule and
// in NonExterior (NonZero gave 13.086 instead of 15.165): the crossing events rounded onto the bar's end height,
// where the batch of edge ends and starts ran first and continued the bar's successor in the bar's stale slot of
// the active order. Guards: exact coverage of that star equals the independent reference for every rule.
TEST(HardCase, EdgeTiltedByOneUlpCrossingOtherEdges) {
  const auto star = one_ulp_pentagram();
  for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::AbsGeq2, FillRule::Negative}) {
    EXPECT_TRUE(grids_near(engine_coverage(star, rule, AntiAlias::Exact, 9, 9), exact::scan_coverage(star, rule, 9, 9),
                           9, 1e-9))
        << to_string(rule);
  }
  EXPECT_TRUE(grids_near(engine_coverage(star, FillRule::NonExterior, AntiAlias::Exact, 9, 9),
                         exact::trapezoid_coverage(star, FillRule::NonExterior, 9, 9), 9, 1e-9));
}

TEST(HardCase, EdgeTiltedByOneUlpReferenceIsConsistent) {
  // Property (of the reference, so that the disabled test above is trustworthy): the one-ulp tilt changes areas by
  // ~1e-15 only, both reference methods agree, and non-exterior equals non-zero (a star has no winding-0 face).
  const auto star = one_ulp_pentagram();
  std::vector<Polygon> flat = star;
  flat[0][3].y = 3.25;
  for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::AbsGeq2}) {
    const auto a = exact::scan_coverage(star, rule, 9, 9);
    EXPECT_TRUE(grids_near(a, exact::trapezoid_coverage(star, rule, 9, 9), 9, 1e-12));
    EXPECT_TRUE(grids_near(a, exact::scan_coverage(flat, rule, 9, 9), 9, 1e-12));
  }
  EXPECT_NEAR(exact::total_area(star, FillRule::NonExterior), exact::total_area(star, FillRule::NonZero), 1e-12);
  // The same star with the bar exactly horizontal is handled correctly by the engine.
  for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::AbsGeq2, FillRule::NonExterior}) {
    EXPECT_TRUE(grids_near(engine_coverage(flat, rule, AntiAlias::Exact, 9, 9),
                           exact::trapezoid_coverage(flat, rule, 9, 9), 9, 1e-9))
        << to_string(rule);
  }
}

TEST(HardCase, NearlyParallelEdgesCrossingAtTinyAngles) {
  // Property: two slivers crossing at angles of 1e-7 .. 1e-3 rad (crossing point inside a pixel, far from its
  // vertices) have exact areas: exact mode matches the reference to 1e-9 for every rule.
  for (double d : {1e-7, 1e-5, 1e-3}) {
    const std::vector<Polygon> x{{{0.5, 5.3 - d}, {15.5, 5.3 + d}, {15.5, 5.3 - 2 * d}, {0.5, 5.3 + 2 * d}}};
    const std::vector<Polygon> two{{{0.5, 5.3}, {15.5, 5.3 + 15 * d}, {15.5, 7}, {0.5, 7}},
                                   {{0.5, 5.3 + 15 * d}, {15.5, 5.3}, {15.5, 3}, {0.5, 3}}};
    for (const auto* shape : {&x, &two}) {
      for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::AbsGeq2}) {
        EXPECT_TRUE(grids_near(engine_coverage(*shape, rule, AntiAlias::Exact, 16, 10),
                               exact::scan_coverage(*shape, rule, 16, 10), 16, 1e-9))
            << "d " << d << " " << to_string(rule);
      }
    }
  }
}

// A star polygon {n/k} around c: vertex j at angle 2 pi j k / n. With k close to n/2 every edge passes within
// R sin(pi/(2n)) of the centre.
Polygon star_polygon(Point c, double radius, int n, int k) {
  Polygon p;
  for (int j = 0; j < n; ++j) {
    const double a = 2 * std::numbers::pi * static_cast<double>(static_cast<long long>(j) * k % n) / n;
    p.push_back({c.x + radius * std::sin(a), c.y - radius * std::cos(a)});
  }
  return p;
}

constexpr int kStarPoints = exact::kOptimizedBuild ? 1001 : 201;

TEST(HardCase, ThousandsOfEdgesThroughOnePixel) {
  // Property: a {1001/500} star sends all 1001 edges through the centre pixel (about 250000 crossings there; {201/100}
  // in slow builds).
  // Non-zero fills the star's outline, area n R r sin(pi/n) with r = R cos(pi k/n) / cos(pi (k-1)/n); the centre pixel
  // has winding ~500 and is fully covered under every rule that holds there; even-odd <= non-zero <= non-exterior.
  const int n = kStarPoints, k = (kStarPoints - 1) / 2;
  const double R = 7.5;
  const Point c{8.25, 8.25};
  const std::vector<Polygon> star{star_polygon(c, R, n, k)};
  const double r = R * std::cos(std::numbers::pi * k / n) / std::cos(std::numbers::pi * (k - 1) / n);
  const double outline = n * R * r * std::sin(std::numbers::pi / n);
  const auto nz = engine_coverage(star, FillRule::NonZero, AntiAlias::Exact, 17, 17);
  const auto eo = engine_coverage(star, FillRule::EvenOdd, AntiAlias::Exact, 17, 17);
  const auto ne = engine_coverage(star, FillRule::NonExterior, AntiAlias::Exact, 17, 17);
  EXPECT_TRUE(sane(nz) && sane(eo) && sane(ne));
  EXPECT_NEAR(exact::sum(nz), outline, 1e-6);
  EXPECT_NEAR(exact::sum(ne), outline, 1e-6);
  EXPECT_NEAR(nz[8 * 17 + 8], 1.0, 1e-9);
  EXPECT_NEAR(engine_coverage(star, FillRule::AbsGeq2, AntiAlias::Exact, 17, 17)[8 * 17 + 8], 1.0, 1e-9);
  for (std::size_t i = 0; i < nz.size(); ++i) {
    EXPECT_LE(eo[i], nz[i] + 1e-6) << i;
    EXPECT_LE(nz[i], ne[i] + 1e-6) << i;
  }
  // A smaller star of the same kind, {151/75} (about 11000 crossings in the centre pixel; {101/50} in slow builds),
  // against the reference.
  const int m = exact::kOptimizedBuild ? 151 : 101;
  const std::vector<Polygon> small{star_polygon(c, R, m, (m - 1) / 2)};
  for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero}) {
    double err = 0;
    EXPECT_TRUE(grids_near(engine_coverage(small, rule, AntiAlias::Exact, 17, 17),
                           exact::scan_coverage(small, rule, 17, 17), 17, 1e-9, &err))
        << to_string(rule);
    std::printf("[HardCase] {%d/%d} star %s: max error %.3g\n", m, (m - 1) / 2, std::string(to_string(rule)).c_str(), err);
  }
}

// ------------------------------------------------------------------------------------------------------------
// Degenerate paths.

TEST(HardCase, CollinearOverlappingOppositeEdgesAreZeroArea) {
  // Property: slits (a contour running along a line and straight back) cover nothing in any rule or mode; a slit
  // attached to a square changes nothing; a square and the same square reversed cancel for winding rules, but the
  // inside stays enclosed by the path, so non-exterior fills it.
  const std::vector<Polygon> slit{{{1.5, 1.25}, {9.75, 6.5}, {1.5, 1.25}}};
  const std::vector<Polygon> hslit{{{1, 3.5}, {9, 3.5}, {4, 3.5}}};
  const std::vector<double> none(100, 0.0);
  const Polygon sq = ccw_box(2.25, 2.25, 7.75, 7.75);
  const std::vector<Polygon> with_slit{{{2.25, 2.25}, {2.25, 7.75}, {7.75, 7.75}, {7.75, 5}, {9.5, 5.5}, {7.75, 5},
                                        {7.75, 2.25}}};
  const std::vector<Polygon> cancel{sq, Polygon(sq.rbegin(), sq.rend())};
  const auto sq_cov = reference_coverage({sq}, 10, 10);
  for (FillRule rule : kAllRules) {
    for (AntiAlias aa : kAllAa) {
      EXPECT_TRUE(grids_near(engine_coverage(slit, rule, aa, 10, 10), none, 10, 0)) << name_of(rule, aa);
      EXPECT_TRUE(grids_near(engine_coverage(hslit, rule, aa, 10, 10), none, 10, 0)) << name_of(rule, aa);
      const bool filled = rule != FillRule::Negative && rule != FillRule::AbsGeq2;
      if (aa != AntiAlias::None) {
        EXPECT_TRUE(grids_near(engine_coverage(with_slit, rule, aa, 10, 10), filled ? sq_cov : none, 10, 1e-9))
            << name_of(rule, aa);
        EXPECT_TRUE(grids_near(engine_coverage(cancel, rule, aa, 10, 10),
                               rule == FillRule::NonExterior ? sq_cov : none, 10, 1e-9))
            << name_of(rule, aa);
      }
    }
  }
}

TEST(HardCase, ZeroLengthSegmentsAndRepeatedPoints) {
  // Property: repeating every vertex (zero-length segments) and adding one-point and two-equal-point contours
  // changes no pixel, bit for bit.
  const Polygon tri{{1.3, 1.1}, {8.6, 3.7}, {3.2, 8.9}};
  Polygon repeated;
  for (Point p : tri) repeated.insert(repeated.end(), {p, p, p});
  const std::vector<Polygon> plain{tri};
  const std::vector<Polygon> messy{repeated, {{5, 5}}, {{2, 2}, {2, 2}}, {{7, 1}, {7, 1}, {7, 1}}};
  for (FillRule rule : kAllRules) {
    for (AntiAlias aa : kAllAa) {
      EXPECT_EQ(engine_coverage(messy, rule, aa, 10, 10), engine_coverage(plain, rule, aa, 10, 10)) << name_of(rule, aa);
    }
  }
}

TEST(HardCase, PathDoublingBackOnItselfIsEmpty) {
  // Property: a zigzag that returns along exactly the same segments encloses nothing (every rule, every mode).
  const std::vector<Polygon> back{{{1.25, 1.5}, {9.5, 4.75}, {2.5, 8.25}, {9.75, 9.5}, {2.5, 8.25}, {9.5, 4.75}}};
  const std::vector<double> none(121, 0.0);
  for (FillRule rule : kAllRules) {
    for (AntiAlias aa : kAllAa) {
      EXPECT_TRUE(grids_near(engine_coverage(back, rule, aa, 11, 11), none, 11, 1e-12)) << name_of(rule, aa);
    }
  }
}

// ------------------------------------------------------------------------------------------------------------
// Curves.

std::vector<Polygon> flattened(const Path& path, double tol) {
  Polylines lines;
  FlattenOptions opt;
  opt.tolerance = tol;
  flatten(path, Affine{}, opt, lines);
  std::vector<Polygon> out;
  for (std::size_t k = 0; k < lines.contour_count(); ++k) {
    const auto c = lines.contour(k);
    out.emplace_back(c.begin(), c.end());
  }
  return out;
}

TEST(HardCase, CubicsWithCuspsLoopsAndCoincidentControlPoints) {
  // Property: degenerate cubics flatten to finite points; the engine's exact coverage equals the reference on the
  // flattened polyline (1e-9) for every winding rule, and non-exterior on the trapezoid reference; a cubic whose
  // control points all coincide covers nothing, one with P1 = P0 and P2 = P3 is its chord.
  Path cusp, loop, coincident, chord, line;
  cusp.move_to(2, 14).cubic_to({14, 2}, {2, 2}, {14, 14}).close();
  loop.move_to(3, 13).cubic_to({22, -4}, {-6, -4}, {13, 13}).close();
  coincident.move_to(5, 5).cubic_to({5, 5}, {5, 5}, {5, 5}).close();
  chord.move_to(2, 3).cubic_to({2, 3}, {12, 11}, {12, 11}).line_to(2, 11).close();
  line.move_to(2, 3).line_to(12, 11).line_to(2, 11).close();
  for (const Path* p : {&cusp, &loop, &chord}) {
    const auto poly = flattened(*p, 0.01);
    for (const auto& c : poly) {
      for (Point q : c) ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y));
    }
    for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative,
                          FillRule::AbsGeq2}) {
      EXPECT_TRUE(grids_near(engine_coverage(*p, rule, AntiAlias::Exact, 16, 16, 0.01),
                             exact::scan_coverage(poly, rule, 16, 16), 16, 1e-9))
          << to_string(rule);
    }
    EXPECT_TRUE(grids_near(engine_coverage(*p, FillRule::NonExterior, AntiAlias::Exact, 16, 16, 0.01),
                           exact::trapezoid_coverage(poly, FillRule::NonExterior, 16, 16), 16, 1e-9));
  }
  for (FillRule rule : kAllRules) {
    for (AntiAlias aa : kAllAa) {
      EXPECT_EQ(exact::sum(engine_coverage(coincident, rule, aa, 16, 16)), 0.0) << name_of(rule, aa);
      EXPECT_TRUE(grids_near(engine_coverage(chord, rule, aa, 16, 16), engine_coverage(line, rule, aa, 16, 16), 16,
                             1e-9))
          << name_of(rule, aa);
    }
  }
}

TEST(HardCase, ZeroRadiusArcsAreStraightLines) {
  // Property: SVG arcs with a zero radius are straight lines, so a square drawn with them equals the square.
  Path arcs, square;
  arcs.move_to(2.5, 2.5).arc_to(0, 0, 0, false, true, {2.5, 9.5}).arc_to(0, 5, 30, true, false, {9.5, 9.5});
  arcs.arc_to(5, 0, 0, false, false, {9.5, 2.5}).close();
  square.add_polygon(ccw_box(2.5, 2.5, 9.5, 9.5));
  for (FillRule rule : kAllRules) {
    for (AntiAlias aa : kAllAa) {
      EXPECT_TRUE(grids_near(engine_coverage(arcs, rule, aa, 12, 12), engine_coverage(square, rule, aa, 12, 12), 12,
                             1e-9))
          << name_of(rule, aa);
    }
  }
  EXPECT_NEAR(exact::sum(engine_coverage(arcs, FillRule::NonZero, AntiAlias::Exact, 12, 12)), 49, 1e-9);
}

// ------------------------------------------------------------------------------------------------------------
// Size and scaling.

constexpr int kManySegments = exact::kOptimizedBuild ? 1000000 : 200000;  // slow builds: same property, smaller

// A simple polygon of n vertices: a circle of radius 14 with a radial wobble of +-0.3 px (star-shaped, so simple).
// With `zigzag`, alternate vertices are also moved in and out by 0.2 px, so nearly every vertex is a local extremum
// in y and hundreds of edges cross each scanline.
Polygon wobbly_circle(int n, bool zigzag = false) {
  Polygon p;
  p.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    const double r = 14 + 0.3 * std::sin(37.0 * a) + (zigzag ? 0.2 * ((i & 1) ? 1 : -1) : 0.0);
    p.push_back({16.2 + r * std::cos(a), 15.9 + r * std::sin(a)});
  }
  return p;
}

long max_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

TEST(HardCase, MillionSegmentPathIsCompleteWithBoundedMemory) {
  // Property: a simple polygon of 10^6 segments (2*10^5 in Debug/sanitizer builds) rasterizes completely: total
  // coverage equals its shoelace area (1e-6 relative) in analytic and exact mode; non-exterior equals non-zero;
  // the peak memory grows by less than 1 GiB. (How the time grows with n is measured by bench/scaling_bench.cpp,
  // figures in docs/performance.md: timings do not belong in unit tests.)
  const long rss_before = max_rss_kib();
  for (const int n : {kManySegments / 10, kManySegments}) {
    const std::vector<Polygon> poly{wobbly_circle(n)};
    const double area = std::abs(shoelace_area(poly[0]));
    const auto analytic = engine_coverage(poly, FillRule::NonZero, AntiAlias::Analytic, 33, 32);
    const auto exact_cov = engine_coverage(poly, FillRule::NonZero, AntiAlias::Exact, 33, 32);
    const auto ne = engine_coverage(poly, FillRule::NonExterior, AntiAlias::Exact, 33, 32);
    EXPECT_NEAR(exact::sum(analytic), area, 1e-6 * area) << n;
    EXPECT_NEAR(exact::sum(exact_cov), area, 1e-6 * area) << n;
    EXPECT_TRUE(grids_near(exact_cov, analytic, 33, 1e-7)) << n;
    EXPECT_TRUE(grids_near(ne, exact_cov, 33, 1e-7)) << n;
  }
  const long rss_growth_mib = (max_rss_kib() - rss_before) / 1024;
  std::printf("[HardCase] %d segments: peak RSS growth %ld MiB\n", kManySegments, rss_growth_mib);
  EXPECT_LT(rss_growth_mib, 1024);
}

// Regression (boundary sweep, performance): fixed in 82f4180 (turning vertices handled locally instead of rebuilding
// the active order). The sweep used to rebuild the active order in O(active edges) at every vertex that did not
// simply continue an edge, so a zigzag contour (nearly every vertex a y-extremum, hundreds of edges per scanline)
// cost O(n^2): non-exterior took 0.45 s / 5.2 s / 57 s for n = 10^4 / 3*10^4 / 10^5. Guards here: the zigzag comes
// out complete (coverage = area) in exact non-zero and non-exterior; its time against n is measured by
// bench/scaling_bench.cpp (docs/performance.md).
TEST(HardCase, ZigzagPathIsComplete) {
  for (const int n : {10000, 40000}) {
    const std::vector<Polygon> poly{wobbly_circle(n, /*zigzag=*/true)};
    const double area = std::abs(shoelace_area(poly[0]));
    const auto nz = engine_coverage(poly, FillRule::NonZero, AntiAlias::Exact, 33, 32);
    const auto ne = engine_coverage(poly, FillRule::NonExterior, AntiAlias::Exact, 33, 32);
    EXPECT_NEAR(exact::sum(nz), area, 1e-6 * area) << n;
    EXPECT_NEAR(exact::sum(ne), area, 1e-6 * area) << n;
    EXPECT_TRUE(grids_near(ne, nz, 33, 1e-7)) << n;
  }
}

// A band spiral: out along r = r0 + s theta / (2 pi), back along the same curve shifted by half the spacing. A simple
// polygon; the gap between its turns is a spiral channel of width ~s/2 that opens to the outside.
Polygon spiral_band(Point c, int turns, int per_turn, double r0, double spacing) {
  Polygon out, back;
  const int n = turns * per_turn;
  for (int i = 0; i <= n; ++i) {
    const double t = 2 * std::numbers::pi * i / per_turn;
    const double r = r0 + spacing * i / per_turn;
    out.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
    back.push_back({c.x + (r + spacing / 2) * std::cos(t), c.y + (r + spacing / 2) * std::sin(t)});
  }
  out.insert(out.end(), back.rbegin(), back.rend());
  return out;
}

constexpr int kSpiralSteps = exact::kOptimizedBuild ? 48 : 24;  // polyline points per turn
constexpr int kBandTurns = exact::kOptimizedBuild ? 500 : 150;  // slow builds: a shorter band (its cost is ~turns^2)

TEST(HardCase, SpiralWith500Turns) {
  // Property: a 500-turn band spiral (48k segments, turns 0.024 px apart; 150 turns in slow builds) is a simple polygon: exact == analytic
  // == shoelace area; its channel reaches the outside, so non-exterior == non-zero; closing an open 500-turn spiral
  // by its chord instead gives even-odd <= non-zero <= non-exterior per pixel and a non-exterior area of about
  // pi R^2 (everything inside the outer turn is enclosed).
  const Point c{16.1, 15.8};
  const Polygon band = spiral_band(c, kBandTurns, kSpiralSteps, 2, 0.024);
  const double area = std::abs(shoelace_area(band));
  const auto analytic = engine_coverage({band}, FillRule::NonZero, AntiAlias::Analytic, 32, 32);
  const auto exact_cov = engine_coverage({band}, FillRule::NonZero, AntiAlias::Exact, 32, 32);
  const auto ne = engine_coverage({band}, FillRule::NonExterior, AntiAlias::Exact, 32, 32);
  EXPECT_NEAR(exact::sum(exact_cov), area, 1e-9 * band.size());
  EXPECT_TRUE(grids_near(analytic, exact_cov, 32, 1e-7));
  EXPECT_TRUE(grids_near(ne, exact_cov, 32, 1e-7));

  // (0.37 turn extra: the chord back to the start must not run through the spiral's vertices at angle 0.)
  Polygon open;
  const int extra = kSpiralSteps * 37 / 100;
  for (int i = 0; i <= 500 * kSpiralSteps + extra; ++i) {
    const double t = 2 * std::numbers::pi * i / kSpiralSteps;
    const double r = 2 + 0.024 * i / kSpiralSteps;
    open.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
  }
  const double R = 2 + 0.024 * (500 + static_cast<double>(extra) / kSpiralSteps);
  const auto eo = engine_coverage({open}, FillRule::EvenOdd, AntiAlias::Exact, 32, 32);
  const auto nz = engine_coverage({open}, FillRule::NonZero, AntiAlias::Exact, 32, 32);
  const auto ne2 = engine_coverage({open}, FillRule::NonExterior, AntiAlias::Exact, 32, 32);
  EXPECT_TRUE(sane(eo) && sane(nz) && sane(ne2));
  for (std::size_t i = 0; i < eo.size(); ++i) {
    EXPECT_LE(eo[i], nz[i] + 1e-6) << i;
    EXPECT_LE(nz[i], ne2[i] + 1e-6) << i;
  }
  // The outermost piece of the channel (one turn long, 0.024 wide) is open to the outside; all the rest is enclosed.
  // (The disc of radius R as a polygon of kSpiralSteps sides: area n/2 sin(2 pi/n) R^2.)
  const double disc = 0.5 * kSpiralSteps * std::sin(2 * std::numbers::pi / kSpiralSteps) * R * R;
  EXPECT_NEAR(exact::sum(ne2), disc, 2 * 2 * std::numbers::pi * R * 0.024);
}

// ------------------------------------------------------------------------------------------------------------
// Invariances.

std::vector<Polygon> translated(const std::vector<Polygon>& cs, double dx, double dy) {
  std::vector<Polygon> out = cs;
  for (auto& c : out)
    for (auto& p : c) p = p + Point{dx, dy};
  return out;
}

std::vector<double> shifted_window(const std::vector<double>& g, int w, int dx, int dy, int ow, int oh) {
  std::vector<double> out(static_cast<std::size_t>(ow) * oh);
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) out[y * ow + x] = g[(y + dy) * w + (x + dx)];
  return out;
}

TEST(HardCase, InvariantUnderIntegerTranslationReversalAndStartVertex) {
  // Property, random dyadic polygons (vertices on k/64 + 1/128, inside the canvas, one or two contours):
  //  - translating by whole pixels (3, 5) shifts the coverage by exactly those pixels (1e-9);
  //  - reversing every contour changes nothing for even-odd, non-zero, non-exterior, |w| >= 2, and swaps positive
  //    and negative;
  //  - starting each contour at another vertex changes nothing;
  // in every AA mode (exact values compared to 1e-9 plus float rounding; aliased exactly).
  double worst = 0;
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(seed * 1013);
    std::vector<Polygon> cs{random_dyadic_polygon(rng, 3 + static_cast<int>(rng() % 30), 0.5, 15.5)};
    if (seed % 2) cs.push_back(random_dyadic_polygon(rng, 3 + static_cast<int>(rng() % 8), 0.5, 15.5));
    const auto rev = reversed(cs);
    std::vector<Polygon> rotated = cs;
    for (auto& c : rotated) std::rotate(c.begin(), c.begin() + static_cast<long>(rng() % c.size()), c.end());
    const auto moved = translated(cs, 3, 5);
    for (FillRule rule : kAllRules) {
      for (AntiAlias aa : kAllAa) {
        const double tol = aa == AntiAlias::None ? 0 : 1e-9;
        const auto base = engine_coverage(cs, rule, aa, 16, 16);
        EXPECT_TRUE(sane(base));
        double e = 0;
        const auto big = engine_coverage(moved, rule, aa, 19, 21);
        EXPECT_TRUE(grids_near(shifted_window(big, 19, 3, 5, 16, 16), base, 16, tol, &e))
            << "translation seed " << seed << " " << name_of(rule, aa);
        worst = std::max(worst, e);
        const FillRule mirror = rule == FillRule::Positive   ? FillRule::Negative
                                : rule == FillRule::Negative ? FillRule::Positive
                                                             : rule;
        EXPECT_TRUE(grids_near(engine_coverage(rev, mirror, aa, 16, 16), base, 16, tol, &e))
            << "reversal seed " << seed << " " << name_of(rule, aa);
        worst = std::max(worst, e);
        EXPECT_TRUE(grids_near(engine_coverage(rotated, rule, aa, 16, 16), base, 16, tol, &e))
            << "start vertex seed " << seed << " " << name_of(rule, aa);
        worst = std::max(worst, e);
      }
    }
  }
  std::printf("[HardCase] invariances: max difference %.3g\n", worst);
}

TEST(HardCase, ModesAgreeWhereTheoryRequires) {
  // Property: for pixel-aligned rectangles (integer corners, overlapping, nested, opposite orientations) every pixel
  // has one winding number, so aliased == analytic == exact for every rule; for simple polygons analytic == exact.
  const std::vector<Polygon> rects{ccw_box(1, 1, 9, 7), ccw_box(4, 3, 12, 10), Polygon{{6, 2}, {11, 2}, {11, 12}, {6, 12}},
                                   ccw_box(2, 8, 5, 11)};
  for (FillRule rule : kAllRules) {
    const auto ex = engine_coverage(rects, rule, AntiAlias::Exact, 13, 13);
    EXPECT_TRUE(grids_near(engine_coverage(rects, rule, AntiAlias::Analytic, 13, 13), ex, 13, 1e-12))
        << to_string(rule);
    EXPECT_TRUE(grids_near(engine_coverage(rects, rule, AntiAlias::None, 13, 13), ex, 13, 1e-12)) << to_string(rule);
    if (rule != FillRule::NonExterior) {
      EXPECT_TRUE(grids_near(ex, exact::scan_coverage(rects, rule, 13, 13), 13, 1e-12)) << to_string(rule);
    }
  }
}

}  // namespace
}  // namespace vraster::test
