// Rasterizer::fill_mask (8-bit masks for small analytic fills) against the edge-table row sweep, rounded to bytes
// the way the 8-bit compositor rounds. Tolerance: one level (the mask sums its cells in float, the row sweep in
// double, so a pixel within ~1e-6 of a rounding boundary may land on the other side). Also the properties the
// rasterizer promises: every byte written, integer translation, contour reversal, rule symmetry, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "raster/cpu.hpp"
#include "support/capture.hpp"
#include "vraster/error.hpp"

namespace vraster::test {
namespace {

constexpr FillRule kRules[] = {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative,
                               FillRule::AbsGeq2, FillRule::NonExterior};

std::uint8_t to_byte(float coverage) {
  return static_cast<std::uint8_t>(static_cast<std::uint32_t>(coverage * 255.f + 0.5f));
}

// The row sweep (dense path off) as bytes.
std::vector<std::uint8_t> row_sweep_bytes(const Polylines& lines, FillRule rule, int w, int h) {
  CoverageGrid grid(w, h);
  Rasterizer r;
  r.set_dense_limit(0);
  r.fill(lines, rule, AntiAlias::Analytic, w, h, grid);
  EXPECT_TRUE(grid.violations().empty());
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) out[static_cast<std::size_t>(y) * w + x] = to_byte(grid.at(x, y));
  }
  return out;
}

// fill_mask into a mask pre-filled with garbage, so a byte the mask path forgets to write shows up.
std::vector<std::uint8_t> mask_bytes(Rasterizer& r, const Polylines& lines, FillRule rule, int w, int h) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h, 0xA5);
  r.fill_mask(lines, rule, w, h, out.data(), w);
  return out;
}

Polylines flattened(const Path& path, const Affine& m = {}) {
  Polylines lines;
  flatten(path, m, FlattenOptions{}, lines);
  return lines;
}

Path random_polygon(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> coord(lo, hi);
  Path path;
  const int contours = 1 + static_cast<int>(rng() % 3);
  for (int c = 0; c < contours; ++c) {
    const int n = 3 + static_cast<int>(rng() % 12);
    path.move_to(coord(rng), coord(rng));
    for (int i = 1; i < n; ++i) {
      if (rng() % 3 == 0) {
        path.quad_to({coord(rng), coord(rng)}, {coord(rng), coord(rng)});
      } else {
        path.line_to(coord(rng), coord(rng));
      }
    }
    path.close();
  }
  return path;
}

// Compares fill_mask with the row sweep pixel by pixel; returns the largest difference.
int max_difference(Rasterizer& r, const Polylines& lines, FillRule rule, int w, int h) {
  const auto mask = mask_bytes(r, lines, rule, w, h);
  const auto rows = row_sweep_bytes(lines, rule, w, h);
  int worst = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) worst = std::max(worst, std::abs(mask[i] - rows[i]));
  return worst;
}

