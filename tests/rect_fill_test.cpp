// The axis-aligned rectangle fast path (src/raster/rect.cpp) against the general sweeps on seeded random rectangles:
// fractional and whole-pixel edges, partly or wholly outside the image, both orientations, any starting corner,
// under transforms that keep them axis-aligned, for every anti-aliasing mode and fill rule. The fast path repeats
// the sweeps' arithmetic in double cells, so coverage must match the sweeps in double cells bit for bit (not just to
// round-off), and so must 8- and 16-bit pixels drawn through the compositor (whose span and row paths quantize
// coverage the same way). The sweeps' fixed-point cells (the default for fills of few edges) stay within their
// bound of it.
#include <gtest/gtest.h>

#include <random>

#include "raster/fixed_cells.hpp"
#include "raster/rect.hpp"
#include "support/capture.hpp"
#include "vraster/composite.hpp"

namespace vraster::test {
namespace {

constexpr AntiAlias kModes[] = {AntiAlias::None,   AntiAlias::Analytic, AntiAlias::Exact,  AntiAlias::Ssaa2,
                                AntiAlias::Ssaa4,  AntiAlias::Ssaa8,    AntiAlias::Ssaa16, AntiAlias::Msaa4,
                                AntiAlias::Msaa8,  AntiAlias::Msaa16};
constexpr FillRule kRules[] = {FillRule::EvenOdd,  FillRule::NonZero, FillRule::NonExterior,
                               FillRule::Positive, FillRule::Negative, FillRule::AbsGeq2};

// A rectangle as a path with a random starting corner, orientation and (sometimes) an explicit closing point.
Path random_rect_path(std::mt19937& rng, double x0, double y0, double x1, double y1) {
  const Point corners[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  const int start = static_cast<int>(rng() % 4);
  const int step = rng() % 2 ? 1 : 3;
  Path p;
  p.move_to(corners[start]);
  for (int i = 1; i < 4; ++i) p.line_to(corners[(start + i * step) % 4]);
  if (rng() % 3 == 0) p.line_to(corners[start]);
  p.close();
  return p;
}

// A coordinate: whole pixel, quarter pixel or arbitrary, anywhere from well left of the image to well right of it.
double random_coord(std::mt19937& rng, int extent) {
  std::uniform_real_distribution<double> u(-0.3 * extent, 1.3 * extent);
  const double v = u(rng);
  switch (rng() % 3) {
    case 0: return std::round(v);
    case 1: return std::round(v * 4) / 4;
    default: return v;
  }
}

// Transforms that keep a rectangle axis-aligned: scale, translate, quarter turns, mirrors.
Affine random_axis_transform(std::mt19937& rng) {
  std::uniform_real_distribution<double> s(0.5, 2.0), t(-20, 20);
  switch (rng() % 4) {
    case 0: return Affine{};
    case 1: return Affine::translate(t(rng), t(rng)) * Affine::scale(s(rng), s(rng));
    case 2: return Affine{0, 1, -1, 0, 40, t(rng)};  // a quarter turn
    default: return Affine{-s(rng), 0, 0, s(rng), 60, t(rng)};  // mirrored
  }
}

// shortcut false: the general sweeps, in double cells unless fixed_cells.
CoverageGrid coverage(const Polylines& lines, FillRule rule, AntiAlias aa, int w, int h, bool shortcut,
                      bool fixed_cells = false) {
  CoverageGrid grid(w, h);
  Rasterizer r;
  r.set_rect_shortcut(shortcut);
  r.set_fixed_cells(fixed_cells);
  r.fill(lines, rule, aa, w, h, grid);
  EXPECT_TRUE(grid.violations().empty()) << grid.violations().front();
  return grid;
}

TEST(RectFill, MatchesTheSweepsBitForBitOnRandomRectangles) {
  std::mt19937 rng(1313);
  int compared = 0;
  for (int it = 0; it < 150; ++it) {
    // Small images take the dense sweep, larger ones the edge-table sweep: both are the reference.
    const bool large = it % 3 == 0;
    const int w = large ? 150 + static_cast<int>(rng() % 100) : 10 + static_cast<int>(rng() % 40);
    const int h = large ? 100 + static_cast<int>(rng() % 80) : 10 + static_cast<int>(rng() % 40);
    const double x0 = random_coord(rng, w), x1 = random_coord(rng, w), y0 = random_coord(rng, h),
                 y1 = random_coord(rng, h);
    if (x0 == x1 || y0 == y1) continue;
    const Path path = random_rect_path(rng, x0, y0, x1, y1);
    Polylines lines;
    FlattenOptions options;
    flatten(path, random_axis_transform(rng), options, lines);
    for (AntiAlias aa : kModes) {
      for (FillRule rule : kRules) {
        const CoverageGrid fast = coverage(lines, rule, aa, w, h, true);
        const CoverageGrid sweep = coverage(lines, rule, aa, w, h, false);
        const CoverageGrid fixed = coverage(lines, rule, aa, w, h, false, true);
        for (int y = 0; y < h; ++y) {
          for (int x = 0; x < w; ++x) {
            ASSERT_EQ(fast.at(x, y), sweep.at(x, y))
                << "iteration " << it << " " << to_string(aa) << " " << to_string(rule) << " pixel " << x << "," << y
                << " rect " << x0 << "," << y0 << " - " << x1 << "," << y1;
            ASSERT_NEAR(fast.at(x, y), fixed.at(x, y), detail::kFixedCellsError) << "iteration " << it;
          }
        }
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 8000);
}

// Pixels through the compositor (8 and 16 bits, translucent and opaque colours): the fast path sends the inside
// as spans where the sweep sent rows; both must round alike.
template <class T>
void expect_same_pixels(std::uint32_t seed) {
  std::mt19937 rng(seed);
  int drawn = 0;  // iterations that changed a pixel (the comparison is not vacuous)
  for (int it = 0; it < 60; ++it) {
    const int w = 20 + static_cast<int>(rng() % 200), h = 20 + static_cast<int>(rng() % 60);
    const double x0 = random_coord(rng, w), x1 = random_coord(rng, w), y0 = random_coord(rng, h),
                 y1 = random_coord(rng, h);
    const Path path = random_rect_path(rng, x0, y0, x1, y1);
    const AntiAlias aa = kModes[rng() % std::size(kModes)];
    const FillRule rule = kRules[rng() % std::size(kRules)];
    const Color color{0.2f, 0.7f, 0.4f, rng() % 2 ? 1.0f : 0.6f};
    BasicImage<T> fast(w, h), sweep(w, h);
    for (BasicImage<T>* image : {&fast, &sweep}) {
      std::fill(image->data.begin(), image->data.end(), static_cast<T>(BasicImage<T>::kMax / 3));
      Renderer renderer;
      renderer.rasterizer().set_rect_shortcut(image == &fast);
      renderer.rasterizer().set_fixed_cells(false);
      Compositor<T> comp;
      comp.set(ImageView<T>::of(*image), Paint::solid(color), Affine{}, CompositeOp::SourceOver, 0.9f);
      FillOptions options;
      options.rule = rule;
      options.aa = aa;
      renderer.fill(path, Affine{}, options, w, h, comp);
      // And the solid compositor of Renderer's convenience fill.
      renderer.fill(*image, path, Affine::translate(0.5, 0.25), color, options);
    }
    ASSERT_EQ(fast.data, sweep.data) << "iteration " << it << " " << to_string(aa) << " " << to_string(rule);
    drawn += std::any_of(fast.data.begin(), fast.data.end(), [](T v) { return v != BasicImage<T>::kMax / 3; });
  }
  EXPECT_GT(drawn, 20);
}

TEST(RectFill, SamePixelsAsTheSweepIn8Bits) { expect_same_pixels<std::uint8_t>(77); }
TEST(RectFill, SamePixelsAsTheSweepIn16Bits) { expect_same_pixels<std::uint16_t>(78); }

TEST(RectFill, InsideRowsAreOneFullSpan) {
  // A full-frame opaque fill: one span of coverage 1 per row, nothing else (what makes it a store).
  struct Calls final : CoverageSink {
    int spans = 0, rows = 0;
    bool all_full = true;
    void span(int, int x0, int x1, float c) override {
      ++spans;
      all_full = all_full && x0 == 0 && x1 == 64 && c == 1.0f;
    }
    void row(int, int, int, const float*) override { ++rows; }
  } calls;
  Path p;
  p.add_rect({0, 0, 64, 32});
  Polylines lines;
  flatten(p, Affine{}, FlattenOptions{}, lines);
  Rasterizer r;
  r.fill(lines, FillRule::NonZero, AntiAlias::Analytic, 64, 32, calls);
  EXPECT_EQ(calls.spans, 32);
  EXPECT_EQ(calls.rows, 0);
  EXPECT_TRUE(calls.all_full);
}

TEST(RectFill, OnlyOneAxisAlignedRectangleTakesIt) {
  // Not rectangles: a rotated square, two rectangles, a degenerate one. They must still draw (through the sweep).
  Path rotated;
  rotated.move_to(10, 0);
  rotated.line_to(20, 10);
  rotated.line_to(10, 20);
  rotated.line_to(0, 10);
  rotated.close();
  Path two;
  two.add_rect({1, 1, 5, 5});
  two.add_rect({8, 8, 12, 12});
  for (const Path* p : {&rotated, &two}) {
    Polylines lines;
    flatten(*p, Affine{}, FlattenOptions{}, lines);
    Rect box;
    int winding = 0;
    EXPECT_FALSE(detail::axis_aligned_rectangle(lines, box, winding));
    const CoverageGrid fast = coverage(lines, FillRule::NonZero, AntiAlias::Analytic, 24, 24, true);
    const CoverageGrid sweep = coverage(lines, FillRule::NonZero, AntiAlias::Analytic, 24, 24, false);
    EXPECT_EQ(fast.total(), sweep.total());
  }
}

}  // namespace
}  // namespace vraster::test
