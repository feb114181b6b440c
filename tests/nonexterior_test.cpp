// FillRule::NonExterior: a point is filled when it cannot reach infinity without crossing the path.
//
// Each hand case gives its input contours and the expected filled region as simple, non-overlapping polygons
// (holes reversed). Expectations are computed from that region only, independently of the engine:
//   Exact and Analytic: clip-and-shoelace area per pixel (reference.hpp's reference_coverage);
//   None:               point in region at the pixel centre (skipped where a centre lies on the region's boundary).
// The trapezoid flood-fill reference (exact_reference.hpp) must agree with the same expectation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "raster/fixed_cells.hpp"
#include "support/capture.hpp"
#include "support/exact_reference.hpp"
#include "support/reference.hpp"

namespace vraster::test {
namespace {

using exact::engine_coverage;
using exact::grids_near;

Polygon ccw_box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}}; }
Polygon cw_box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

std::vector<double> aliased_expectation(const std::vector<Polygon>& region, int w, int h, std::vector<bool>& known) {
  std::vector<double> out(static_cast<std::size_t>(w) * h, 0.0);
  known.assign(out.size(), true);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto wn = winding_number(region, {x + 0.5, y + 0.5});
      if (!wn) {
        known[y * w + x] = false;
      } else {
        out[y * w + x] = *wn != 0 ? 1.0 : 0.0;
      }
    }
  }
  return out;
}

// Checks `rule` on `input` in all three AA modes against the region, and the reference against the region.
void check_region(const std::vector<Polygon>& input, FillRule rule, const std::vector<Polygon>& region, int w, int h,
                  const char* what, bool check_reference = true) {
  SCOPED_TRACE(std::string(what) + " / " + std::string(to_string(rule)));
  const auto area = reference_coverage(region, w, h);
  for (AntiAlias aa : {AntiAlias::Exact, AntiAlias::Analytic}) {
    EXPECT_TRUE(grids_near(engine_coverage(input, rule, aa, w, h), area, w, 1e-9)) << to_string(aa);
  }
  std::vector<bool> known;
  const auto centres = aliased_expectation(region, w, h, known);
  const auto got = engine_coverage(input, rule, AntiAlias::None, w, h);
  int mismatches = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (known[i] && got[i] != centres[i]) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0) << "aliased:\n" << exact::grid_text(got, w) << "want:\n" << exact::grid_text(centres, w);
  if (check_reference) {
    const auto ref = rule == FillRule::NonExterior || rule == FillRule::NonZero
                         ? exact::trapezoid_coverage(input, rule, w, h)
                         : exact::scan_coverage(input, rule, w, h);
    EXPECT_TRUE(grids_near(ref, area, w, 1e-9)) << "reference disagrees with the hand-made region";
  }
}

TEST(NonExteriorHand, NestedSquaresSameAndOppositeOrientation) {
  // Outer [2.25,11.25] x [1.5,10.5]; inner [4.75,8.25] x [4.25,7.75] (fractional: partial pixels in AA modes).
  const Polygon outer = ccw_box(2.25, 1.5, 11.25, 10.5);
  const std::vector<Polygon> same{outer, ccw_box(4.75, 4.25, 8.25, 7.75)};
  const std::vector<Polygon> opposite{outer, cw_box(4.75, 4.25, 8.25, 7.75)};
  check_region(same, FillRule::NonExterior, {outer}, 13, 12, "same");
  check_region(same, FillRule::NonZero, {outer}, 13, 12, "same");
  check_region(opposite, FillRule::NonExterior, {outer}, 13, 12, "opposite");
  check_region(opposite, FillRule::NonZero, opposite, 13, 12, "opposite: non-zero leaves the hole");
  // Reversing everything changes nothing.
  check_region(reversed(opposite), FillRule::NonExterior, {outer}, 13, 12, "opposite reversed");
}

// Outer square [2,12]^2 with a square hole [5,9]^2; the contour reaches the hole along y = 7 from the right side.
// gap = 0: a keyhole (the slit y = 7 is traversed both ways); gap > 0: a C shape with an opening of that height.
Polygon slit_ring(double gap) {
  const double a = 7 - gap / 2, b = 7 + gap / 2;
  return {{12, b}, {12, 12}, {2, 12}, {2, 2}, {12, 2}, {12, a}, {9, a}, {9, 5}, {5, 5}, {5, 9}, {9, 9}, {9, b}};
}