TEST(MaskFill, MatchesTheRowSweepWithinOneLevelInsideTheMask) {
  // Polygons with curves entirely inside the mask (the fast path), widths on both sides of the 8-cell blocks.
  std::mt19937 rng(2024);
  Rasterizer r;
  int compared = 0;
  for (int it = 0; it < 300; ++it) {
    const int w = 1 + static_cast<int>(rng() % 40), h = 1 + static_cast<int>(rng() % 30);
    const Path path = random_polygon(rng, 0, std::min(w, h));
    const Polylines lines = flattened(path, Affine::scale(static_cast<double>(w) / std::min(w, h),
                                                          static_cast<double>(h) / std::min(w, h)));
    for (FillRule rule : kRules) {
      ASSERT_LE(max_difference(r, lines, rule, w, h), 1) << "iteration " << it << " rule " << to_string(rule);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 1800);
}

// The row pass in AVX2 (where the processor has it) adds in the SSE2 pass's order: the same bytes, on every rule and
// width (the steps of eight, the tail, the cells past the width).
TEST(MaskFill, TheAvx2RowPassGivesTheSseBytes) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this processor: only the SSE2 row pass runs";
  std::mt19937 rng(23);
  Rasterizer r;
  int compared = 0;
  for (int it = 0; it < 300; ++it) {
    const int w = 1 + static_cast<int>(rng() % 70), h = 1 + static_cast<int>(rng() % 40);
    const Polylines lines = flattened(random_polygon(rng, 0, std::min(w, h)));
    for (FillRule rule : kRules) {
      if (rule == FillRule::NonExterior) continue;  // takes the general sweep
      const std::vector<std::uint8_t> avx2 = mask_bytes(r, lines, rule, w, h);
      detail::portable_kernels_forced() = true;
      const std::vector<std::uint8_t> sse = mask_bytes(r, lines, rule, w, h);
      detail::portable_kernels_forced() = false;
      ASSERT_EQ(avx2, sse) << "iteration " << it << " rule " << to_string(rule) << " size " << w << "x" << h;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 300 * 5);
#else
  GTEST_SKIP() << "no AVX2 kernels in this build";
#endif
}

TEST(MaskFill, MatchesTheRowSweepForPathsReachingOutsideTheMask) {
  // Cut by every border, left of the mask (winding kept), right of it (winding holds to the row's end).
  std::mt19937 rng(77);
  Rasterizer r;
  for (int it = 0; it < 200; ++it) {
    const int w = 4 + static_cast<int>(rng() % 30), h = 4 + static_cast<int>(rng() % 30);
    const Polylines lines = flattened(random_polygon(rng, -12, 45));
    for (FillRule rule : kRules) {
      ASSERT_LE(max_difference(r, lines, rule, w, h), 1) << "iteration " << it << " rule " << to_string(rule);
    }
  }
}

TEST(MaskFill, ContoursWithAnInfiniteOrNaNPointAreLeftOutAsTheRowSweepLeavesThem) {
  // The bounds pass must notice a bad point wherever it sits in the list (even or odd place, last), or the mask
  // path would walk it. A square contour stays and is drawn; the contour holding the bad point is dropped.
  const double bad_values[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()};
  Rasterizer r;
  for (const double bad : bad_values) {
    for (int place = 0; place < 5; ++place) {
      for (const bool in_x : {true, false}) {
        Polylines lines;
        lines.points = {{1.5, 1.5}, {6.5, 1.5}, {6.5, 6.5}, {1.5, 6.5}};  // the square
        lines.ends.push_back(4);
        lines.closed.push_back(1);
        std::vector<Point> other = {{2, 2}, {7, 3}, {5, 7}, {3, 6}, {2, 5}};
        (in_x ? other[static_cast<std::size_t>(place)].x : other[static_cast<std::size_t>(place)].y) = bad;
        lines.points.insert(lines.points.end(), other.begin(), other.end());
        lines.ends.push_back(static_cast<std::uint32_t>(lines.points.size()));
        lines.closed.push_back(1);
        const auto mask = mask_bytes(r, lines, FillRule::NonZero, 8, 8);
        EXPECT_EQ(mask[4 * 8 + 4], 255) << "place " << place;  // inside the square
        EXPECT_EQ(mask[0], 0) << "place " << place;
        EXPECT_LE(max_difference(r, lines, FillRule::NonZero, 8, 8), 1) << "place " << place;
      }
    }
  }
}

TEST(MaskFill, HandMadeRectangleHasTheExactAreas) {
  Path path;
  path.add_rect({1.5, 0.25, 3, 2});
  Rasterizer r;
  const auto mask = mask_bytes(r, flattened(path), FillRule::NonZero, 4, 3);
  const std::vector<int> expected = {0, 96, 191, 0,    // row 0: 0.75 high; pixel 1 half wide
                                     0, 128, 255, 0,   // row 1
                                     0, 0, 0, 0};      // row 2: untouched, but written
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(mask[i], expected[i]) << "pixel " << i;
}

TEST(MaskFill, WritesEveryByteOfTheMaskAndNothingPastTheWidth) {
  // A stride wider than the mask: the bytes between width and stride belong to the caller.
  Path path;
  path.add_circle({10, 6}, 4.3);
  const Polylines lines = flattened(path);
  Rasterizer r;
  for (int w : {15, 16, 17, 23, 24, 25}) {
    const int h = 13, stride = w + 5;
    std::vector<std::uint8_t> mask(static_cast<std::size_t>(stride) * h, 0xA5);
    r.fill_mask(lines, FillRule::NonZero, w, h, mask.data(), stride);
    const auto rows = row_sweep_bytes(lines, FillRule::NonZero, w, h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < stride; ++x) {
        const int v = mask[static_cast<std::size_t>(y) * stride + x];
        if (x >= w) {
          EXPECT_EQ(v, 0xA5) << "padding " << x << "," << y << " width " << w;
        } else {
          EXPECT_LE(std::abs(v - rows[static_cast<std::size_t>(y) * w + x]), 1) << x << "," << y << " width " << w;
        }
      }
    }
  }
}

TEST(MaskFill, EmptyPathsAndEmptyMasks) {
  Rasterizer r;
  const auto mask = mask_bytes(r, Polylines{}, FillRule::NonZero, 5, 4);
  EXPECT_TRUE(std::all_of(mask.begin(), mask.end(), [](std::uint8_t v) { return v == 0; }));
  std::uint8_t untouched = 7;
  Path path;
  path.add_rect({0, 0, 3, 3});
  r.fill_mask(flattened(path), FillRule::NonZero, 0, 4, &untouched, 0);
  r.fill_mask(flattened(path), FillRule::NonZero, 4, 0, &untouched, 4);
  EXPECT_EQ(untouched, 7);
}

TEST(MaskFill, BadArgumentsThrow) {
  Path path;
  path.add_rect({0, 0, 3, 3});
  Rasterizer r;
  std::vector<std::uint8_t> mask(16);
  EXPECT_THROW(r.fill_mask(flattened(path), FillRule::NonZero, 4, 4, nullptr, 4), Error);
  EXPECT_THROW(r.fill_mask(flattened(path), FillRule::NonZero, 4, 4, mask.data(), 3), Error);
}

