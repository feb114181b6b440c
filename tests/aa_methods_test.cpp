// Antialiasing methods: supersampling (ssaa-N), multisampling (msaa-N) and the FXAA post-filter, against the exact
// coverage, brute-force sample tests, and the sink contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "raster/supersample.hpp"
#include "support/capture.hpp"
#include "support/reference.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/vraster.hpp"

namespace vraster {
namespace {

using test::CoverageGrid;
using test::rasterize;

constexpr AntiAlias kAll[] = {AntiAlias::None,   AntiAlias::Analytic, AntiAlias::Exact,  AntiAlias::Ssaa2,
                              AntiAlias::Ssaa4,  AntiAlias::Ssaa8,    AntiAlias::Ssaa16, AntiAlias::Msaa4,
                              AntiAlias::Msaa8,  AntiAlias::Msaa16};
constexpr FillRule kWindingRules[] = {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative,
                                      FillRule::AbsGeq2};

Path random_polygon(std::mt19937& rng, int vertices, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Path p;
  p.move_to(u(rng), u(rng));
  for (int i = 1; i < vertices; ++i) p.line_to(u(rng), u(rng));
  p.close();
  return p;
}

double rms(const CoverageGrid& a, const CoverageGrid& b) {
  double s = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      const double d = a.at(x, y) - b.at(x, y);
      s += d * d;
    }
  }
  return std::sqrt(s / (a.width() * a.height()));
}

// Winding number at (sx, sy) by brute force over the polygon's segments: a segment counts when sy is in its
// half-open y range [top, bottom) and it crosses the sample line at or left of sx (the aliased sweep's rules).
int winding_at(const std::vector<Point>& pts, double sx, double sy) {
  int w = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point p = pts[i], q = pts[(i + 1) % pts.size()];
    if (p.y == q.y) continue;
    const Point top = p.y < q.y ? p : q, bottom = p.y < q.y ? q : p;
    if (!(top.y <= sy && sy < bottom.y)) continue;
    const double x = top.x + (sy - top.y) * ((bottom.x - top.x) / (bottom.y - top.y));
    if (x <= sx) w += q.y > p.y ? 1 : -1;
  }
  return w;
}

std::vector<Point> flat_points(const Path& path) {
  Polylines lines;
  flatten(path, Affine{}, FlattenOptions{}, lines);
  return std::vector<Point>(lines.points.begin(), lines.points.end());
}

TEST(AaNames, EveryModeHasAName) {
  for (const AntiAlias aa : kAll) {
    AntiAlias back{};
    ASSERT_TRUE(parse_anti_alias(to_string(aa), back)) << to_string(aa);
    EXPECT_EQ(back, aa);
  }
  AntiAlias out;
  EXPECT_TRUE(parse_anti_alias("ssaa-4", out));
  EXPECT_EQ(out, AntiAlias::Ssaa4);
  EXPECT_TRUE(parse_anti_alias("msaa-16", out));
  EXPECT_EQ(out, AntiAlias::Msaa16);
  // FXAA is a post-filter, not a coverage mode: only the method names know it.
  EXPECT_FALSE(parse_anti_alias("fxaa", out));
  AntiAliasMethod method;
  EXPECT_TRUE(parse_anti_alias_method("fxaa", method));
  EXPECT_EQ(method, (AntiAliasMethod{AntiAlias::None, true}));
  EXPECT_EQ(to_string(method), "fxaa");
  for (const AntiAlias aa : kAll) {
    ASSERT_TRUE(parse_anti_alias_method(to_string(aa), method)) << to_string(aa);
    EXPECT_EQ(method, (AntiAliasMethod{aa, false}));
    EXPECT_EQ(to_string(method), to_string(aa));
  }
  EXPECT_FALSE(parse_anti_alias_method("fxaa-2", method));
  EXPECT_FALSE(parse_anti_alias("ssaa-3", out));
  EXPECT_FALSE(parse_anti_alias("msaa-2", out));
}

