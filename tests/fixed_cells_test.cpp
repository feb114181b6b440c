// Fixed-point cells (src/raster/fixed_cells.hpp): the row sweep's rows of at most 31 active edges sum their pieces in
// 32-bit integers of 2^-26 of a pixel, rows of more (up to kWideRowEdges) in 64-bit integers of 2^-36. Properties:
// within kFixedCellsError of the double cells for every rule (rows of many edges within kWideCellsError), the same
// bits as the double cells where a row has more than kWideRowEdges edges, exact where the areas are whole units, the
// AVX2 split's integers equal to the portable ones, the AVX2 and portable sweeps giving the same bits, and every
// piece's running total within half a unit of its double shares'.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "raster/cells.hpp"
#include "raster/fixed_cells.hpp"
#include "raster/rasterizer_p.hpp"
#include "support/capture.hpp"
#include "support/exact_reference.hpp"

namespace vraster::test {
namespace {

constexpr FillRule kRules[] = {FillRule::NonZero, FillRule::EvenOdd, FillRule::Positive, FillRule::Negative,
                               FillRule::AbsGeq2};

CoverageGrid row_sweep(const std::vector<Polygon>& shapes, FillRule rule, int w, int h, bool fixed_cells) {
  return row_sweep_grid(exact::polylines_of(shapes), rule, w, h, fixed_cells);
}

// The largest difference between two grids.
double largest_difference(const CoverageGrid& a, const CoverageGrid& b, int w, int h) {
  double worst = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) worst = std::max(worst, std::abs(double{a.at(x, y)} - b.at(x, y)));
  }
  return worst;
}

TEST(FixedCells, StayWithinTheirBoundOfTheDoubleCellsForEveryRule) {
  // Overlapping random polygons (up to 3 x 9 edges in a row, long shallow pieces among them), both windings.
  std::mt19937 rng(2612);
  const int w = 160, h = 120;
  double worst = 0;
  for (int it = 0; it < 30; ++it) {
    std::vector<Polygon> shapes;
    for (int k = 0; k < 3; ++k) {
      shapes.push_back(exact::random_polygon(rng, 3 + static_cast<int>(rng() % 7), -10, 170));
    }
    for (const FillRule rule : kRules) {
      const CoverageGrid fixed = row_sweep(shapes, rule, w, h, true);
      const CoverageGrid doubles = row_sweep(shapes, rule, w, h, false);
      const double d = largest_difference(fixed, doubles, w, h);
      ASSERT_LE(d, detail::kFixedCellsError) << "scene " << it << " rule " << to_string(rule);
      worst = std::max(worst, d);
    }
  }
  EXPECT_GT(worst, 0.0);  // the fixed-point rows were used (their rounding shows somewhere)
}

TEST(FixedCells, CoverageIsExactlyZeroWhereNothingIsDrawn) {
  // Vertices inside rows (several in one row, at any height): the pieces' rounded totals need not cancel to the unit
  // where a row's winding returns to 0; what is left (a few units) snaps to 0, as the double cells' 2^-43 does. So
  // is the coverage next to 1 inside.
  std::mt19937 rng(4242);
  const int w = 240, h = 200;
  std::uniform_real_distribution<double> at(20, 220), radius(8, 90);
  for (int it = 0; it < 40; ++it) {
    Polygon star;
    const double cx = at(rng), cy = at(rng) * 0.8;
    const int points = 5 + static_cast<int>(rng() % 20);
    for (int i = 0; i < points; ++i) {
      const double a = 2 * 3.141592653589793 * (i + 0.37 * (rng() % 100) / 100.0) / points;
      const double r = radius(rng);
      star.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
    const std::vector<Polygon> shapes{star};
    const CoverageGrid grid = row_sweep(shapes, FillRule::NonZero, w, h, true);
    const std::vector<double> want = exact::trapezoid_coverage(shapes, FillRule::NonZero, w, h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const double exact_area = want[static_cast<std::size_t>(y) * w + x];
        if (exact_area == 0 || exact_area == 1) {
          ASSERT_EQ(double{grid.at(x, y)}, exact_area) << "shape " << it << " pixel " << x << "," << y;
        }
      }
    }
  }
}

