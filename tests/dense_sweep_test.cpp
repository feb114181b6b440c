// The dense small-path sweep and the edge-table row sweep must give the same coverage (to round-off) for every
// rule, including paths cut by the image borders, paths that leave the image on the right (their winding holds to
// the row's end) and self-intersecting ones.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raster/cpu.hpp"
#include "raster/fixed_cells.hpp"
#include "raster/rasterizer_p.hpp"
#include "support/capture.hpp"
#include "support/exact_reference.hpp"
#include "vraster/renderer.hpp"

namespace vraster::test {
namespace {

// dense_limit 0: the row sweep; fixed_cells false: every row in double cells (the fixed-point ones, rows of few
// edges in the row sweep and wide blocks of fills of few edges in the dense sweep, are within
// detail::kFixedCellsError of them).
CoverageGrid fill_with(const Polylines& lines, FillRule rule, int w, int h, std::int64_t dense_limit,
                       bool fixed_cells = true) {
  CoverageGrid grid(w, h);
  Rasterizer r;
  r.set_dense_limit(dense_limit);
  r.set_fixed_cells(fixed_cells);
  r.fill(lines, rule, AntiAlias::Analytic, w, h, grid);
  EXPECT_TRUE(grid.violations().empty()) << grid.violations().front();
  return grid;
}

// Fills `path` with the dense sweep and with the row sweep under every rule and compares them pixel by pixel;
// returns how many rules it compared (5, or fewer after a failure).
int compare_every_rule(const Path& path, int w, int h, int iteration) {
  Polylines lines;
  flatten(path, Affine{}, FlattenOptions{}, lines);
  int compared = 0;
  for (FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative,
                        FillRule::AbsGeq2}) {
    const CoverageGrid dense = fill_with(lines, rule, w, h, 1 << 20);
    const CoverageGrid rows = fill_with(lines, rule, w, h, 0);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        // (each within kFixedCellsError of the double cells, where its cells are fixed-point)
        EXPECT_NEAR(dense.at(x, y), rows.at(x, y), 1e-9 + 2 * detail::kFixedCellsError)
            << "iteration " << iteration << " rule " << to_string(rule) << " pixel " << x << "," << y;
        if (::testing::Test::HasFailure()) return compared;
      }
    }
    ++compared;
  }
  return compared;
}

TEST(DenseSweep, MatchesTheRowSweepOnRandomPolygonsForEveryRule) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> coord(-6, 30);
  int compared = 0;
  for (int it = 0; it < 300; ++it) {
    const int w = 8 + static_cast<int>(rng() % 25), h = 8 + static_cast<int>(rng() % 25);
    Path path;
    const int contours = 1 + static_cast<int>(rng() % 2);
    for (int c = 0; c < contours; ++c) {
      const int n = 3 + static_cast<int>(rng() % 12);
      path.move_to(coord(rng), coord(rng));
      for (int i = 1; i < n; ++i) path.line_to(coord(rng), coord(rng));
      path.close();
    }
    compared += compare_every_rule(path, w, h, it);
    if (HasFailure()) return;
  }
  EXPECT_EQ(compared, 1500);
}

// Wide blocks sweep each row only between its first and last touched cell: shapes with empty margins, rows with no
// piece at all (a shape in two parts), and shapes leaving the image on the right must still give the row sweep's
// coverage.
TEST(DenseSweep, MatchesTheRowSweepOnWideBlocksWithMarginsAndEmptyRows) {
  std::mt19937 rng(777);
  int compared = 0;
  for (int it = 0; it < 200; ++it) {
    const int w = 24 + static_cast<int>(rng() % 140), h = 8 + static_cast<int>(rng() % 40);
    std::uniform_real_distribution<double> x_of(-6, w + (it % 4 == 0 ? 40 : 6)), y_of(-4, h + 4);
    Path path;
    const int contours = 1 + static_cast<int>(rng() % 3);
    for (int c = 0; c < contours; ++c) {
      // Small contours far apart leave margins and empty rows inside the block.
      const double cx = x_of(rng), cy = y_of(rng), size = 2 + static_cast<double>(rng() % 20);
      const int n = 3 + static_cast<int>(rng() % 8);
      for (int i = 0; i < n; ++i) {
        std::uniform_real_distribution<double> d(-size, size);
        if (i == 0) {
          path.move_to(cx + d(rng), cy + d(rng));
        } else {
          path.line_to(cx + d(rng), cy + d(rng));
        }
      }
      path.close();
    }
    compared += compare_every_rule(path, w, h, it);
    if (HasFailure()) return;
  }
  EXPECT_EQ(compared, 1000);
}