TEST(AaPatterns, SparsePatternsAreNRooks) {
  for (const AntiAlias aa : {AntiAlias::Msaa4, AntiAlias::Msaa8, AntiAlias::Msaa16}) {
    const detail::SamplePattern p = detail::sample_pattern(aa);
    ASSERT_TRUE(p.sparse);
    std::vector<int> cols(p.permutation().begin(), p.permutation().end());
    ASSERT_EQ(static_cast<int>(cols.size()), p.grid);
    std::sort(cols.begin(), cols.end());
    for (int i = 0; i < p.grid; ++i) EXPECT_EQ(cols[i], i) << to_string(aa);
  }
}

// Convergence: on random self-intersecting polygons, the error against exact shrinks as N grows.
TEST(AaConvergence, SupersamplingErrorShrinksWithN) {
  std::mt19937 rng(1234);
  const AntiAlias ssaa[] = {AntiAlias::Ssaa2, AntiAlias::Ssaa4, AntiAlias::Ssaa8, AntiAlias::Ssaa16};
  const AntiAlias msaa[] = {AntiAlias::Msaa4, AntiAlias::Msaa8, AntiAlias::Msaa16};
  double e_ssaa[4] = {}, e_msaa[3] = {};
  for (int t = 0; t < 24; ++t) {
    const Path path = random_polygon(rng, 5 + t % 7, 0.5, 39.5);
    const FillRule rule = t % 2 ? FillRule::EvenOdd : FillRule::NonZero;
    const CoverageGrid exact = rasterize(path, rule, AntiAlias::Exact, 40, 40);
    for (int k = 0; k < 4; ++k) e_ssaa[k] += rms(rasterize(path, rule, ssaa[k], 40, 40), exact);
    for (int k = 0; k < 3; ++k) e_msaa[k] += rms(rasterize(path, rule, msaa[k], 40, 40), exact);
  }
  for (int k = 0; k + 1 < 4; ++k) EXPECT_LT(e_ssaa[k + 1], 0.7 * e_ssaa[k]) << "ssaa step " << k;
  for (int k = 0; k + 1 < 3; ++k) EXPECT_LT(e_msaa[k + 1], 0.85 * e_msaa[k]) << "msaa step " << k;
  // ssaa-16 is close: RMS of a 1/256-step estimate of the area.
  EXPECT_LT(e_ssaa[3] / 24, 0.01);
}

// none, ssaa-N, msaa-N against brute-force point-in-polygon tests at their sample positions, exactly.
TEST(AaSamples, PointSampledModesMatchBruteForceWinding) {
  std::mt19937 rng(99);
  const int W = 24, H = 20;
  for (int t = 0; t < 12; ++t) {
    const Path path = random_polygon(rng, 4 + t % 6, 0.3, 19.7);
    const std::vector<Point> pts = flat_points(path);
    for (const FillRule rule : kWindingRules) {
      // none: one sample at the pixel centre.
      {
        const CoverageGrid g = rasterize(path, rule, AntiAlias::None, W, H);
        for (int y = 0; y < H; ++y) {
          for (int x = 0; x < W; ++x) {
            const float want = test::rule_inside(rule, winding_at(pts, x + 0.5, y + 0.5)) ? 1.f : 0.f;
            ASSERT_EQ(g.at(x, y), want) << "none " << to_string(rule) << " at " << x << "," << y;
          }
        }
      }
      for (const AntiAlias aa : {AntiAlias::Ssaa2, AntiAlias::Ssaa4, AntiAlias::Msaa4, AntiAlias::Msaa8}) {
        const detail::SamplePattern p = detail::sample_pattern(aa);
        const CoverageGrid g = rasterize(path, rule, aa, W, H);
        for (int y = 0; y < H; ++y) {
          for (int x = 0; x < W; ++x) {
            int inside = 0;
            for (int j = 0; j < p.grid; ++j) {
              const double sy = y + (j + 0.5) / p.grid;
              if (p.sparse) {
                inside += test::rule_inside(rule, winding_at(pts, x + (p.permutation()[j] + 0.5) / p.grid, sy));
              } else {
                for (int i = 0; i < p.grid; ++i) inside += test::rule_inside(rule, winding_at(pts, x + (i + 0.5) / p.grid, sy));
              }
            }
            const float want = static_cast<float>(inside) / static_cast<float>(p.samples());
            ASSERT_EQ(g.at(x, y), want) << to_string(aa) << " " << to_string(rule) << " at " << x << "," << y;
          }
        }
      }
    }
  }
}