TEST(MaskFill, IntegerTranslationMovesTheMaskWithinOneLevel) {
  std::mt19937 rng(9);
  Rasterizer r;
  const int w = 40, h = 36;
  for (int it = 0; it < 60; ++it) {
    const Path path = random_polygon(rng, 0.0, 20.0);
    const int dx = 1 + static_cast<int>(rng() % 15), dy = 1 + static_cast<int>(rng() % 13);
    for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
      const auto a = mask_bytes(r, flattened(path), rule, w, h);
      const auto b = mask_bytes(r, flattened(path, Affine::translate(dx, dy)), rule, w, h);
      for (int y = 0; y + dy < h; ++y) {
        for (int x = 0; x + dx < w; ++x) {
          ASSERT_LE(std::abs(a[y * w + x] - b[(y + dy) * w + x + dx]), 1)
              << "iteration " << it << " pixel " << x << "," << y << " shift " << dx << "," << dy;
        }
      }
    }
  }
}

TEST(MaskFill, ReversingEveryContourSwapsPositiveAndNegativeAndKeepsTheSymmetricRules) {
  // Reversal negates every cell's contributions exactly, but adds them in another order, so float round-off may
  // move a pixel that sits on a rounding boundary by one level; no more, and rarely.
  std::mt19937 rng(31);
  Rasterizer r;
  const int w = 27, h = 22;
  long differing = 0, pixels = 0;
  const auto compare = [&](const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int it,
                           FillRule rule) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_LE(std::abs(a[i] - b[i]), 1) << "iteration " << it << " rule " << to_string(rule) << " pixel " << i;
      differing += a[i] != b[i];
    }
    pixels += static_cast<long>(a.size());
  };
  for (int it = 0; it < 80; ++it) {
    const Polylines lines = flattened(random_polygon(rng, 0.0, 22.0));
    Polylines reversed = lines;
    for (std::size_t k = 0; k < reversed.contour_count(); ++k) {
      std::reverse(reversed.points.begin() + reversed.start(k), reversed.points.begin() + reversed.ends[k]);
    }
    for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd, FillRule::AbsGeq2}) {
      compare(mask_bytes(r, lines, rule, w, h), mask_bytes(r, reversed, rule, w, h), it, rule);
    }
    compare(mask_bytes(r, lines, FillRule::Positive, w, h), mask_bytes(r, reversed, FillRule::Negative, w, h), it,
            FillRule::Positive);
  }
  EXPECT_LE(differing, pixels / 1000) << differing << " of " << pixels << " pixels differ";
}

TEST(MaskFill, PointsARoundOffOutsideTheMaskAreTakenAsOnItsBorder) {
  // A glyph's mask is computed from the same points its polylines come from; round-off may put a point 1e-12
  // outside. The result must be the border fill's.
  Path on_border, outside;
  on_border.add_rect({0, 0, 6, 5});
  outside.add_rect({-1e-12, -1e-12, 6 + 1e-12, 5 + 1e-12});
  Rasterizer r;
  const auto a = mask_bytes(r, flattened(on_border), FillRule::NonZero, 6, 5);
  const auto b = mask_bytes(r, flattened(outside), FillRule::NonZero, 6, 5);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(std::all_of(a.begin(), a.end(), [](std::uint8_t v) { return v == 255; }));
}

TEST(MaskFill, ManyOverlappingContoursFoldUnderEvenOddAndClampUnderTheOthers) {
  // Seven nested squares of the same orientation: pixel (i, i) has winding i + 1 (up to 7).
  Path whole, shifted;
  for (int k = 0; k < 7; ++k) whole.add_rect({1.0 * k, 1.0 * k, 16.0 - k, 16.0 - k});
  for (int k = 0; k < 7; ++k) shifted.add_rect({k + 0.3, k + 0.3, 15.3 - k, 15.3 - k});
  Rasterizer r;
  for (const Path* path : {&whole, &shifted}) {
    for (FillRule rule : kRules) EXPECT_LE(max_difference(r, flattened(*path), rule, 16, 16), 1) << to_string(rule);
  }
  const auto even_odd = mask_bytes(r, flattened(whole), FillRule::EvenOdd, 16, 16);
  const auto abs_geq2 = mask_bytes(r, flattened(whole), FillRule::AbsGeq2, 16, 16);
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(even_odd[i * 16 + i], i % 2 == 0 ? 255 : 0) << "winding " << i + 1;
    EXPECT_EQ(abs_geq2[i * 16 + i], i >= 1 ? 255 : 0) << "winding " << i + 1;
  }
}

TEST(MaskFill, LargeMasksTakeTheGeneralSweepWithTheSameResult) {
  // More cells than kMaskBlockLimit: the general sweep writes the bytes.
  const int w = 1100, h = 1000;
  ASSERT_GT(static_cast<std::int64_t>(w) * h, Rasterizer::kMaskBlockLimit);
  Path path;
  path.add_circle({550.3, 500.7}, 480.2);
  const Polylines lines = flattened(path);
  Rasterizer r;
  EXPECT_LE(max_difference(r, lines, FillRule::NonZero, w, h), 1);
}

}  // namespace
}  // namespace vraster::test