// Wide rows of the row sweep: pieces close together (a self-intersecting polygon's, a zigzag's) are swept as one run
// from the row's first touched cell to its last, pieces far apart (the two sides of a disc) run by run with constant
// spans between them. Both must give the dense sweep's coverage, on shapes whose rows have both kinds, some leaving
// the image on the right.
TEST(DenseSweep, MatchesTheRowSweepOnWideRowsWithPiecesCloseTogetherAndFarApart) {
  std::mt19937 rng(4321);
  int compared = 0;
  for (int it = 0; it < 24; ++it) {
    const int w = 160 + static_cast<int>(rng() % 120), h = 60 + static_cast<int>(rng() % 60);
    std::uniform_real_distribution<double> x_of(-10, w + (it % 3 == 0 ? 60 : 10)), y_of(-5, h + 5);
    Path path;
    // A random ten-vertex polygon: rows with several crossings a few cells apart.
    path.move_to(x_of(rng), y_of(rng));
    for (int i = 1; i < 10; ++i) path.line_to(x_of(rng), y_of(rng));
    path.close();
    // A disc: rows with two pieces a hundred cells apart.
    const double cx = x_of(rng), cy = y_of(rng);
    path.add_circle({cx, cy}, 40 + static_cast<double>(rng() % 30));
    // A zigzag band: many pieces two or three cells apart.
    const double zx = x_of(rng), zy = y_of(rng);
    path.move_to(zx, zy);
    for (int i = 1; i <= 30; ++i) path.line_to(zx + 2.5 * i, zy + (i % 2 == 0 ? 0 : 25));
    path.line_to(zx + 75, zy + 35);
    path.line_to(zx, zy + 35);
    path.close();
    compared += compare_every_rule(path, w, h, it);
    if (HasFailure()) return;
  }
  EXPECT_EQ(compared, 120);
}

// Thin shapes take the dense sweep whatever their box, in strips of rows (a sliver across a 420 x 420 image is far
// over the dense limit). Slivers never cross themselves, so analytic coverage is exact there up to round-off: each
// must match the exact trapezoid reference, with the row sweep's coverage too, in every direction (steep and shallow,
// both windings), some cut by the image's edges.
TEST(DenseSweep, ThinShapesInStripsMatchTheExactReference) {
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> coord(-30, 450), unit(0, 1);
  const int side = 420;
  const int slivers = exact::kOptimizedBuild ? 40 : 10;
  for (int it = 0; it < slivers; ++it) {
    const Point a{coord(rng), coord(rng)}, b{coord(rng), coord(rng)};
    const double base = 0.02 + 2 * unit(rng), turn = 6.283185307179586 * unit(rng);
    const Point c{a.x + base * std::cos(turn), a.y + base * std::sin(turn)};
    const std::vector<Polygon> shape{it % 2 == 0 ? Polygon{a, b, c} : Polygon{c, b, a}};
    const Polylines lines = exact::polylines_of(shape);
    const std::vector<double> want = exact::trapezoid_coverage(shape, FillRule::NonZero, side, side);
    // The dense sweep and the row sweep in double cells (both to 1e-9), and both in fixed-point cells.
    for (const auto& [limit, fixed] :
         {std::pair{Rasterizer::kDefaultDenseLimit, false}, std::pair{std::int64_t{0}, false},
          std::pair{Rasterizer::kDefaultDenseLimit, true}, std::pair{std::int64_t{0}, true}}) {
      const CoverageGrid got = fill_with(lines, FillRule::NonZero, side, side, limit, fixed);
      std::vector<double> values(static_cast<std::size_t>(side) * side);
      for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) values[static_cast<std::size_t>(y) * side + x] = got.at(x, y);
      }
      const double tolerance = 1e-9 + (fixed ? detail::kFixedCellsError : 0.0);
      ASSERT_TRUE(exact::grids_near(values, want, side, tolerance))
          << "sliver " << it << ", dense limit " << limit << ", fixed cells " << fixed;
    }
  }
}