// All methods agree exactly on unions of axis-aligned rectangles with integer corners (every pixel is fully in
// or out, so every sample and every area agrees).
TEST(AaAgreement, IntegerRectanglesAreExactInEveryMode) {
  Path path;
  path.add_rect(Rect{2, 3, 17, 9});
  path.add_rect(Rect{5, 1, 9, 15});  // overlaps: winding 2 inside the overlap
  path.add_rect(Rect{-4, 12, 6, 14});  // partly left of the image
  path.add_rect(Rect{15, 14, 30, 19});  // partly right of it
  for (const FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::AbsGeq2, FillRule::NonExterior}) {
    const CoverageGrid exact = rasterize(path, rule, AntiAlias::Exact, 20, 18);
    for (const AntiAlias aa : kAll) {
      const CoverageGrid g = rasterize(path, rule, aa, 20, 18);
      EXPECT_TRUE(g.violations().empty()) << to_string(aa);
      for (int y = 0; y < 18; ++y) {
        for (int x = 0; x < 20; ++x) {
          ASSERT_EQ(g.at(x, y), exact.at(x, y)) << to_string(aa) << " " << to_string(rule) << " at " << x << "," << y;
        }
      }
    }
  }
}

// Coverage in [0, 1] and the sink contract (rows in order, x increasing, spans in range) for every mode and rule,
// with geometry partly outside the image.
TEST(AaContract, EveryModeKeepsTheSinkContract) {
  std::mt19937 rng(7);
  for (int t = 0; t < 10; ++t) {
    const Path path = random_polygon(rng, 6 + t, -10, 50);
    for (const FillRule rule : {FillRule::EvenOdd, FillRule::NonZero, FillRule::NonExterior, FillRule::AbsGeq2}) {
      for (const AntiAlias aa : kAll) {
        const CoverageGrid g = rasterize(path, rule, aa, 37, 29);
        ASSERT_TRUE(g.violations().empty()) << to_string(aa) << " " << to_string(rule) << ": " << g.violations()[0];
        for (int y = 0; y < 29; ++y) {
          for (int x = 0; x < 37; ++x) {
            ASSERT_GE(g.at(x, y), 0.f);
            ASSERT_LE(g.at(x, y), 1.f);
          }
        }
      }
    }
  }
}

// A polygon's area is kept by supersampling within the sampling error; ssaa-16 within 1/256 per pixel on average.
TEST(AaConvergence, NonExteriorWorksInSampledModes) {
  Path path;  // a pentagram: non-exterior fills the centre that even-odd leaves empty
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * 3.14159265358979 * k * 2 / 5;
    const Point q{20 + 17 * std::sin(a), 20 - 17 * std::cos(a)};
    k == 0 ? path.move_to(q) : path.line_to(q);
  }
  path.close();
  const CoverageGrid exact = rasterize(path, FillRule::NonExterior, AntiAlias::Exact, 40, 40);
  const CoverageGrid s16 = rasterize(path, FillRule::NonExterior, AntiAlias::Ssaa16, 40, 40);
  EXPECT_NEAR(s16.total(), exact.total(), 0.02 * exact.total());
  EXPECT_EQ(s16.at(20, 20), 1.f);  // the centre is filled
}