// The rows of a polygon holding more than `edges` edges (with a piece in the row).
std::vector<int> rows_of_more_edges(const std::vector<Polygon>& shapes, int w, int h, std::size_t edges) {
  std::vector<Edge> built;
  int y_min = 0, y_max = 0;
  detail::build_edges(exact::polylines_of(shapes), w, h, built, y_min, y_max);
  std::vector<int> rows;
  for (int y = 0; y < h; ++y) {
    std::size_t active = 0;
    for (const Edge& e : built) active += e.y0 < y + 1.0 && e.y1 > y ? 1 : 0;
    if (active > edges) rows.push_back(y);
  }
  return rows;
}

// A star polygon of `points` points, each joined to the one `step` points on.
Polygon star_polygon(int points, int step, double cx, double cy, double r) {
  Polygon star;
  for (int i = 0; i < points; ++i) {
    const double a = 2 * 3.141592653589793 * (i * step % points) / points + 0.1;
    star.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
  }
  return star;
}

TEST(FixedCells, RowsOfManyEdgesTakeWideCellsWithinTheBound) {
  // Stars whose middle rows hold more than kFixedRowEdges edges (up to several hundred): those rows are summed in
  // wide cells, within kWideCellsError of the double cells and exactly 0 or 1 where the exact area is; the tips
  // (two edges a row) take the 32-bit cells.
  const int w = 200, h = 200;
  const std::vector<std::vector<Polygon>> scenes{
      {star_polygon(40, 17, 100, 100, 90)},
      {star_polygon(301, 140, 101.3, 99.1, 95)},
      {star_polygon(97, 13, 90, 110, 80), star_polygon(60, 29, 120, 95, 70)}};
  double worst = 0;
  for (std::size_t it = 0; it < scenes.size(); ++it) {
    const std::vector<Polygon>& shapes = scenes[it];
    const std::vector<int> crowded = rows_of_more_edges(shapes, w, h, detail::kFixedRowEdges);
    EXPECT_GT(crowded.size(), 50u) << "scene " << it;
    for (const FillRule rule : kRules) {
      const CoverageGrid fixed = row_sweep(shapes, rule, w, h, true);
      const CoverageGrid doubles = row_sweep(shapes, rule, w, h, false);
      const double d = largest_difference(fixed, doubles, w, h);
      ASSERT_LE(d, detail::kWideCellsError) << "scene " << it << " rule " << to_string(rule);
      worst = std::max(worst, d);
      const std::vector<double> want = exact::trapezoid_coverage(shapes, rule, w, h);
      for (const int y : crowded) {
        for (int x = 0; x < w; ++x) {
          const double exact_area = want[static_cast<std::size_t>(y) * w + x];
          if (exact_area == 0 || exact_area == 1) {
            ASSERT_EQ(double{fixed.at(x, y)}, exact_area) << "scene " << it << " rule " << to_string(rule)
                                                          << " pixel " << x << "," << y;
          }
        }
      }
    }
  }
  EXPECT_GT(worst, 0.0);  // the integer rows were used (their rounding shows somewhere)
}

TEST(FixedCells, RowsOfMoreEdgesThanWideCellsHoldKeepTheDoubleCells) {
  // A comb of kWideRowEdges + 16 teeth across rows 2 .. 9: those rows keep the double cells, to the bit.
  const int w = 1100, h = 12;
  Polygon comb;
  const int teeth = static_cast<int>(detail::kWideRowEdges) / 2 + 8;
  for (int i = 0; i < teeth; ++i) {
    const double x = 5 + 1000.0 * i / teeth;
    comb.push_back({x, 2.3});
    comb.push_back({x + 0.5 * 1000.0 / teeth, 9.7});
  }
  comb.push_back({1050, 11});
  comb.push_back({5, 11});
  const std::vector<Polygon> shapes{comb};
  const std::vector<int> crowded = rows_of_more_edges(shapes, w, h, detail::kWideRowEdges);
  ASSERT_EQ(crowded.size(), 8u);
  for (const FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
    const CoverageGrid fixed = row_sweep(shapes, rule, w, h, true);
    const CoverageGrid doubles = row_sweep(shapes, rule, w, h, false);
    for (const int y : crowded) {
      for (int x = 0; x < w; ++x) ASSERT_EQ(fixed.at(x, y), doubles.at(x, y)) << "row " << y << " pixel " << x;
    }
  }
}