// A convex polygon: `corners` points on an ellipse around (cx, cy), turned by `turn`.
Polygon convex(double cx, double cy, double rx, double ry, double turn, int corners) {
  Polygon p;
  for (int i = 0; i < corners; ++i) {
    const double t = 6.283185307179586 * i / corners;
    const double x = rx * std::cos(t), y = ry * std::sin(t);
    p.push_back({cx + x * std::cos(turn) - y * std::sin(turn), cy + x * std::sin(turn) + y * std::cos(turn)});
  }
  return p;
}

// Large fills whose rows hold few pieces (convex shapes) take the dense sweep with each row's pieces noted, and
// rows whose pieces lie far apart are swept cluster by cluster with spans between them. Convex shapes have no
// crossings, so their analytic coverage is exact up to round-off: triangles, turned rectangles and many-sided
// polygons in every size from a block past the dense limit to the image, some cut by the image's sides (the right
// side's winding holds to the row's end), must match the exact trapezoid reference and the row sweep; with a small
// second contour beside them, some rows hold three or four pieces, close together or far apart.
TEST(DenseSweep, ConvexShapesWithTheirRowsPiecesNotedMatchTheExactReference) {
  std::mt19937 rng(2027);
  std::uniform_real_distribution<double> unit(0, 1);
  const int w = 300, h = 260;
  const int shapes = exact::kOptimizedBuild ? 60 : 16;
  int ranged = 0;
  for (int it = 0; it < shapes; ++it) {
    const double cx = -40 + (w + 80) * unit(rng), cy = -30 + (h + 60) * unit(rng);
    const double rx = 40 + 150 * unit(rng), ry = 40 + 150 * unit(rng), turn = 3.14159 * unit(rng);
    const int corners = it % 3 == 0 ? 3 : (it % 3 == 1 ? 4 : 5 + static_cast<int>(rng() % 60));
    std::vector<Polygon> shape{convex(cx, cy, rx, ry, turn, corners)};
    if (it % 4 == 3) {  // beside the shape, clear of it (no crossing): 2 to 40 cells right of its bounding circle
      const double r = 3 + 10 * unit(rng);
      shape.push_back(convex(cx + std::max(rx, ry) + 2 + 38 * unit(rng) + r, cy, r, r, 0.3, 3));
    }
    if (it % 2 == 1) std::reverse(shape[0].begin(), shape[0].end());  // both windings
    const Polylines lines = exact::polylines_of(shape);
    // Which sweep the rasterizer picks for these edges (the test is about the noted rows).
    std::vector<Edge> edges;
    int y_min = 0, y_max = 0, x_base = 0, columns = 0;
    detail::build_edges(lines, w, h, edges, y_min, y_max);
    if (edges.empty()) continue;
    detail::edge_columns(edges, x_base, columns);
    if (detail::dense_kind(edges, y_min, y_max, columns, Rasterizer::kDefaultDenseLimit) == detail::DenseKind::Ranged) {
      ++ranged;
    }
    const std::vector<double> want = exact::trapezoid_coverage(shape, FillRule::NonZero, w, h);
    const CoverageGrid rows = fill_with(lines, FillRule::NonZero, w, h, 0, false);
    const CoverageGrid fixed_rows = fill_with(lines, FillRule::NonZero, w, h, 0, true);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_NEAR(fixed_rows.at(x, y), rows.at(x, y), detail::kFixedCellsError)
            << "shape " << it << " pixel " << x << "," << y;
      }
    }
    for (const FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
      // In double cells (rows the default limit still leaves to the row sweep in double cells, as `rows`) to 1e-9;
      // in fixed-point cells (the shapes of at most 31 edges) to their bound.
      for (const bool fixed : {false, true}) {
        const CoverageGrid got = fill_with(lines, rule, w, h, Rasterizer::kDefaultDenseLimit, fixed);
        const double tolerance = 1e-9 + (fixed ? detail::kFixedCellsError : 0.0);
        std::vector<double> values(static_cast<std::size_t>(w) * h);
        for (int y = 0; y < h; ++y) {
          for (int x = 0; x < w; ++x) {
            values[static_cast<std::size_t>(y) * w + x] = got.at(x, y);
            ASSERT_NEAR(got.at(x, y), rows.at(x, y), tolerance) << "shape " << it << " pixel " << x << "," << y;
          }
        }
        ASSERT_TRUE(exact::grids_near(values, want, w, tolerance))
            << "shape " << it << " rule " << to_string(rule) << " fixed cells " << fixed;
      }
    }
  }
  EXPECT_GE(ranged, shapes / 2);  // most shapes are large enough to take the noted rows
}

