// Rasterizer: tiny hand-made coverage grids (both anti-aliasing modes) and a cross-check of the analytic mode
// against the independent clipping reference (tests/support/reference.hpp) on hundreds of random polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/capture.hpp"
#include "support/reference.hpp"
#include "vraster/vraster.hpp"

namespace vraster::test {
namespace {

constexpr double kAnalyticTol = 1e-6;

// Expected grids are written as text (parse_grid in support/capture.hpp): one row per line, cells separated by
// blanks, each "0", "1", ".25", "0.5" or a fraction "5/6".
::testing::AssertionResult grid_matches(const CoverageGrid& got, const std::string& expected_text, double tol) {
  const auto expected = parse_grid(expected_text);
  if (static_cast<int>(expected.size()) != got.height()) {
    return ::testing::AssertionFailure() << "expected grid has " << expected.size() << " rows, canvas "
                                         << got.height();
  }
  std::ostringstream bad;
  int mismatches = 0;
  for (int y = 0; y < got.height(); ++y) {
    if (static_cast<int>(expected[y].size()) != got.width()) {
      return ::testing::AssertionFailure() << "expected row " << y << " has " << expected[y].size() << " cells";
    }
    for (int x = 0; x < got.width(); ++x) {
      const double e = expected[y][x], g = got.at(x, y);
      if (!(std::abs(g - e) <= tol)) {
        if (++mismatches <= 12) bad << "  pixel (" << x << "," << y << "): got " << g << ", expected " << e << "\n";
      }
    }
  }
  if (!got.violations().empty()) {
    return ::testing::AssertionFailure() << "sink contract violated: " << got.violations().front();
  }
  if (mismatches == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << mismatches << " pixel(s) differ:\n"
                                       << bad.str() << "got (percent):\n"
                                       << got.to_string();
}

Path polygon(std::initializer_list<Point> pts) {
  Path p;
  p.add_polygon(std::vector<Point>(pts), true);
  return p;
}

CoverageGrid analytic(const Path& p, int w, int h, FillRule rule = FillRule::NonZero) {
  return rasterize(p, rule, AntiAlias::Analytic, w, h);
}
CoverageGrid aliased(const Path& p, int w, int h, FillRule rule = FillRule::NonZero) {
  return rasterize(p, rule, AntiAlias::None, w, h);
}

// ---------------------------------------------------------------------------------------------------------------
// Hand-made references. Analytic values are the pixel areas inside the shape; aliased values sample the pixel
// centre (x + 0.5, y + 0.5) with the top-left rule: a centre on a left or top edge is inside, on a right or
// bottom edge outside.

TEST(RasterReference, SquareAtQuarterOffsetsCoversAreaAndSamplesCentresHalfOpen) {
  // [1.25, 3.5] x [0.5, 2.75]: column shares 0 .75 1 .5, row shares .5 1 .75.
  const Path sq = polygon({{1.25, 0.5}, {3.5, 0.5}, {3.5, 2.75}, {1.25, 2.75}});
  EXPECT_TRUE(grid_matches(analytic(sq, 4, 3), R"(
    0  .375  .5  .25
    0  .75   1   .5
    0  .5625 .75 .375)", kAnalyticTol));
  // Centre y = 0.5 on the top edge: inside; centre x = 3.5 on the right edge: outside.
  EXPECT_TRUE(grid_matches(aliased(sq, 4, 3), R"(
    0 1 1 0
    0 1 1 0
    0 1 1 0)", 0));
}

TEST(RasterReference, SquareWithEdgesThroughCentresOwnsLeftAndTopOnly) {
  const Path sq = polygon({{0.5, 0.25}, {2.5, 0.25}, {2.5, 1.75}, {0.5, 1.75}});
  EXPECT_TRUE(grid_matches(analytic(sq, 3, 2), R"(
    .375 .75 .375
    .375 .75 .375)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(sq, 3, 2), R"(
    1 1 0
    1 1 0)", 0));
}

TEST(RasterReference, SquareSmallerThanAPixelGivesItsAreaButMissesTheCentre) {
  const Path sq = polygon({{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.5}, {0.25, 0.5}});
  EXPECT_TRUE(grid_matches(analytic(sq, 2, 1), ".125 0", kAnalyticTol));
  // The centre (0.5, 0.5) is on the bottom edge: outside.
  EXPECT_TRUE(grid_matches(aliased(sq, 2, 1), "0 0", 0));
}

TEST(RasterReference, RightTriangleWithVerticesOnPixelCorners) {
  // Hypotenuse x + y = 4 runs through pixel corners: the diagonal pixels are cut in half, and their centres lie on
  // it (a right edge here, so they are outside).
  const Path tri = polygon({{0, 0}, {4, 0}, {0, 4}});
  EXPECT_TRUE(grid_matches(analytic(tri, 4, 4), R"(
    1  1  1  .5
    1  1  .5 0
    1  .5 0  0
    .5 0  0  0)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(tri, 4, 4), R"(
    1 1 1 0
    1 1 0 0
    1 0 0 0
    0 0 0 0)", 0));
}

TEST(RasterReference, TriangleWithVerticesOnPixelCentres) {
  // (0.5, 0.5), (3.5, 0.5), (0.5, 3.5): corner pixels hold 1/8, edge pixels 1/2 or 1/4.
  const Path tri = polygon({{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}});
  EXPECT_TRUE(grid_matches(analytic(tri, 4, 4), R"(
    .25  .5 .5 .125
    .5   1  .5 0
    .5   .5 0  0
    .125 0  0  0)", kAnalyticTol));
  // Centres on the top and left edges are in, on the hypotenuse (right edge) and bottom vertex row out.
  EXPECT_TRUE(grid_matches(aliased(tri, 4, 4), R"(
    1 1 1 0
    1 1 0 0
    1 0 0 0
    0 0 0 0)", 0));
}

TEST(RasterReference, DiamondWithVerticesOnPixelCorners) {
  const Path dia = polygon({{2, 0}, {4, 2}, {2, 4}, {0, 2}});
  EXPECT_TRUE(grid_matches(analytic(dia, 4, 4), R"(
    0  .5 .5 0
    .5 1  1  .5
    .5 1  1  .5
    0  .5 .5 0)", kAnalyticTol));
  // Centres on the upper-left and lower-left sides are in, on the right sides out: the picture is not symmetric.
  EXPECT_TRUE(grid_matches(aliased(dia, 4, 4), R"(
    0 1 0 0
    1 1 1 0
    1 1 1 0
    0 1 0 0)", 0));
}

TEST(RasterReference, DiamondWithVerticesOnPixelCentres) {
  const Path dia = polygon({{2.5, 0.5}, {4.5, 2.5}, {2.5, 4.5}, {0.5, 2.5}});
  EXPECT_TRUE(grid_matches(analytic(dia, 5, 5), R"(
    0   0  .25 0  0
    0   .5 1   .5 0
    .25 1  1   1  .25
    0   .5 1   .5 0
    0   0  .25 0  0)", kAnalyticTol));
  // Top vertex on a sample line: an empty span (no pixel); left vertex: its centre is in, right vertex: out;
  // bottom vertex: the edges end there (half-open), so nothing.
  EXPECT_TRUE(grid_matches(aliased(dia, 5, 5), R"(
    0 0 0 0 0
    0 1 1 0 0
    1 1 1 1 0
    0 1 1 0 0
    0 0 0 0 0)", 0));
}

// A pentagram whose vertices and five inner crossings are all on pixel corners (so no two edges cross inside a
// pixel and the analytic mode is exact): points (5,0) (10,3) (9,12) (1,12) (0,3) joined as a star; the inner
// pentagon (4,3) (6,3) (7,6) (5,8) (3,6) has winding 2. Analytic values: area of the star outline in the pixel
// (non-zero), minus the inner pentagon's share (even-odd).
Path pentagram() { return polygon({{5, 0}, {9, 12}, {0, 3}, {10, 3}, {1, 12}}); }

TEST(RasterReference, PentagramNonZeroFillsTheInnerPentagon) {
  EXPECT_TRUE(grid_matches(analytic(pentagram(), 10, 12, FillRule::NonZero), R"(
     0    0    0    0  1/6  1/6    0    0    0    0
     0    0    0    0   .5   .5    0    0    0    0
     0    0    0    0  5/6  5/6    0    0    0    0
    .5    1    1    1    1    1    1    1    1   .5
     0   .5    1    1    1    1    1    1   .5    0
     0    0   .5    1    1    1    1   .5    0    0
     0    0  1/6    1    1    1    1  1/6    0    0
     0    0   .5    1    1    1    1   .5    0    0
     0    0  5/6    1   .5   .5    1  5/6    0    0
     0  1/6    1   .5    0    0   .5    1  1/6    0
     0   .5   .5    0    0    0    0   .5   .5    0
     0  1/3    0    0    0    0    0    0  1/3    0)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(pentagram(), 10, 12, FillRule::NonZero), R"(
    0 0 0 0 0 0 0 0 0 0
    0 0 0 0 1 0 0 0 0 0
    0 0 0 0 1 1 0 0 0 0
    1 1 1 1 1 1 1 1 1 0
    0 1 1 1 1 1 1 1 0 0
    0 0 1 1 1 1 1 0 0 0
    0 0 0 1 1 1 1 0 0 0
    0 0 1 1 1 1 1 0 0 0
    0 0 1 1 0 1 1 1 0 0
    0 0 1 0 0 0 1 1 0 0
    0 1 0 0 0 0 0 1 0 0
    0 0 0 0 0 0 0 0 1 0)", 0));
}

TEST(RasterReference, PentagramEvenOddLeavesTheInnerPentagonEmpty) {
  EXPECT_TRUE(grid_matches(analytic(pentagram(), 10, 12, FillRule::EvenOdd), R"(
     0    0    0    0  1/6  1/6    0    0    0    0
     0    0    0    0   .5   .5    0    0    0    0
     0    0    0    0  5/6  5/6    0    0    0    0
    .5    1    1  5/6    0    0  5/6    1    1   .5
     0   .5    1   .5    0    0   .5    1   .5    0
     0    0   .5  1/6    0    0  1/6   .5    0    0
     0    0  1/6   .5    0    0   .5  1/6    0    0
     0    0   .5    1   .5   .5    1   .5    0    0
     0    0  5/6    1   .5   .5    1  5/6    0    0
     0  1/6    1   .5    0    0   .5    1  1/6    0
     0   .5   .5    0    0    0    0   .5   .5    0
     0  1/3    0    0    0    0    0    0  1/3    0)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(pentagram(), 10, 12, FillRule::EvenOdd), R"(
    0 0 0 0 0 0 0 0 0 0
    0 0 0 0 1 0 0 0 0 0
    0 0 0 0 1 1 0 0 0 0
    1 1 1 1 0 0 1 1 1 0
    0 1 1 0 0 0 1 1 0 0
    0 0 1 0 0 0 0 0 0 0
    0 0 0 0 0 0 1 0 0 0
    0 0 1 1 0 1 1 0 0 0
    0 0 1 1 0 1 1 1 0 0
    0 0 1 0 0 0 1 1 0 0
    0 1 0 0 0 0 0 1 0 0
    0 0 0 0 0 0 0 0 1 0)", 0));
}

TEST(RasterReference, HorizontalEdgesOnSampleLinesAndInsideRows) {
  // A step: top edge y = 0.5 (on row 0's sample line), a step at y = 1.5 (on row 1's sample line).
  const Path step = polygon({{0, 0.5}, {2, 0.5}, {2, 1.5}, {3, 1.5}, {3, 3}, {0, 3}});
  EXPECT_TRUE(grid_matches(analytic(step, 3, 3), R"(
    .5 .5 0
    1  1  .5
    1  1  1)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(step, 3, 3), R"(
    1 1 0
    1 1 1
    1 1 1)", 0));
  // A horizontal edge inside a row (y = 1.25 and y = 1.75): analytic takes its share, aliased misses the row.
  const Path thin = polygon({{0, 1.25}, {3, 1.25}, {3, 1.75}, {0, 1.75}});
  EXPECT_TRUE(grid_matches(analytic(thin, 3, 3), R"(
    0  0  0
    .5 .5 .5
    0  0  0)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(thin, 3, 3), R"(
    0 0 0
    1 1 1
    0 0 0)", 0));
}

TEST(RasterReference, ShapesCrossingTheCanvasBorderAreClipped) {
  const Path left_top = polygon({{-1.5, -0.5}, {1.5, -0.5}, {1.5, 1.5}, {-1.5, 1.5}});
  EXPECT_TRUE(grid_matches(analytic(left_top, 3, 3), R"(
    1  .5  0
    .5 .25 0
    0  0   0)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(left_top, 3, 3), R"(
    1 0 0
    0 0 0
    0 0 0)", 0));
  const Path right = polygon({{1.5, 0.5}, {10, 0.5}, {10, 1.5}, {1.5, 1.5}});
  EXPECT_TRUE(grid_matches(analytic(right, 3, 2), R"(
    0 .25 .5
    0 .25 .5)", kAnalyticTol));
  EXPECT_TRUE(grid_matches(aliased(right, 3, 2), R"(
    0 1 1
    0 0 0)", 0));
}

// ---------------------------------------------------------------------------------------------------------------
// Two shapes sharing an edge: aliased, every pixel of the union is owned exactly once (never 0 or 2 times along
// the shared edge); analytic, the two coverages add up to the union's coverage (here 1 everywhere).

void expect_partition(const std::vector<Path>& parts, int w, int h, const std::string& what) {
  for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic}) {
    std::vector<double> sum(static_cast<std::size_t>(w) * h, 0.0);
    for (const Path& p : parts) {
      const CoverageGrid g = rasterize(p, FillRule::NonZero, aa, w, h);
      ASSERT_TRUE(g.violations().empty()) << what << ": " << g.violations().front();
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) sum[static_cast<std::size_t>(y) * w + x] += g.at(x, y);
    }
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const double s = sum[static_cast<std::size_t>(y) * w + x];
        if (aa == AntiAlias::None) {
          EXPECT_EQ(s, 1.0) << what << " (aliased): pixel (" << x << "," << y << ") owned " << s << " times";
        } else {
          EXPECT_NEAR(s, 1.0, kAnalyticTol) << what << " (analytic): pixel (" << x << "," << y << ")";
        }
      }
    }
  }
}

TEST(RasterSharedEdge, DiagonalThroughPixelCentresIsOwnedOnceAndCoverageSumsToOne) {
  // The hypotenuse x + y = 4 passes through the centres of the pixels with x + y = 3.
  expect_partition({polygon({{0, 0}, {4, 0}, {0, 4}}), polygon({{4, 0}, {4, 4}, {0, 4}})}, 4, 4, "diagonal");
  // Same with one of the two shapes drawn in the other direction.
  expect_partition({polygon({{0, 0}, {0, 4}, {4, 0}}), polygon({{4, 0}, {4, 4}, {0, 4}})}, 4, 4,
                   "diagonal, opposite orientation");
}

TEST(RasterSharedEdge, VerticalEdgeThroughPixelCentresIsOwnedOnce) {
  expect_partition({polygon({{0, 0}, {1.5, 0}, {1.5, 3}, {0, 3}}), polygon({{1.5, 0}, {3, 0}, {3, 3}, {1.5, 3}})},
                   3, 3, "vertical x = 1.5");
  // The right shape owns column 1 (its centre is on the right shape's left edge).
  const CoverageGrid right = aliased(polygon({{1.5, 0}, {3, 0}, {3, 3}, {1.5, 3}}), 3, 3);
  EXPECT_TRUE(grid_matches(right, "0 1 1\n0 1 1\n0 1 1", 0));
}

TEST(RasterSharedEdge, SlantedFractionalEdgeIsOwnedOnceAndCoverageSumsToOne) {
  // The square [0, 8]^2 cut by the segment (0.3, 0) - (5.7, 8), and a fan of triangles around (4.25, 3.75).
  expect_partition({polygon({{0, 0}, {0.3, 0}, {5.7, 8}, {0, 8}}), polygon({{0.3, 0}, {8, 0}, {8, 8}, {5.7, 8}})}, 8,
                   8, "slanted cut");
  const Point c{4.25, 3.75};
  const std::vector<Point> ring = {{0, 0}, {3.5, 0}, {8, 0}, {8, 2.5}, {8, 8}, {5, 8}, {0, 8}, {0, 4.5}};
  std::vector<Path> fan;
  for (std::size_t i = 0; i < ring.size(); ++i) fan.push_back(polygon({c, ring[i], ring[(i + 1) % ring.size()]}));
  expect_partition(fan, 8, 8, "fan of 8 triangles");
}

TEST(RasterSharedEdge, HorizontalEdgeOnASampleLineIsOwnedOnce) {
  expect_partition({polygon({{0, 0}, {3, 0}, {3, 1.5}, {0, 1.5}}), polygon({{0, 1.5}, {3, 1.5}, {3, 3}, {0, 3}})},
                   3, 3, "horizontal y = 1.5");
}

// ---------------------------------------------------------------------------------------------------------------
// Analytic coverage vs the clipping reference on random simple polygons.

std::string describe(const Polygon& poly) {
  std::ostringstream s;
  s.precision(17);
  for (Point p : poly) s << "(" << p.x << ", " << p.y << ") ";
  return s.str();
}

TEST(RasterVsReference, AnalyticCoverageEqualsExactPixelAreaOnRandomSimplePolygons) {
  int polygons = 0;
  for (unsigned seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> size(16, 32), vertices(3, 24);
    std::uniform_real_distribution<double> unit(0, 1);
    const int w = size(rng), h = size(rng);
    // Centres may lie near or beyond the border, so many polygons are partly outside the canvas.
    const Point centre{-4 + unit(rng) * (w + 8), -4 + unit(rng) * (h + 8)};
    const double r_max = 2 + unit(rng) * 18;
    const Polygon poly = random_star_polygon(rng, centre, vertices(rng), 0.1 * r_max, r_max);
    const FillRule rule = seed % 2 ? FillRule::NonZero : FillRule::EvenOdd;
    const CoverageGrid got = rasterize(path_of({poly}), rule, AntiAlias::Analytic, w, h);
    ASSERT_TRUE(got.violations().empty()) << "seed " << seed << ": " << got.violations().front();
    const std::vector<double> ref = reference_coverage({poly}, w, h);
    int bad = 0;
    for (int y = 0; y < h && bad < 5; ++y) {
      for (int x = 0; x < w && bad < 5; ++x) {
        const double r = ref[static_cast<std::size_t>(y) * w + x];
        if (!(std::abs(got.at(x, y) - r) <= kAnalyticTol)) {
          ++bad;
          ADD_FAILURE() << "seed " << seed << " (" << to_string(rule) << ", " << w << "x" << h << "), pixel (" << x
                        << "," << y << "): engine " << got.at(x, y) << ", reference " << r
                        << "\npolygon: " << describe(poly);
        }
      }
    }
    ++polygons;
  }
  EXPECT_EQ(polygons, 300);
}

TEST(RasterVsReference, TotalCoverageEqualsShoelaceAreaForPolygonsInsideTheCanvas) {
  for (unsigned seed = 1000; seed < 1300; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> size(16, 32), vertices(3, 40);
    std::uniform_real_distribution<double> unit(0, 1);
    const int w = size(rng), h = size(rng);
    const double r_max = 1 + unit(rng) * (std::min(w, h) / 2.0 - 1.5);
    const Point centre{r_max + 0.5 + unit(rng) * (w - 2 * r_max - 1), r_max + 0.5 + unit(rng) * (h - 2 * r_max - 1)};
    const Polygon poly = random_star_polygon(rng, centre, vertices(rng), 0.05 * r_max, r_max);
    const double area = std::abs(shoelace_area(poly));
    for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
      const CoverageGrid got = rasterize(path_of({poly}), rule, AntiAlias::Analytic, w, h);
      EXPECT_NEAR(got.total(), area, 1e-6 * area)
          << "seed " << seed << " (" << to_string(rule) << "), polygon: " << describe(poly);
    }
  }
}

TEST(RasterVsReference, AnalyticCoverageMatchesReferenceOnCanvasWidthsAroundWordBoundaries) {
  // The analytic sweep keeps one bit per cell in 64-bit words: widths next to multiples of 64, shapes crossing the
  // right border (edges there are dropped), thin canvases.
  for (int w : {1, 2, 63, 64, 65, 66, 127, 128, 129, 130, 191, 192, 193}) {
    for (unsigned seed = 1; seed <= 12; ++seed) {
      std::mt19937 rng(seed * 1000 + w);
      std::uniform_real_distribution<double> unit(0, 1);
      const int h = 1 + seed % 7;
      const Point centre{unit(rng) * (w + 20) - 10, unit(rng) * (h + 4) - 2};
      const Polygon poly = random_star_polygon(rng, centre, 10, 0.5, 3 + unit(rng) * 80);
      const CoverageGrid got = rasterize(path_of({poly}), FillRule::NonZero, AntiAlias::Analytic, w, h);
      ASSERT_TRUE(got.violations().empty()) << "width " << w << ", seed " << seed << ": " << got.violations().front();
      const std::vector<double> ref = reference_coverage({poly}, w, h);
      for (int i = 0; i < w * h; ++i) {
        ASSERT_NEAR(got.at(i % w, i / w), ref[i], kAnalyticTol)
            << "width " << w << ", height " << h << ", seed " << seed << ", pixel (" << i % w << "," << i / w
            << ")\npolygon: " << describe(poly);
      }
    }
  }
}

TEST(RasterVsReference, PolygonsWithFarAwayVerticesMatchTheReference) {
  // Edges from up to 1e6 pixels away are clipped to the canvas; what is left must still be exact.
  for (unsigned seed = 1; seed <= 200; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1, 1);
    const double far = std::pow(10.0, 2 + seed % 5);
    const Polygon poly = {{unit(rng) * far, unit(rng) * far}, {8 + unit(rng) * 8, 8 + unit(rng) * 8},
                          {unit(rng) * far, unit(rng) * far}};
    const Path path = path_of({poly});
    const CoverageGrid got = rasterize(path, FillRule::NonZero, AntiAlias::Analytic, 16, 16);
    const std::vector<double> ref = reference_coverage({poly}, 16, 16);
    const CoverageGrid aliased_grid = rasterize(path, FillRule::NonZero, AntiAlias::None, 16, 16);
    for (int i = 0; i < 256; ++i) {
      ASSERT_NEAR(got.at(i % 16, i / 16), ref[i], kAnalyticTol)
          << "seed " << seed << ", pixel (" << i % 16 << "," << i / 16 << ")\npolygon: " << describe(poly);
      const auto w = winding_number({poly}, {i % 16 + 0.5, i / 16 + 0.5});
      if (w) {
        ASSERT_EQ(aliased_grid.at(i % 16, i / 16), *w != 0 ? 1.f : 0.f)
            << "aliased, seed " << seed << ", pixel (" << i % 16 << "," << i / 16 << ")";
      }
    }
  }
}

TEST(RasterVsReference, ReferenceItselfAgreesWithHandComputedAreas) {
  // The reference is only useful if it is right: a triangle whose pixel areas are known (see
  // TriangleWithVerticesOnPixelCentres) and a shoelace area.
  const Polygon tri = {{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}};
  EXPECT_DOUBLE_EQ(shoelace_area(tri), 4.5);
  EXPECT_DOUBLE_EQ(shoelace_area({{0.5, 0.5}, {0.5, 3.5}, {3.5, 0.5}}), -4.5);
  const std::vector<double> ref = reference_coverage({tri}, 4, 4);
  const double expected[16] = {.25, .5, .5, .125, .5, 1, .5, 0, .5, .5, 0, 0, .125, 0, 0, 0};
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(ref[i], expected[i], 1e-12) << "pixel " << i % 4 << "," << i / 4;
  const Polygon clipped = clip_to_box({{-1, -1}, {3, -1}, {3, 3}, {-1, 3}}, 0, 0, 2, 1);
  EXPECT_DOUBLE_EQ(shoelace_area(clipped), 2.0);
  // Clockwise on screen: the downward edge (the hypotenuse) is right of (1, 1), the upward one left of it.
  EXPECT_EQ(winding_number({tri}, {1, 1}), -1);
  EXPECT_EQ(winding_number(reversed({tri}), {1, 1}), 1);
  EXPECT_EQ(winding_number({tri}, {3, 3}), 0);
  EXPECT_EQ(winding_number({tri}, {2, 2}), std::nullopt);  // on the hypotenuse
}

// ---------------------------------------------------------------------------------------------------------------

TEST(RasterContract, SpansComeInOrderInsideTheCanvasWithCoverageInRange) {
  // A sink contract check on a scene with many contours crossing all four borders, both modes and all rules.
  std::mt19937 rng(77);
  Path scene;
  for (int i = 0; i < 20; ++i) {
    scene.add_polygon(random_star_polygon(rng, {std::uniform_real_distribution<double>(-10, 30)(rng),
                                                std::uniform_real_distribution<double>(-10, 30)(rng)},
                                          12, 1, 15));
  }
  for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd, FillRule::Positive, FillRule::Negative,
                        FillRule::AbsGeq2}) {
    for (AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic}) {
      const CoverageGrid g = rasterize(scene, rule, aa, 20, 20);
      EXPECT_TRUE(g.violations().empty()) << to_string(rule) << "/" << to_string(aa) << ": "
                                          << (g.violations().empty() ? "" : g.violations().front());
      EXPECT_GT(g.total(), 0) << to_string(rule) << "/" << to_string(aa);
    }
  }
}

// Thin shapes' short rows reach the sink in batches (CoverageSink::rows), of at most 32 rows. The calls still come in
// increasing y (x increasing within a row) with spans right of a row's cells (a sliver that leaves the image on the
// right) and wide rows between the batches, and the coverage is the exact area: in the row sweep (large shapes) and
// in the dense sweep (small ones) alike.
TEST(RasterContract, BatchedRowsKeepTheOrderAndTheArea) {
  struct Log final : CoverageSink {
    explicit Log(int w, int h) : grid(w, h) {}
    CoverageGrid grid;  // checks the order of the calls it gets
    int batches = 0;
    std::size_t largest = 0;
    void span(int y, int x0, int x1, float c) override { grid.span(y, x0, x1, c); }
    void row(int y, int x0, int x1, const float* c) override { grid.row(y, x0, x1, c); }
    void rows(const CoverageRow* r, std::size_t n) override {
      ++batches;
      largest = std::max(largest, n);
      CoverageSink::rows(r, n);  // row() for each
    }
  };
  struct Case {
    int width, height;
    std::vector<Polygon> shapes;
  };
  const std::vector<Case> cases = {
      {200, 120,
       {{{10, 2}, {40, 50}, {10.4, 2.2}},             // narrow rows
        {{150, 52}, {400, 52}, {150, 64}},            // narrow rows with a span to the right edge, then wide rows
        {{70, 65}, {190, 75}, {120, 100}},            // wide rows
        {{100.25, 90}, {101.5, 118.5}, {99, 119}}}},  // rows of one and two pixels
      // Dense: a sliver, and a shape whose only edge in the image is its left one (spans to the right edge).
      {30, 70, {{{2, 1}, {9, 68}, {2.3, 1.5}}, {{12, 1}, {100, 1}, {100, 10}, {13, 10}}}},
  };
  for (const Case& c : cases) {
    Polylines lines;
    flatten(path_of(c.shapes), Affine{}, FlattenOptions{}, lines);
    Log log(c.width, c.height);
    Rasterizer r;
    r.fill(lines, FillRule::NonZero, AntiAlias::Analytic, c.width, c.height, log);
    ASSERT_TRUE(log.grid.violations().empty()) << log.grid.violations().front();
    EXPECT_GT(log.batches, 1) << c.width << "x" << c.height;
    EXPECT_LE(log.largest, 32u);
    const std::vector<double> ref = reference_coverage(c.shapes, c.width, c.height);
    for (int y = 0; y < c.height; ++y) {
      for (int x = 0; x < c.width; ++x) {
        ASSERT_NEAR(log.grid.at(x, y), ref[static_cast<std::size_t>(y) * c.width + x], kAnalyticTol)
            << c.width << "x" << c.height << ", pixel " << x << "," << y;
      }
    }
  }
}

// Records every sink call (to see spans that should not exist).
struct SpanLog final : CoverageSink {
  struct Call {
    int y, x0, x1;
    float first;
  };
  std::vector<Call> calls;
  void span(int y, int x0, int x1, float c) override { calls.push_back({y, x0, x1, c}); }
  void row(int y, int x0, int x1, const float* c) override { calls.push_back({y, x0, x1, c[0]}); }
};

// Regression (analytic round-off residue): fixed in bbb3daf (trailing-span fix, round-off coverage snapped to 0). The
// running sum of the cell deltas did not return to exactly 0 right of a shape, and the leftover (~1e-16) went to the
// sink as coverage, as a span to the end of the row: the triangle (0,0) (1,1/3) (1/3,1) lies inside pixel (0,0)
// (area 4/9), yet on a 1000-pixel-wide canvas row 0 got "row [0,3) 0.444 1.1e-16 1.1e-16" and
// "span [3,1000) 1.1e-16". Guards: only pixel (0,0) gets coverage, and on random polygons every pixel of exact area 0
// gets exactly 0.
TEST(RasterContract, AnalyticCoverageIsExactlyZeroWhereNothingIsDrawn) {
  Path tri;
  tri.move_to(0, 0).line_to(1, 1.0 / 3).line_to(1.0 / 3, 1).close();
  Polylines lines;
  flatten(tri, Affine{}, FlattenOptions{}, lines);
  SpanLog log;
  Rasterizer r;
  r.fill(lines, FillRule::NonZero, AntiAlias::Analytic, 1000, 2, log);
  ASSERT_FALSE(log.calls.empty());
  for (const auto& c : log.calls) {
    EXPECT_TRUE(c.y == 0 && c.x0 == 0 && c.x1 == 1) << "unexpected call y=" << c.y << " [" << c.x0 << "," << c.x1
                                                      << ") coverage " << c.first;
  }
  EXPECT_NEAR(log.calls.front().first, 4.0 / 9.0, 1e-6);
  // And on random polygons: every pixel whose exact area is 0 gets exactly 0.
  for (unsigned seed = 1; seed <= 200; ++seed) {
    std::mt19937 rng(seed);
    const Polygon poly = random_star_polygon(rng, {8, 8}, 12, 1, 7);
    const CoverageGrid g = rasterize(path_of({poly}), FillRule::NonZero, AntiAlias::Analytic, 16, 16);
    const std::vector<double> ref = reference_coverage({poly}, 16, 16);
    for (int i = 0; i < 256; ++i) {
      if (ref[i] == 0) {
        ASSERT_EQ(g.at(i % 16, i / 16), 0.f) << "seed " << seed << ", pixel " << i % 16 << "," << i / 16;
      }
    }
  }
}

// A contour with a NaN or infinite point has no shape: it is skipped, and the other contours of the same fill draw
// exactly as they do alone, in every mode and under every rule (polylines built by hand can hold such points;
// flatten() refuses them).
TEST(Raster, ContoursWithNonFinitePointsAreSkipped) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  Polylines good;
  good.points = {{2.5, 1.25}, {13.75, 3.5}, {6.5, 14.0}};
  good.ends = {3};
  good.closed = {1};
  const std::vector<std::vector<Point>> bad = {
      {{1, 1}, {nan, 8}, {12, 12}}, {{-inf, 2}, {14, 7}, {3, inf}}, {{nan, nan}, {nan, nan}, {nan, nan}}};
  for (const std::vector<Point>& contour : bad) {
    Polylines both = good;
    both.points.insert(both.points.end(), contour.begin(), contour.end());
    both.ends.push_back(static_cast<std::uint32_t>(both.points.size()));
    both.closed.push_back(1);
    for (const AntiAlias aa : {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact, AntiAlias::Ssaa4,
                               AntiAlias::Msaa8}) {
      for (const FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::NonExterior, FillRule::Negative}) {
        CoverageGrid alone(16, 16), with_bad(16, 16);
        Rasterizer r;
        r.fill(good, rule, aa, 16, 16, alone);
        r.fill(both, rule, aa, 16, 16, with_bad);
        EXPECT_GT(alone.total(), 10.0);
        EXPECT_EQ(alone.to_string(), with_bad.to_string()) << to_string(aa) << ", " << to_string(rule);
        EXPECT_TRUE(with_bad.violations().empty());
      }
    }
    std::vector<std::uint8_t> mask_alone(16 * 16), mask_with_bad(16 * 16);
    Rasterizer r;
    r.fill_mask(good, FillRule::NonZero, 16, 16, mask_alone.data(), 16);
    r.fill_mask(both, FillRule::NonZero, 16, 16, mask_with_bad.data(), 16);
    EXPECT_EQ(mask_alone, mask_with_bad);
  }
}

}  // namespace
}  // namespace vraster::test
