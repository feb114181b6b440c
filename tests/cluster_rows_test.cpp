// Wide rows whose pieces lie far apart (a ring's four walls, discs side by side on the same rows) are swept as
// clusters of nearby pieces with constant spans between them (sweep.cpp, resolve_clusters). Checked against the exact
// trapezoid reference (tests/support/exact_reference.hpp, no cells and no sweep) on shapes that never cross one
// another, where analytic coverage is exact up to round-off, and AVX2 against the portable kernels bit for bit.
// The scenes hold clusters wider than a narrow row (a shallow sliver), pieces just under and just over the merge
// distance apart (pairs of thin bars), holes, and shapes cut by the image's left and right edges.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "raster/cpu.hpp"
#include "raster/fixed_cells.hpp"
#include "support/capture.hpp"
#include "support/exact_reference.hpp"

namespace vraster::test {
namespace {

Polygon regular(Point c, double r, int sides, bool clockwise, double turn) {
  Polygon p;
  for (int i = 0; i < sides; ++i) {
    const double a = turn + 2 * std::numbers::pi * (clockwise ? i : sides - i) / sides;
    p.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return p;
}

Polygon box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// A scene of disjoint shapes in a w x h image: a ring in the middle (two polygons; for NonZero the inner one runs
// the other way), discs left and right of it on the same rows, a pair of thin bars `gap` cells apart below it, and a
// long, nearly horizontal sliver above it. Some scenes are shifted so that shapes leave the image on either side.
std::vector<Polygon> scene(std::mt19937& rng, int w, int h, bool nonzero) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Polygon> s;
  const double shift = rng() % 3 == 0 ? (u(rng) - 0.5) * 120 : 0;
  const Point c{w / 2.0 + shift + u(rng), h / 2.0 + u(rng)};
  const double outer = 40 + 15 * u(rng), wall = 1.5 + 10 * u(rng), turn = u(rng);
  s.push_back(regular(c, outer, 40 + static_cast<int>(rng() % 30), true, turn));
  s.push_back(regular(c, outer - wall, 40 + static_cast<int>(rng() % 30), !nonzero, turn));
  for (const double side : {-1.0, 1.0}) {  // two discs on each side, 30 cells or more apart
    for (int k = 0; k < 2; ++k) {
      const double r = 3 + 6 * u(rng);
      const Point d{c.x + side * (outer + 12 + r + k * 38 + 8 * u(rng)), c.y + (u(rng) - 0.5) * 30};
      s.push_back(regular(d, r, 12 + static_cast<int>(rng() % 12), u(rng) < 0.5, u(rng)));
    }
  }
  // Bars: the gap runs from 18 to 30 cells, around the distance at which pieces join one cluster.
  const double gap = 18 + 12 * u(rng), bx = c.x - 40 + 10 * u(rng), by = c.y + outer + 3;
  s.push_back(box(bx, by, bx + 0.7, by + 6));
  s.push_back(box(bx + 0.7 + gap, by, bx + 1.3 + gap, by + 6));
  // The sliver: about 4 cells across per row over its 10 rows, and 0.3 rows thick.
  const double sx = c.x - 60 * u(rng), sy = c.y - outer - 14;
  s.push_back({{sx, sy}, {sx + 120, sy + 10}, {sx + 120, sy + 10.3}});
  return s;
}

// fixed_cells false: every row in double cells (the fixed-point rows are within detail::kFixedCellsError of them).
std::vector<double> row_sweep(const std::vector<Polygon>& shapes, FillRule rule, int w, int h,
                              bool fixed_cells = true) {
  const CoverageGrid grid = row_sweep_grid(exact::polylines_of(shapes), rule, w, h, fixed_cells);
  std::vector<double> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) out[static_cast<std::size_t>(y) * w + x] = grid.at(x, y);
  }
  return out;
}

TEST(ClusterRows, MatchTheExactReferenceOnRingsDiscsBarsAndSlivers) {
  std::mt19937 rng(2026);
  const int scenes = exact::kOptimizedBuild ? 24 : 6;
  int compared = 0;
  for (int it = 0; it < scenes; ++it) {
    const bool nonzero = it % 2 == 1;
    const FillRule rule = nonzero ? FillRule::NonZero : FillRule::EvenOdd;
    const int w = 260 + static_cast<int>(rng() % 40), h = 150 + static_cast<int>(rng() % 20);
    const std::vector<Polygon> shapes = scene(rng, w, h, nonzero);
    const std::vector<double> want = exact::trapezoid_coverage(shapes, rule, w, h);
    ASSERT_GT(exact::sum(want), 250) << "scene " << it << ": the ring is missing";
    ASSERT_TRUE(exact::grids_near(row_sweep(shapes, rule, w, h, false), want, w, 1e-9)) << "scene " << it;
    ASSERT_TRUE(exact::grids_near(row_sweep(shapes, rule, w, h), want, w, 1e-9 + detail::kFixedCellsError))
        << "scene " << it << ", fixed-point cells";
    ++compared;
  }
  EXPECT_EQ(compared, scenes);
}

TEST(ClusterRows, AreTheSameBitsWithAndWithoutAvx2) {
  std::mt19937 rng(17);
  int compared = 0;
  for (int it = 0; it < 12; ++it) {
    const bool nonzero = it % 2 == 0;
    const int w = 260 + static_cast<int>(rng() % 40), h = 150 + static_cast<int>(rng() % 20);
    const std::vector<Polygon> shapes = scene(rng, w, h, nonzero);
    for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative,
                          FillRule::AbsGeq2}) {
      const std::vector<double> simd = row_sweep(shapes, rule, w, h);
      detail::portable_kernels_forced() = true;
      const std::vector<double> portable = row_sweep(shapes, rule, w, h);
      detail::portable_kernels_forced() = false;
      for (std::size_t i = 0; i < simd.size(); ++i) {
        ASSERT_EQ(simd[i], portable[i]) << "scene " << it << " rule " << to_string(rule) << " pixel " << i % w << ","
                                        << i / w;
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 60);
}

}  // namespace
}  // namespace vraster::test