// Wide dense blocks of fills of few edges (Trimmed rows: polygons of a few dozen columns; Ranged rows: large convex
// shapes) take fixed-point cells, those of stars (rows of more than kFixedRowEdges pieces) wide cells. Their integers
// are the same with and without AVX2 (the split's rounded shares, then exact sums), and so are the coverage and the
// pixels blended straight from the cells (8-bit solid colours, the fused path), one thread or two. The comparison is
// not vacuous: the integer cells' coverage differs from the double cells' somewhere in most shapes.
TEST(DenseSweep, FixedPointBlocksGiveTheSameBitsWithAndWithoutAvx2AndWithThreads) {
  std::mt19937 rng(5150);
  std::uniform_real_distribution<double> unit(0, 1);
  const int w = 240, h = 200;
  int differs = 0;
  for (int it = 0; it < 40; ++it) {
    Path path;
    if (it % 5 == 4) {  // a star of 61 points, 50-90 px across: rows of up to some 60 pieces, wide cells
      const double cx = 50 + (w - 100) * unit(rng), cy = 50 + (h - 100) * unit(rng), r = 25 + 20 * unit(rng);
      for (int i = 0; i < 61; ++i) {
        const double a = 6.283185307179586 * (i * 23 % 61) / 61 + unit(rng) * 0.01;
        const Point p{cx + r * std::cos(a), cy + r * std::sin(a)};
        if (i == 0) {
          path.move_to(p);
        } else {
          path.line_to(p);
        }
      }
      path.close();
    } else if (it % 2 == 0) {  // large and convex: Ranged rows
      const Polygon p = convex(w * unit(rng), h * unit(rng), 40 + 100 * unit(rng), 40 + 100 * unit(rng),
                               3.14159 * unit(rng), 3 + static_cast<int>(rng() % 20));
      path.move_to(p[0]);
      for (std::size_t i = 1; i < p.size(); ++i) path.line_to(p[i]);
      path.close();
    } else {  // a polygon a few dozen cells wide, self-intersecting: Trimmed rows
      const double cx = w * unit(rng), cy = h * unit(rng);
      std::uniform_real_distribution<double> d(-25, 25);
      path.move_to(cx + d(rng), cy + d(rng));
      for (int i = 1; i < 3 + static_cast<int>(rng() % 12); ++i) path.line_to(cx + d(rng), cy + d(rng));
      path.close();
    }
    Polylines lines;
    flatten(path, Affine{}, FlattenOptions{}, lines);
    const FillRule rule = it % 4 < 2 ? FillRule::NonZero : FillRule::EvenOdd;
    const CoverageGrid simd = fill_with(lines, rule, w, h, Rasterizer::kDefaultDenseLimit);
    CoverageGrid portable(1, 1);
    detail::portable_kernels_forced() = true;
    portable = fill_with(lines, rule, w, h, Rasterizer::kDefaultDenseLimit);
    detail::portable_kernels_forced() = false;
    const CoverageGrid doubles = fill_with(lines, rule, w, h, Rasterizer::kDefaultDenseLimit, false);
    bool any_difference = false;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_EQ(simd.at(x, y), portable.at(x, y)) << "shape " << it << " pixel " << x << "," << y;
        ASSERT_NEAR(simd.at(x, y), doubles.at(x, y), detail::kFixedCellsError) << "shape " << it;
        any_difference = any_difference || simd.at(x, y) != doubles.at(x, y);
      }
    }
    differs += any_difference;
    // Pixels: one thread with AVX2 (cells blended into the pixels), portable kernels, two threads.
    auto draw = [&](int threads) {
      Image image(w, h);
      image.clear(Color{0.2f, 0.4f, 0.6f, 0.8f});
      Renderer renderer;
      renderer.set_threads(threads);
      FillOptions options;
      options.rule = rule;
      renderer.fill(image, path, Affine{}, Color{0.9f, 0.3f, 0.1f, it % 3 == 0 ? 1.0f : 0.7f}, options);
      return image;
    };
    const Image one = draw(1), two = draw(2);
    detail::portable_kernels_forced() = true;
    const Image portable_pixels = draw(1);
    detail::portable_kernels_forced() = false;
    ASSERT_EQ(one.data, portable_pixels.data) << "shape " << it;
    ASSERT_EQ(one.data, two.data) << "shape " << it;
  }
  EXPECT_GE(differs, 20);
}