TEST(NonExteriorHand, RingWithSlitIsFilledCShapeIsNot) {
  const Polygon outer = ccw_box(2, 2, 12, 12);
  // The keyhole: the hole can only get out through the slit, which is path: enclosed.
  const std::vector<Polygon> keyhole{slit_ring(0)};
  check_region(keyhole, FillRule::NonExterior, {outer}, 14, 14, "keyhole");
  check_region(keyhole, FillRule::NonZero, {outer, cw_box(5, 5, 9, 9)}, 14, 14, "keyhole");
  // The C shape: the opening [9,12] x [6.5,7.5] joins the hole to the outside.
  const std::vector<Polygon> c_shape{slit_ring(1)};
  for (FillRule rule : {FillRule::NonExterior, FillRule::NonZero}) {
    check_region(c_shape, rule, c_shape, 14, 14, "C shape");
  }
  EXPECT_NEAR(exact::sum(engine_coverage(c_shape, FillRule::NonExterior, AntiAlias::Exact, 14, 14)), 100 - 16 - 3,
              1e-9);
}

// The cells of a (n+2) x (n+2) block: a solid border ring and inside it a square spiral wall one cell thick,
// separated by a one-cell channel. Every wall cell is its own counterclockwise unit square (shared sides cancel), so
// the wall has winding 1 and the channel winding 0, but the channel is enclosed by the border.
std::vector<std::vector<bool>> spiral_walls(int n) {
  std::vector<std::vector<bool>> wall(n + 2, std::vector<bool>(n + 2, false));
  for (int i = 0; i < n + 2; ++i) wall[0][i] = wall[n + 1][i] = wall[i][0] = wall[i][n + 1] = true;
  // Turtle inside the border: start at (1,1) heading right, segment lengths n-1, n-1, n-1, n-3, n-3, n-5, n-5, ...
  int x = 1, y = 1, dir = 0;
  const int dx[] = {1, 0, -1, 0}, dy[] = {0, 1, 0, -1};
  wall[y][x] = true;
  int len = n - 1;
  for (int seg = 0; len > 0; ++seg) {
    for (int k = 0; k < len; ++k) {
      x += dx[dir], y += dy[dir];
      wall[y][x] = true;
    }
    dir = (dir + 1) % 4;
    if (seg >= 2 && seg % 2 == 0) len -= 2;
  }
  return wall;
}

TEST(NonExteriorHand, SquareSpiralChannelOfWindingZeroIsEnclosed) {
  const int n = 11;
  const auto wall = spiral_walls(n);
  // Cell size 1.5 with the block at (0.25, 0.25): cell sides at 0.25 + 1.5 k never pass through a pixel centre.
  const double s = 1.5, o = 0.25;
  std::vector<Polygon> cells, channel;
  int wall_cells = 0;
  for (int j = 0; j < n + 2; ++j) {
    for (int i = 0; i < n + 2; ++i) {
      const Polygon box = ccw_box(o + s * i, o + s * j, o + s * (i + 1), o + s * (j + 1));
      (wall[j][i] ? cells : channel).push_back(box);
      wall_cells += wall[j][i];
    }
  }
  ASSERT_GT(channel.size(), 30u);  // a long channel
  const int size = 20;             // (n + 2) * 1.5 + 0.25 = 19.75
  const Polygon block = ccw_box(o, o, o + s * (n + 2), o + s * (n + 2));
  check_region(cells, FillRule::NonExterior, {block}, size, size, "spiral", /*check_reference=*/true);
  check_region(cells, FillRule::NonZero, cells, size, size, "spiral", /*check_reference=*/false);
  EXPECT_NEAR(exact::sum(engine_coverage(cells, FillRule::NonZero, AntiAlias::Exact, size, size)),
              wall_cells * s * s, 1e-9);
  // Removing the border cell next to the first channel cell of column 1 opens the channel to the outside.
  int open_i = -1, open_j = -1;
  for (int j = 1; j <= n && open_i < 0; ++j) {
    if (!wall[j][1]) open_i = 0, open_j = j;  // channel cell at column 1: open the border cell left of it
  }
  ASSERT_GE(open_i, 0);
  std::vector<Polygon> open_cells;
  for (int j = 0; j < n + 2; ++j) {
    for (int i = 0; i < n + 2; ++i) {
      if (wall[j][i] && !(i == open_i && j == open_j)) {
        open_cells.push_back(ccw_box(o + s * i, o + s * j, o + s * (i + 1), o + s * (j + 1)));
      }
    }
  }
  // With the opening every channel cell reaches the outside (the channel is one connected corridor): NonExterior is
  // then the walls alone.
  check_region(open_cells, FillRule::NonExterior, open_cells, size, size, "spiral opened", false);
}