TEST(FixedCells, WideCellsSweepTheSameBitsWithAndWithoutAvx2) {
  if (!detail::cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor";
  const int w = 220, h = 210;
  const std::vector<Polygon> shapes{star_polygon(151, 67, 110, 105, 100)};
  for (const FillRule rule : kRules) {
    const CoverageGrid simd = row_sweep(shapes, rule, w, h, true);
    detail::portable_kernels_forced() = true;
    const CoverageGrid portable = row_sweep(shapes, rule, w, h, true);
    detail::portable_kernels_forced() = false;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_EQ(simd.at(x, y), portable.at(x, y)) << to_string(rule) << " " << x << "," << y;
      }
    }
  }
}

TEST(FixedCells, WholeUnitsAreExact) {
  // Edges on pixel boundaries and at half pixels: every share is a whole number of units, so the coverage is the
  // exact area (1, 0.5, 0.25), with no rounding at all.
  const int w = 40, h = 20;
  const std::vector<Polygon> shapes{{{2, 2}, {30, 2}, {30, 10}, {2, 10}},
                                    {{4.5, 12.5}, {20.5, 12.5}, {20.5, 18}, {4.5, 18}}};
  const CoverageGrid grid = row_sweep(shapes, FillRule::NonZero, w, h, true);
  const std::vector<double> want = exact::trapezoid_coverage(shapes, FillRule::NonZero, w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ASSERT_EQ(double{grid.at(x, y)}, want[static_cast<std::size_t>(y) * w + x]) << x << "," << y;
    }
  }
  EXPECT_EQ(grid.at(4, 12), 0.25f);
  EXPECT_EQ(grid.at(10, 12), 0.5f);
  EXPECT_EQ(grid.at(10, 5), 1.0f);
}

TEST(FixedCells, ExactModeKeepsTheDoubleCells) {
  // A path without crossings in exact mode takes the analytic row sweep (it is exact for such paths): in double
  // cells, to 1e-9 of the reference, where the fixed-point rows would be off by up to 3e-7.
  const int w = 300, h = 200;
  for (int it = 0; it < 6; ++it) {
    const double cx = 150 + 20 * std::sin(it), cy = 100 + 10 * std::cos(it);
    const std::vector<Polygon> shapes{{{cx - 120.3, cy - 70.1}, {cx + 110.7, cy - 81.9}, {cx + 97.2, cy + 77.4},
                                       {cx - 101.1, cy + 88.6}, {cx - 130.4, cy + 3.3}}};
    CoverageGrid grid(w, h);
    Rasterizer r;
    r.set_dense_limit(0);
    r.fill(exact::polylines_of(shapes), FillRule::NonZero, AntiAlias::Exact, w, h, grid);
    const std::vector<double> want = exact::trapezoid_coverage(shapes, FillRule::NonZero, w, h);
    std::vector<double> got(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) got[static_cast<std::size_t>(y) * w + x] = grid.at(x, y);
    }
    ASSERT_TRUE(exact::grids_near(got, want, w, 1e-9)) << "shape " << it;
    // The same fill in analytic mode takes the fixed-point rows: within their bound, and not to 1e-9.
    CoverageGrid analytic(w, h);
    r.fill(exact::polylines_of(shapes), FillRule::NonZero, AntiAlias::Analytic, w, h, analytic);
    EXPECT_LE(largest_difference(analytic, grid, w, h), detail::kFixedCellsError);
  }
}

// A piece's shares as the fixed-point (or wide) cells get them, and the running totals of its double shares
// (accumulate_piece).
template <class Cell>
struct PieceShares {
  std::vector<Cell> fixed;
  std::vector<double> totals;
};