// Fixed-point cells need at most kFixedRowEdges pieces in every row, not at most that many edges: a 64-sided disc
// (two or three pieces a row) takes them; a comb of 40 teeth (40 pieces in its middle rows) takes wide cells. Either
// way the coverage differs from the double cells' (the rounding shows), within the bound.
TEST(DenseSweep, FixedPointCellsGoByThePiecesOfEachRowNotTheEdgeCount) {
  Path disc, comb;
  for (int i = 0; i < 64; ++i) {
    const double t = 6.283185307179586 * i / 64;
    const Point p{24.3 + 20 * std::cos(t), 16.7 + 14 * std::sin(t)};
    if (i == 0) {
      disc.move_to(p);
    } else {
      disc.line_to(p);
    }
  }
  disc.close();
  comb.move_to(1.3, 30.5);
  for (int i = 0; i < 20; ++i) {
    comb.line_to(1.3 + 2.2 * i, 4.4);
    comb.line_to(2.4 + 2.2 * i, 27.1);
  }
  comb.line_to(45.5, 30.5);
  comb.close();
  for (const Path* path : {&disc, &comb}) {
    Polylines lines;
    flatten(*path, Affine{}, FlattenOptions{}, lines);
    ASSERT_GT(lines.points.size(), detail::kFixedRowEdges);
    for (const FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
      const CoverageGrid fixed = fill_with(lines, rule, 48, 32, Rasterizer::kDefaultDenseLimit);
      const CoverageGrid doubles = fill_with(lines, rule, 48, 32, Rasterizer::kDefaultDenseLimit, false);
      bool differs = false;
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 48; ++x) {
          ASSERT_NEAR(fixed.at(x, y), doubles.at(x, y), detail::kFixedCellsError) << x << "," << y;
          differs = differs || fixed.at(x, y) != doubles.at(x, y);
        }
      }
      EXPECT_TRUE(differs) << (path == &disc ? "the disc " : "the comb ") << to_string(rule);
    }
  }
}

// A dense fill of more than kWideRowEdges edges (a zigzag of tiny steps inside a small box) keeps the double cells,
// bit for bit.
TEST(DenseSweep, FillsOfMoreEdgesThanWideCellsHoldKeepTheDoubleCells) {
  Path zigzag;
  zigzag.move_to(2, 2);
  const int steps = static_cast<int>(detail::kWideRowEdges) + 200;
  for (int i = 0; i < steps; ++i) zigzag.line_to(2 + 150.0 * i / steps, i % 2 ? 20.0 : 22.5);
  zigzag.line_to(152, 60);
  zigzag.line_to(2, 60);
  zigzag.close();
  Polylines lines;
  flatten(zigzag, Affine{}, FlattenOptions{}, lines);
  ASSERT_GT(lines.points.size(), detail::kWideRowEdges);
  for (const FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
    const CoverageGrid integer = fill_with(lines, rule, 160, 64, Rasterizer::kDefaultDenseLimit);
    const CoverageGrid doubles = fill_with(lines, rule, 160, 64, Rasterizer::kDefaultDenseLimit, false);
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 160; ++x) ASSERT_EQ(integer.at(x, y), doubles.at(x, y)) << x << "," << y;
    }
  }
}

TEST(DenseSweep, WindingOfAShapeLeavingTheImageOnTheRightHoldsToTheRowEnd) {
  Path path;
  path.add_rect({2.5, 1, 40, 3});  // right edge far outside a 10-wide image
  Polylines lines;
  flatten(path, Affine{}, FlattenOptions{}, lines);
  const CoverageGrid dense = fill_with(lines, FillRule::NonZero, 10, 4, 1 << 20);
  EXPECT_NEAR(dense.at(2, 1), 0.5, 1e-12);
  for (int x = 3; x < 10; ++x) {
    EXPECT_NEAR(dense.at(x, 1), 1.0, 1e-12) << x;
    EXPECT_NEAR(dense.at(x, 2), 1.0, 1e-12) << x;
  }
  EXPECT_NEAR(dense.total(), 2 * 7.5, 1e-9);
}

}  // namespace
}  // namespace vraster::test