TEST(NonExteriorHand, TouchingSquares) {
  // Side by side (shared side traversed both ways): the union.
  const std::vector<Polygon> side{ccw_box(2, 2, 5, 5), ccw_box(5, 2, 8, 5)};
  check_region(side, FillRule::NonExterior, side, 10, 7, "side by side");
  // Four squares around a hole, touching along sides: the hole is enclosed.
  const std::vector<Polygon> ring{ccw_box(2, 2, 4, 8), ccw_box(6, 2, 8, 8), ccw_box(4, 2, 6, 4), ccw_box(4, 6, 6, 8)};
  check_region(ring, FillRule::NonExterior, {ccw_box(2, 2, 8, 8)}, 10, 10, "ring of four");
  check_region(ring, FillRule::NonZero, ring, 10, 10, "ring of four");
  // Four squares touching only at corners around a hole: the way out through a corner point crosses the path, so
  // the hole [3,5]^2 is enclosed as well.
  const std::vector<Polygon> corners{ccw_box(3, 1, 5, 3), ccw_box(5, 3, 7, 5), ccw_box(3, 5, 5, 7),
                                     ccw_box(1, 3, 3, 5)};
  std::vector<Polygon> filled = corners;
  filled.push_back(ccw_box(3, 3, 5, 5));
  check_region(corners, FillRule::NonExterior, filled, 8, 8, "corner ring");
}

TEST(NonExteriorHand, OverlappingSubpathsOfOppositeOrientation) {
  // [2,8]^2 winding +1 and [5,11]^2 winding -1: the overlap [5,8]^2 has winding 0 but is enclosed.
  const std::vector<Polygon> two{ccw_box(2, 2, 8, 8), cw_box(5, 5, 11, 11)};
  const std::vector<Polygon> union_region{{{2, 2}, {2, 8}, {5, 8}, {5, 11}, {11, 11}, {11, 5}, {8, 5}, {8, 2}}};
  check_region(two, FillRule::NonExterior, union_region, 12, 12, "overlap");
  EXPECT_NEAR(exact::sum(engine_coverage(two, FillRule::NonExterior, AntiAlias::Exact, 12, 12)), 63, 1e-9);
  EXPECT_NEAR(exact::sum(engine_coverage(two, FillRule::NonZero, AntiAlias::Exact, 12, 12)), 54, 1e-9);
}

TEST(NonExteriorHand, OpenSubpathIsClosedImplicitly) {
  Path open_path, closed_path;
  open_path.move_to(1.5, 1.25).line_to(1.5, 8.75).line_to(9.25, 8.75).line_to(9.25, 1.25);
  closed_path.move_to(1.5, 1.25).line_to(1.5, 8.75).line_to(9.25, 8.75).line_to(9.25, 1.25).close();
  // Plus an open reversed inner square: a hole for non-zero, filled for non-exterior.
  open_path.move_to(3, 3).line_to(7, 3).line_to(7, 7).line_to(3, 7);
  closed_path.move_to(3, 3).line_to(7, 3).line_to(7, 7).line_to(3, 7).close();
  const auto want = reference_coverage({ccw_box(1.5, 1.25, 9.25, 8.75)}, 11, 10);
  for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact}) {
    const auto got = engine_coverage(open_path, FillRule::NonExterior, aa, 11, 10);
    EXPECT_EQ(got, engine_coverage(closed_path, FillRule::NonExterior, aa, 11, 10)) << to_string(aa);
    if (aa != AntiAlias::None) {
      EXPECT_TRUE(grids_near(got, want, 11, 1e-9)) << to_string(aa);
    }
  }
}