template <class Cell>
PieceShares<Cell> shares_of(double xa, double xb, double h) {
  const int cells = 64;
  std::vector<Cell> fixed(cells + detail::kFixedBlock, 0);
  std::vector<double> doubles(cells + detail::kFixedBlock, 0.0);
  detail::accumulate_piece_fixed(fixed.data(), xa, xb, h);
  detail::accumulate_piece(doubles.data(), xa, xb, h);
  PieceShares<Cell> s{fixed, std::vector<double>(doubles.size())};
  double total = 0;
  for (std::size_t i = 0; i < doubles.size(); ++i) s.totals[i] = total += doubles[i];
  return s;
}

template <class Cell>
void expect_every_piece_within_half_a_unit(double unit) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> x(0.0, 50.0), span(0.0, 9.0), height(-1.0, 1.0);
  for (int it = 0; it < 20000; ++it) {
    const double xa = x(rng);
    const double xb = it % 3 == 0 ? xa + span(rng) * 0.05 : xa + span(rng);  // inside one cell, and longer
    const double h = it % 5 == 0 ? std::copysign(1.0, height(rng)) : height(rng);
    const PieceShares<Cell> s = shares_of<Cell>(it % 2 ? xa : xb, it % 2 ? xb : xa, h);
    std::int64_t running = 0;
    for (std::size_t i = 0; i < s.fixed.size(); ++i) {
      running += s.fixed[i];
      // Half a unit, plus the double shares' own round-off in the long sums (under 1e-14 of a pixel).
      ASSERT_LE(std::abs(static_cast<double>(running) - s.totals[i] * unit), 0.5 + 1e-14 * unit)
          << "piece " << xa << " .. " << xb << " height " << h << ", cell " << i;
    }
  }
}

TEST(FixedCells, EveryPieceIsWithinHalfAUnitUpToEveryCell) {
  expect_every_piece_within_half_a_unit<std::int32_t>(detail::kFixedUnit);
  expect_every_piece_within_half_a_unit<std::int64_t>(detail::kWideUnit);
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
// Four pieces split as the AVX2 sweep splits them (in a function compiled for AVX2).
template <class Cell>
[[gnu::target("avx2")]] void add_lane(const detail::SplitLanes<Cell>& split, int i, Cell* cells) {
  split.add_fixed(i, cells);
}

template <class Cell>
[[gnu::target("avx2")]] detail::SplitLanes<Cell> split_avx2(const double* xa, const double* xb, const double* h) {
  return detail::SplitLanes<Cell>(_mm256_loadu_pd(xa), _mm256_loadu_pd(xb), _mm256_loadu_pd(h));
}

template <class Cell>
void expect_avx2_split_gives_the_portable_integers() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(0.0, 40.0), span(0.0, 4.0), height(-1.0, 1.0);
  int long_pieces = 0;
  for (int it = 0; it < 5000; ++it) {
    double xa[4], xb[4], h[4];
    for (int i = 0; i < 4; ++i) {
      xa[i] = x(rng);
      xb[i] = xa[i] + (i == 0 ? span(rng) * 0.1 : span(rng)) * (rng() % 2 ? 1 : -1);
      xb[i] = std::max(xb[i], 0.0);
      h[i] = height(rng);
    }
    const detail::SplitLanes<Cell> split = split_avx2<Cell>(xa, xb, h);
    for (int i = 0; i < 4; ++i) {
      std::vector<Cell> portable(64, 0);
      detail::accumulate_piece_fixed(portable.data(), xa[i], xb[i], h[i]);
      if (split.past[i] > 2) {  // long pieces: both sweeps call accumulate_long_piece_fixed
        ++long_pieces;
        continue;
      }
      std::vector<Cell> simd(64, 0);
      add_lane(split, i, simd.data());  // lane i's four shares, as both AVX2 sweeps add them
      ASSERT_EQ(simd, portable) << "piece " << xa[i] << " .. " << xb[i] << " height " << h[i];
    }
  }
  EXPECT_GT(long_pieces, 100);
}

TEST(FixedCells, TheAvx2SplitGivesThePortableIntegers) {
  if (!detail::cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor";
  expect_avx2_split_gives_the_portable_integers<std::int32_t>();
  expect_avx2_split_gives_the_portable_integers<std::int64_t>();
}
#endif

}  // namespace
}  // namespace vraster::test