// FXAA changes only pixels next to an edge: a pixel whose 4 neighbours all equal it is never changed.
TEST(Fxaa, ChangesOnlyPixelsNearEdges) {
  std::mt19937 rng(5);
  Image image(64, 48);
  image.clear(Color{1, 1, 1, 1});
  Renderer renderer;
  for (int i = 0; i < 6; ++i) {
    const Color c{static_cast<float>(i % 3) / 2, 0.3f, static_cast<float>(i % 2), 1};
    renderer.fill(image, random_polygon(rng, 5, 1, 60), Affine{}, c, FillOptions{FillRule::EvenOdd, AntiAlias::None});
  }
  const Image before = image;
  fxaa(image);
  int changed = 0;
  auto same = [&](int x, int y, int nx, int ny) {
    nx = std::clamp(nx, 0, before.width - 1);
    ny = std::clamp(ny, 0, before.height - 1);
    return std::equal(before.pixel(x, y), before.pixel(x, y) + 4, before.pixel(nx, ny));
  };
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (std::equal(image.pixel(x, y), image.pixel(x, y) + 4, before.pixel(x, y))) continue;
      ++changed;
      const bool near_edge = !same(x, y, x - 1, y) || !same(x, y, x + 1, y) || !same(x, y, x, y - 1) || !same(x, y, x, y + 1);
      EXPECT_TRUE(near_edge) << "pixel " << x << "," << y << " changed away from any edge";
    }
  }
  EXPECT_GT(changed, 20);  // it does smooth the aliased edges
}

TEST(Fxaa, PlaneVersionStaysInRangeAndSmoothsAStaircase) {
  // A diagonal staircase in a coverage plane: FXAA moves values toward the edge average, never outside [0, 1].
  const int W = 32, H = 32;
  std::vector<float> plane(W * H, 0.f);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) plane[y * W + x] = (x + 0.5) < 0.37 * (y + 0.5) + 6 ? 1.f : 0.f;
  }
  const std::vector<float> before = plane;
  fxaa(std::span<float>(plane), W, H);
  int fractional = 0;
  for (int i = 0; i < W * H; ++i) {
    EXPECT_GE(plane[i], 0.f);
    EXPECT_LE(plane[i], 1.f);
    fractional += plane[i] > 0.02f && plane[i] < 0.98f;
    const int x = i % W, y = i / W;
    bool flat = true;
    for (const auto& [dx, dy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
      const int nx = std::clamp(x + dx, 0, W - 1), ny = std::clamp(y + dy, 0, H - 1);
      flat = flat && before[ny * W + nx] == before[i];
    }
    if (flat) {
      EXPECT_EQ(plane[i], before[i]) << x << "," << y;
    }
  }
  EXPECT_GT(fractional, H / 2);
}

// The fxaa method: aliased coverage, then fxaa() on the finished image or plane; other methods filter nothing.
TEST(Fxaa, MethodIsAliasedCoverageThenThePostFilter) {
  std::mt19937 rng(3);
  const Path path = random_polygon(rng, 7, 0.5, 29.5);
  AntiAliasMethod method;
  ASSERT_TRUE(parse_anti_alias_method("fxaa", method));
  const CoverageGrid aliased = rasterize(path, FillRule::NonZero, AntiAlias::None, 30, 30);
  const CoverageGrid drawn = rasterize(path, FillRule::NonZero, method.coverage, 30, 30);
  std::vector<float> plane(30 * 30), filtered;
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 30; ++x) {
      ASSERT_EQ(drawn.at(x, y), aliased.at(x, y));
      plane[static_cast<std::size_t>(y) * 30 + x] = aliased.at(x, y);
    }
  }
  filtered = plane;
  post_filter(method, std::span<float>(filtered), 30, 30);
  std::vector<float> reference = plane;
  fxaa(std::span<float>(reference), 30, 30);
  EXPECT_EQ(filtered, reference);
  EXPECT_NE(filtered, plane);  // an aliased polygon has edges to smooth
  std::vector<float> untouched = plane;
  post_filter(AntiAliasMethod{AntiAlias::Analytic, false}, std::span<float>(untouched), 30, 30);
  EXPECT_EQ(untouched, plane);
  // Images too.
  Image image(30, 30), reference_image(30, 30);
  image.clear(Color{1, 1, 1, 1});
  Renderer renderer;
  renderer.fill(image, path, Affine{}, Color{0, 0, 0, 1}, FillOptions{FillRule::NonZero, method.coverage});
  reference_image = image;
  post_filter(method, image);
  fxaa(reference_image);
  EXPECT_EQ(image.data, reference_image.data);
}

}  // namespace
}  // namespace vraster