TEST(NonExteriorHand, PathFarLargerThanCanvasCoversIt) {
  // A huge square with a reversed square hole that itself contains the 16x16 canvas: non-zero leaves the canvas
  // empty, non-exterior covers all of it (the enclosing geometry is entirely off-canvas).
  const std::vector<Polygon> frame{ccw_box(-1e6, -1e6, 1e6, 1e6), cw_box(-1e5, -1e5, 1e5, 1e5)};
  const std::vector<double> full(256, 1.0), none(256, 0.0);
  for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact}) {
    EXPECT_TRUE(grids_near(engine_coverage(frame, FillRule::NonExterior, aa, 16, 16), full, 16, 0)) << to_string(aa);
    EXPECT_TRUE(grids_near(engine_coverage(frame, FillRule::NonZero, aa, 16, 16), none, 16, 0)) << to_string(aa);
    EXPECT_TRUE(grids_near(engine_coverage({frame[0]}, FillRule::NonExterior, aa, 16, 16), full, 16, 0))
        << to_string(aa);
  }
}

TEST(NonExteriorHand, RingAroundCanvasWithTopFarAbove) {
  // Ring: outer [-10,26] x [-1e4,26], hole [-5,21] x [-5e3,21]; the canvas lies inside the hole.
  const std::vector<Polygon> ring{ccw_box(-10, -1e4, 26, 26), cw_box(-5, -5e3, 21, 21)};
  const std::vector<double> full(256, 1.0), none(256, 0.0);
  // The same ring with its top bar cut through far above the canvas: a C shape, the hole reaches the outside.
  const std::vector<Polygon> cut{{{-10, -1e4}, {-10, 26}, {26, 26}, {26, -1e4}, {8, -1e4}, {8, -5e3}, {21, -5e3},
                                  {21, 21}, {-5, 21}, {-5, -5e3}, {7, -5e3}, {7, -1e4}}};
  for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact}) {
    EXPECT_TRUE(grids_near(engine_coverage(ring, FillRule::NonExterior, aa, 16, 16), full, 16, 0)) << to_string(aa);
    EXPECT_TRUE(grids_near(engine_coverage(ring, FillRule::NonZero, aa, 16, 16), none, 16, 0)) << to_string(aa);
    EXPECT_TRUE(grids_near(engine_coverage(cut, FillRule::NonExterior, aa, 16, 16), none, 16, 0)) << to_string(aa);
  }
  EXPECT_NEAR(exact::total_area(cut, FillRule::NonExterior), exact::total_area(cut, FillRule::NonZero), 1e-6);
  EXPECT_NEAR(exact::total_area(ring, FillRule::NonExterior), 36.0 * (26 + 1e4), 1e-6);
}

TEST(NonExteriorHand, CircleWithReversedConcentricCircle) {
  const Point c{16.25, 15.75};
  const double R = 12, r = 6, tol = 0.01;
  Path outer, inner;
  outer.add_circle(c, R);
  inner.add_circle(c, r);
  inner.transform(Affine{-1, 0, 0, 1, 2 * c.x, 0});  // mirrored about x = c.x: reversed orientation
  Path both = outer;
  both.add_path(inner);
  // The flattened outer circle, exactly as the engine will see it.
  Polylines lines;
  FlattenOptions opt;
  opt.tolerance = tol;
  flatten(outer, Affine{}, opt, lines);
  const Polygon outer_poly(lines.points.begin(), lines.points.end());
  const auto want = reference_coverage({outer_poly}, 33, 32);
  for (AntiAlias aa : {AntiAlias::Analytic, AntiAlias::Exact}) {
    const auto got = engine_coverage(both, FillRule::NonExterior, aa, 33, 32, tol);
    // (analytic: the boundary's fill in fixed-point cells, its rows having few pieces)
    const double bound = 1e-9 + (aa == AntiAlias::Analytic ? detail::kFixedCellsError : 0.0);
    EXPECT_TRUE(grids_near(got, want, 33, bound)) << to_string(aa);
    // Full disc area within the flattening tolerance (area error <= perimeter * tolerance).
    EXPECT_NEAR(exact::sum(got), std::numbers::pi * R * R, 2 * std::numbers::pi * R * tol);
    const auto nz = engine_coverage(both, FillRule::NonZero, aa, 33, 32, tol);
    EXPECT_NEAR(exact::sum(nz), std::numbers::pi * (R * R - r * r), 2 * std::numbers::pi * (R + r) * tol);
  }
  // Aliased: the disc's pixel centres (a margin of 2 * tol around the circle left out).
  const auto got = engine_coverage(both, FillRule::NonExterior, AntiAlias::None, 33, 32, tol);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 33; ++x) {
      const double d = std::hypot(x + 0.5 - c.x, y + 0.5 - c.y);
      if (std::abs(d - R) < 2 * tol) continue;
      EXPECT_EQ(got[y * 33 + x], d < R ? 1.0 : 0.0) << x << "," << y;
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Random polygons: engine vs trapezoid flood-fill reference, and the ordering of the rules.

TEST(NonExteriorRandom, MatchesFloodFillReference) {
  double worst = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed * 7919);
    const int size = 16 + static_cast<int>(rng() % 9);
    std::vector<Polygon> contours{exact::random_polygon(rng, 3 + static_cast<int>(rng() % 22), -3, size + 3)};
    if (seed % 2 == 0) contours.push_back(exact::random_polygon(rng, 3 + static_cast<int>(rng() % 8), -3, size + 3));
    const auto want = exact::trapezoid_coverage(contours, FillRule::NonExterior, size, size);
    double err = 0;
    EXPECT_TRUE(grids_near(engine_coverage(contours, FillRule::NonExterior, AntiAlias::Exact, size, size), want, size,
                           1e-9, &err))
        << "seed " << seed;
    worst = std::max(worst, err);
    // (analytic: the boundary's fill in fixed-point cells where it has few edges)
    EXPECT_TRUE(grids_near(engine_coverage(contours, FillRule::NonExterior, AntiAlias::Analytic, size, size), want,
                           size, 1e-9 + detail::kFixedCellsError))
        << "seed " << seed;
  }
  std::printf("[NonExteriorRandom] max |engine - flood-fill reference| = %.3g\n", worst);
}

TEST(NonExteriorRandom, EvenOddWithinNonZeroWithinNonExterior) {
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::mt19937 rng(seed * 31337);
    const std::vector<Polygon> poly{exact::random_polygon(rng, 3 + static_cast<int>(rng() % 40), -2, 22)};
    const auto eo = engine_coverage(poly, FillRule::EvenOdd, AntiAlias::Exact, 20, 20);
    const auto nz = engine_coverage(poly, FillRule::NonZero, AntiAlias::Exact, 20, 20);
    const auto ne = engine_coverage(poly, FillRule::NonExterior, AntiAlias::Exact, 20, 20);
    for (std::size_t i = 0; i < eo.size(); ++i) {
      ASSERT_LE(eo[i], nz[i] + 1e-6) << "seed " << seed << " pixel " << i;
      ASSERT_LE(nz[i], ne[i] + 1e-6) << "seed " << seed << " pixel " << i;
    }
  }
}

TEST(NonExteriorRandom, EqualsNonZeroWhenNoBoundedFaceHasWindingZero) {
  std::mt19937 rng(4242);
  std::vector<std::vector<Polygon>> shapes;
  for (int k = 0; k < 10; ++k) shapes.push_back({random_star_polygon(rng, {12.3, 11.6}, 3 + k * 5, 2, 11)});
  // Pentagram and a 7/3 star (every bounded face has winding != 0).
  for (int p : {5, 7}) {
    Polygon star;
    const int step = p == 5 ? 2 : 3;
    for (int k = 0; k < p; ++k) {
      const double a = 2 * std::numbers::pi * k * step / p;
      star.push_back({12.1 + 10 * std::sin(a), 12.2 - 10 * std::cos(a)});
    }
    shapes.push_back({star});
  }
  shapes.push_back({ccw_box(2.5, 2.5, 20.5, 20.5), ccw_box(6.25, 6.25, 14.75, 14.75), ccw_box(8, 8, 12, 12)});
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact}) {
      if (aa == AntiAlias::Analytic && i >= 10 && i < 12) continue;  // stars cross inside pixels: analytic inexact
      EXPECT_TRUE(grids_near(engine_coverage(shapes[i], FillRule::NonExterior, aa, 24, 24),
                             engine_coverage(shapes[i], FillRule::NonZero, aa, 24, 24), 24, 1e-9))
          << "shape " << i << " " << to_string(aa);
    }
  }
}

}  // namespace
}  // namespace vraster::test
