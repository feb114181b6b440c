// The hand-written AVX2 kernel (the running sum of a row of cells) must give the bits of its portable version,
// which runs where AVX2 is missing: the same picture on every machine. Each test draws with the portable kernel
// forced and without, and compares exactly. (On a machine without AVX2 both runs take the portable path and the
// comparison holds trivially.) The 8-bit source-over loops are checked against the rounding rule, and their
// hand-written AVX2 versions (a constant colour under constant coverage, a solid colour under a row of coverage)
// against the portable loops on every run length and alignment.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "paint/blend.hpp"
#include "paint/over8_avx2.hpp"
#include "raster/cells.hpp"
#include "raster/cpu.hpp"
#include "support/capture.hpp"
#include "vraster/renderer.hpp"

namespace vraster::test {
namespace {

struct PortableKernels {  // forces the portable kernels for its lifetime
  PortableKernels() { detail::portable_kernels_forced() = true; }
  ~PortableKernels() { detail::portable_kernels_forced() = false; }
};

Path random_path(std::mt19937& rng, double lo, double hi, bool curves) {
  std::uniform_real_distribution<double> coord(lo, hi);
  Path path;
  const int contours = 1 + static_cast<int>(rng() % 3);
  for (int c = 0; c < contours; ++c) {
    path.move_to(coord(rng), coord(rng));
    const int n = 3 + static_cast<int>(rng() % 10);
    for (int i = 1; i < n; ++i) {
      if (curves && rng() % 2) {
        path.cubic_to(Point{coord(rng), coord(rng)}, Point{coord(rng), coord(rng)}, Point{coord(rng), coord(rng)});
      } else {
        path.line_to(coord(rng), coord(rng));
      }
    }
    path.close();
  }
  return path;
}

constexpr FillRule kRules[] = {FillRule::EvenOdd, FillRule::NonZero, FillRule::Positive, FillRule::Negative,
                               FillRule::AbsGeq2};

TEST(SimdKernels, CoverageIsTheSameBitsWithAndWithoutAvx2) {
  std::mt19937 rng(90210);
  int compared = 0;
  for (int it = 0; it < 120; ++it) {
    // Small paths take the dense sweep, large ones (dense limit 0) the row sweep with its touched runs. One in four
    // is glyph-sized (a dense block under 24 columns, whose rows are swept whole), some over the right edge.
    const bool dense = it % 2 == 0, glyph_sized = it % 4 == 0;
    const int w = 20 + static_cast<int>(rng() % 90), h = 10 + static_cast<int>(rng() % 60);
    const double lo = glyph_sized ? w - 6.0 - static_cast<double>(rng() % 20) : -10.0;
    const double hi = glyph_sized ? lo + 2.0 + static_cast<double>(rng() % 20) : w + 10.0;
    const Path path = random_path(rng, lo, hi, it % 3 == 0);
    Polylines lines;
    flatten(path, Affine{}, FlattenOptions{}, lines);
    for (FillRule rule : kRules) {
      auto fill = [&] {
        CoverageGrid grid(w, h);
        Rasterizer r;
        if (!dense) r.set_dense_limit(0);
        r.fill(lines, rule, AntiAlias::Analytic, w, h, grid);
        return grid;
      };
      const CoverageGrid simd = fill();
      CoverageGrid portable(1, 1);
      {
        PortableKernels forced;
        portable = fill();
      }
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          ASSERT_EQ(simd.at(x, y), portable.at(x, y)) << "iteration " << it << " rule " << to_string(rule) << " pixel "
                                                      << x << "," << y;
        }
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 600);
}

TEST(SimdKernels, FilledImagesAreTheSameBitsWithAndWithoutAvx2) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0, 1);
  std::vector<std::pair<Path, Color>> scene;
  for (int i = 0; i < 60; ++i) scene.push_back({random_path(rng, -5, 133, i % 2 == 1), Color{unit(rng), unit(rng), unit(rng), unit(rng)}});
  auto draw = [&] {
    Image image(128, 96);
    image.clear(Color{0.2f, 0.4f, 0.6f, 0.8f});
    Renderer renderer;
    for (const auto& [path, color] : scene) renderer.fill(image, path, Affine{}, color, {FillRule::NonZero});
    return image;
  };
  const Image simd = draw();
  PortableKernels forced;
  const Image portable = draw();
  ASSERT_EQ(std::memcmp(simd.pixel(0, 0), portable.pixel(0, 0), 128 * 96 * 4), 0);
}

// Source-over with coverage and clip, per pixel, as docs/design.md states it (rounded to nearest each step).
std::uint8_t div255(std::uint32_t x) { return static_cast<std::uint8_t>((x + 127) / 255); }

TEST(SourceOverRuns, MatchTheRoundingRuleForEveryCase) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-0.2f, 1.2f);  // coverage products outside [0, 1] are clamped
  int runs = 0;
  for (int it = 0; it < 400; ++it) {
    const int n = static_cast<int>(rng() % 70);
    const bool src_row = rng() % 2, with_cov = rng() % 2, with_clip = rng() % 2;
    if (!with_cov && !with_clip) continue;  // the masked loops' cases
    std::vector<std::uint8_t> dst(4 * static_cast<std::size_t>(n) + 4), src(4 * static_cast<std::size_t>(n) + 4), clip(n + 1);
    std::vector<float> cov(n + 1);
    auto premultiplied = [&](std::uint8_t* p) {
      const std::uint32_t a = rng() % 256;
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(rng() % (a + 1));
      p[3] = static_cast<std::uint8_t>(a);
    };
    for (int i = 0; i < n; ++i) {
      premultiplied(&dst[4 * i]);
      premultiplied(&src[4 * i]);
      cov[i] = unit(rng);
      clip[i] = static_cast<std::uint8_t>(rng() % 256);
    }
    const float scale = it % 3 == 0 ? 1.f : unit(rng);
    const int step = src_row ? 4 : 0;
    auto run = [&] {
      std::vector<std::uint8_t> out = dst;
      detail::composite_run<std::uint8_t, CompositeOp::SourceOver>(out.data() + 4, src.data(), step,
                                                                  with_cov ? cov.data() : nullptr, scale,
                                                                  with_clip ? clip.data() : nullptr, n - 1 > 0 ? n - 1 : 0);
      return out;
    };
    const std::vector<std::uint8_t> out = run();
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint8_t* s = &src[static_cast<std::size_t>(step) * i];
      const std::uint8_t* d = &dst[4 * (i + 1)];
      const float c = (with_cov ? cov[i] : 1.f) * scale;
      const std::uint32_t k = c > 0 ? (c >= 1 ? 255 : static_cast<std::uint32_t>(c * 255.f + 0.5f)) : 0;
      const std::uint32_t m = with_clip ? clip[i] : 255;
      std::uint8_t sk[4];
      for (int ch = 0; ch < 4; ++ch) sk[ch] = div255(s[ch] * k);
      for (int ch = 0; ch < 4; ++ch) {
        const std::uint32_t r = sk[ch] + div255(d[ch] * (255u - sk[3]));
        ASSERT_EQ(out[4 * (i + 1) + ch], div255(d[ch] * (255 - m) + r * m)) << "run " << it << " pixel " << i;
      }
    }
    ASSERT_EQ(std::memcmp(out.data(), dst.data(), 4), 0);  // nothing written before the run
    ++runs;
  }
  EXPECT_GT(runs, 250);
}

// The solid compositor (every Renderer::fill on an Image) against the rounding rule, for spans and rows of every
// short length (its lone-pixel span and the kernels' masked ends) on a random background.
TEST(SourceOverKernels, SolidCompositorFollowsTheRoundingRuleOnShortRuns) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  for (int it = 0; it < 300; ++it) {
    Image image(24, 1);
    for (int x = 0; x < 24; ++x) {
      std::uint8_t* p = image.pixel(x, 0);
      p[3] = static_cast<std::uint8_t>(rng() % 256);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(rng() % (p[3] + 1u));
    }
    const Image before = image;
    const Color color{unit(rng), unit(rng), unit(rng), it % 5 == 0 ? 1.f : unit(rng)};
    SolidCompositor<std::uint8_t> compositor(image, color);
    const int x0 = static_cast<int>(rng() % 12), n = 1 + static_cast<int>(rng() % 12);
    std::vector<float> cov(static_cast<std::size_t>(n));
    for (float& c : cov) c = rng() % 4 == 0 ? 1.f : unit(rng);
    const bool as_span = it % 2 == 0;
    if (as_span) {
      compositor.span(0, x0, x0 + n, cov[0]);
    } else {
      compositor.row(0, x0, x0 + n, cov.data());
    }
    // The premultiplied colour as docs/design.md rounds it: round(255 c a), in double.
    auto level = [&](float c) {
      return static_cast<std::uint32_t>(std::lround(static_cast<double>(c) * color.a * 255.0));
    };
    const std::uint32_t premul[4] = {level(color.r), level(color.g), level(color.b), level(1.f)};
    for (int x = 0; x < 24; ++x) {
      const std::uint8_t* d = before.pixel(x, 0);
      const std::uint8_t* out = image.pixel(x, 0);
      if (x < x0 || x >= x0 + n) {
        ASSERT_EQ(std::memcmp(d, out, 4), 0) << "pixel " << x << " outside the run was written";
        continue;
      }
      const float c = as_span ? cov[0] : cov[static_cast<std::size_t>(x - x0)];
      const std::uint32_t k = static_cast<std::uint32_t>(c * 255.f + 0.5f);
      std::uint8_t s[4];
      for (int ch = 0; ch < 4; ++ch) s[ch] = div255(premul[ch] * k);
      for (int ch = 0; ch < 4; ++ch) {
        ASSERT_EQ(out[ch], static_cast<std::uint8_t>(s[ch] + div255(d[ch] * (255u - s[3]))))
            << "iteration " << it << " pixel " << x << " channel " << ch;
      }
    }
  }
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
// The hand-written loops `constant` and `solid` against the portable ones on runs of every length up to 70 at every
// position against a 32-byte boundary: premultiplied pixels, coverage out of range and NaN, odd scales, opaque
// colours over full coverage.
void expect_portable_bits(detail::Over8ConstantFn constant, detail::Over8SolidFn solid) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-0.3f, 1.3f);
  constexpr int kMax = 70;
  std::vector<std::uint32_t> base(kMax + 16), a(kMax + 16), b(kMax + 16);
  std::vector<float> cov(kMax + 16);
  const float scales[] = {1.f, 0.5f, 0.999f, 1.7f, -1.f, std::numeric_limits<float>::quiet_NaN()};
  int runs = 0;
  for (int n = 0; n <= kMax; ++n) {
    for (int offset = 0; offset < 8; ++offset) {  // every position against a 32-byte boundary
      for (auto& p : base) {  // premultiplied pixels
        const std::uint32_t al = rng() % 256;
        p = al << 24 | (rng() % (al + 1)) << 16 | (rng() % (al + 1)) << 8 | (rng() % (al + 1));
      }
      // Every other run: an opaque colour over long stretches of full coverage (and some above 1), where the AVX2
      // loop stores eight pixels without reading them.
      const bool opaque = (n + offset) % 2 == 1;
      for (auto& c : cov) {
        c = opaque ? (rng() % 8 ? (rng() % 4 ? 1.f : 1.25f) : unit(rng))
                   : (rng() % 5 == 0 ? (rng() % 2 ? 0.f : 1.f) : unit(rng));
      }
      if (n > 0) cov[static_cast<std::size_t>(offset)] = std::numeric_limits<float>::quiet_NaN();  // NaN: 0
      const std::uint32_t al = opaque ? 255 : rng() % 256;
      const std::uint32_t color = al << 24 | (rng() % (al + 1)) << 16 | (rng() % (al + 1)) << 8 | (rng() % (al + 1));
      a = base;
      b = base;
      constant(a.data() + offset, n, color);
      detail::over8_constant_portable(b.data() + offset, n, color);
      ASSERT_EQ(a, b) << "constant, n " << n << " offset " << offset;  // also: nothing outside the run written
      const float scale = opaque && rng() % 2 ? 1.f : scales[rng() % std::size(scales)];
      a = base;
      b = base;
      solid(a.data() + offset, n, cov.data() + offset, scale, color);
      detail::over8_solid_portable(b.data() + offset, n, cov.data() + offset, scale, color);
      ASSERT_EQ(a, b) << "solid, n " << n << " offset " << offset << " scale " << scale;
      ++runs;
    }
  }
  EXPECT_EQ(runs, (kMax + 1) * 8);
}
#endif

#ifdef VRASTER_HAVE_AVX2_KERNELS
// The vector loops divide by 255 as the high half of (a f + 128) * 257; scale8 does it with shifts. Every pair.
[[gnu::target("avx2")]] void expect_scale16_is_scale8() {
  for (std::uint32_t a = 0; a < 256; ++a) {
    alignas(32) std::uint16_t f[16], a16[16], out[16];
    for (std::uint32_t f0 = 0; f0 < 256; f0 += 16) {
      for (std::uint32_t i = 0; i < 16; ++i) {
        f[i] = static_cast<std::uint16_t>(f0 + i);
        a16[i] = static_cast<std::uint16_t>(a);
      }
      const __m256i r = detail::avx2::scale16(_mm256_load_si256(reinterpret_cast<const __m256i*>(a16)),
                                              _mm256_load_si256(reinterpret_cast<const __m256i*>(f)));
      _mm256_store_si256(reinterpret_cast<__m256i*>(out), r);
      for (std::uint32_t i = 0; i < 16; ++i) ASSERT_EQ(out[i], detail::scale8(a, f0 + i)) << a << " x " << f0 + i;
    }
  }
}
#endif

TEST(SourceOverKernels, Avx2ScaleRoundsAsScale8ForEveryPair) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this processor: only the portable loops run";
  expect_scale16_is_scale8();
#else
  GTEST_SKIP() << "no AVX2 kernels in this build";
#endif
}

TEST(SourceOverKernels, Avx2GivesThePortableBitsOnEveryLengthAndAlignment) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this processor: only the portable loops run";
  expect_portable_bits(&detail::over8_constant_avx2, &detail::over8_solid_avx2);
#else
  GTEST_SKIP() << "no AVX2 kernels in this build";
#endif
}

// The sixteen-pixel loops run only where the processor has AVX-512 BW and VL; elsewhere there is nothing of them
// to test.
TEST(SourceOverKernels, Avx512GivesThePortableBitsOnEveryLengthAndAlignment) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512bw") ||
      !__builtin_cpu_supports("avx512vl")) {
    GTEST_SKIP() << "no AVX-512 BW and VL on this processor: the AVX2 or portable loops run";
  }
  expect_portable_bits(&detail::over8_constant_avx512, &detail::over8_solid_avx512);
#else
  GTEST_SKIP() << "no AVX2 kernels in this build";
#endif
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
// Four pieces (lane i into rows[i]) split by split4 and added as the sweeps add them.
template <int kRow>
[[gnu::target("avx2")]] void split_into(double (&rows)[4][kRow], const double* xa, const double* xb, const double* h) {
  const detail::SplitLanes split(_mm256_load_pd(xa), _mm256_load_pd(xb), _mm256_load_pd(h));
  for (int i = 0; i < 4; ++i) split.add(i, rows[i]);
}
#endif

// accumulate_piece splits a piece into cells with branches on how many cells it crosses; the sweeps' AVX2 paths
// split four pieces at once without branches (split4) and add the numbers with accumulate_split, or take
// accumulate_long_piece past three cells. Both must add the same numbers to every cell in the same order. Only the
// sign of a zero may differ (x + 0 where the other way adds nothing), which no sum sees, so cells are compared as
// numbers. Pieces start and end on cell sides and inside cells, have zero width, and cross up to seven cells; several
// pieces go into the same cells, as the pieces of one row do, and the four lanes of a step go to different rows.
TEST(AccumulatePiece, TheSplitWithoutBranchesAddsTheSameNumbers) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this processor: only the branches run";
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr int kCells = 48, kRow = kCells + detail::kRowPadding;
  int shapes[4] = {0, 0, 0, 0};  // pieces inside one, two, three, more cells
  for (int step = 0; step < 3000; ++step) {
    double branches[4][kRow] = {}, split[4][kRow] = {};
    const int pieces = 1 + static_cast<int>(rng() % 6);
    for (int p = 0; p < pieces; ++p) {
      alignas(32) double xa[4], xb[4], h[4];
      for (int lane = 0; lane < 4; ++lane) {
        auto x = [&] {
          const double base = static_cast<double>(rng() % 40);
          switch (rng() % 4) {
            case 0: return base;                // on a cell side
            case 1: return base + 1 - 0x1p-40;  // just left of the next side
            default: return base + unit(rng);
          }
        };
        xa[lane] = x();
        const double span = rng() % 5 == 0 ? 0.0 : unit(rng) * static_cast<double>(1 + rng() % 7);
        xb[lane] = rng() % 2 ? std::min(xa[lane] + span, 44.0) : std::max(xa[lane] - span, 0.0);
        h[lane] = (unit(rng) * 2 - 1) * (rng() % 3 == 0 ? 1.0 : unit(rng));
        const int crossed =
            static_cast<int>(std::max(xa[lane], xb[lane])) - static_cast<int>(std::min(xa[lane], xb[lane]));
        ++shapes[std::min(crossed, 3)];
        detail::accumulate_piece(branches[lane], xa[lane], xb[lane], h[lane]);
      }
      split_into(split, xa, xb, h);
    }
    for (int lane = 0; lane < 4; ++lane) {
      for (int i = 0; i < kRow; ++i) {
        ASSERT_EQ(branches[lane][i], split[lane][i]) << "step " << step << " lane " << lane << " cell " << i;
      }
    }
  }
  for (int count : shapes) EXPECT_GT(count, 2000);
#else
  GTEST_SKIP() << "no AVX2 kernels in this build";
#endif
}

// The AVX2 row sweep adds a long piece's whole cells four at a time (add_whole_cells_avx2): each whole cell must get
// + half twice, as the loop adds it, not + 2 half (a different number where the cell already holds something). Rows
// of pieces crossing up to twelve cells, on top of each other, in rows with the sweep's padding.
TEST(AccumulatePiece, Avx2WholeCellsAddTheSameNumbers) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this processor: only the portable loop runs";
  std::mt19937 rng(2027);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr int kCells = 64, kRow = kCells + detail::kRowPadding;
  int long_pieces = 0;
  for (int row = 0; row < 3000; ++row) {
    double loop[kRow] = {}, avx2[kRow] = {};
    const int pieces = 1 + static_cast<int>(rng() % 6);
    for (int p = 0; p < pieces; ++p) {
      const double xa = static_cast<double>(rng() % 50) + (rng() % 3 == 0 ? 0.0 : unit(rng));
      const double span = unit(rng) * static_cast<double>(1 + rng() % 12);
      const double xb = rng() % 2 ? std::min(xa + span, 60.0) : std::max(xa - span, 0.0);
      const double h = (unit(rng) * 2 - 1) * unit(rng);
      long_pieces += static_cast<int>(std::max(xa, xb)) - static_cast<int>(std::min(xa, xb)) > 2;
      detail::accumulate_piece<false>(loop, xa, xb, h);
      detail::accumulate_piece<true>(avx2, xa, xb, h);
    }
    for (int i = 0; i < kRow; ++i) {
      ASSERT_EQ(loop[i], avx2[i]) << "row " << row << " cell " << i;
    }
  }
  EXPECT_GT(long_pieces, 3000);
#else
  GTEST_SKIP() << "no AVX2 kernels in this build";
#endif
}

// trim_zeros passes zeros four at a time where it can: it must give the bounds of a one-by-one scan on every pattern
// of zeros, with -0 counting as zero and NaN as nonzero, from every start on the sweep's block grid.
TEST(TrimZeros, GivesTheBoundsOfAOneByOneScanOnEveryPatternOfZeros) {
  constexpr int kLength = 16;
  const float nonzero_values[] = {0.5f, 1e-30f, std::numeric_limits<float>::quiet_NaN()};
  int trimmed_both_ends = 0;
  for (int pattern = 0; pattern < (1 << kLength); ++pattern) {
    float cov[kLength + 4];
    for (int i = 0; i < kLength + 4; ++i) {
      cov[i] = (pattern >> (i % kLength)) & 1 ? nonzero_values[(i + pattern) % 3] : (i % 2 ? -0.0f : 0.0f);
    }
    for (int a0 = 0; a0 <= 8; a0 += 4) {
      for (int b0 = a0; b0 <= kLength; ++b0) {
        int ref_a = a0, ref_b = b0;
        while (ref_a < ref_b && cov[ref_a] == 0) ++ref_a;
        while (ref_b > ref_a && cov[ref_b - 1] == 0) --ref_b;
        int a = a0, b = b0;
        detail::trim_zeros(cov, a, b);
        if (ref_b > ref_a) {
          ASSERT_EQ(a, ref_a) << "pattern " << pattern << " [" << a0 << ", " << b0 << ")";
          ASSERT_EQ(b, ref_b) << "pattern " << pattern << " [" << a0 << ", " << b0 << ")";
          trimmed_both_ends += ref_a >= a0 + 4 && ref_b <= b0 - 4;
        } else {
          ASSERT_LE(b, a) << "pattern " << pattern << " [" << a0 << ", " << b0 << ") is all zeros";
        }
      }
    }
  }
  EXPECT_GT(trimmed_both_ends, 100);  // the four-at-a-time steps ran at both ends
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
template <FillRule R>
[[gnu::target("avx2")]] float sweep_narrow_row_avx2(int x_lo, int x_hi, double* acc, float* cov,
                                                    std::uint32_t& nonzero) {
  return detail::sweep_narrow_row<R, true>(x_lo, x_hi, acc, cov, nonzero);
}
#endif

// A narrow row's sweep reports which of its pixels have coverage (the row is trimmed to them): bit i must be set
// exactly where cov[i] != 0, for i below the row's length, with and without AVX2, and both must give the same
// coverage and leave the cells zero.
TEST(NarrowRowSweep, NonzeroBitsAreThePixelsWithCoverage) {
  std::mt19937 rng(2028);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr int kRow = 64 + detail::kRowPadding;
  int partly_zero = 0;
  for (int row = 0; row < 4000; ++row) {
    const int x_lo = static_cast<int>(rng() % 16), n = 1 + static_cast<int>(rng() % detail::kNarrowRowCells);
    const int x_hi = x_lo + n - 1;
    double portable[kRow] = {}, fast[kRow] = {};
    const int pieces = 1 + static_cast<int>(rng() % 4);
    // Pieces mostly in pairs of opposite winding (a closed shape's two sides), some alone (a shape that goes on
    // right of the image, whose coverage goes on past the row's last cell), kept inside [x_lo, x_hi - 1] so that
    // the cells they touch stay within the row.
    const bool paired = rng() % 4 != 0;
    for (int p = 0; p < pieces; ++p) {
      const double h = (rng() % 2 ? 1.0 : -1.0) * (rng() % 3 == 0 ? 1.0 : unit(rng));
      for (int side = 0; side < (paired ? 2 : 1); ++side) {
        const double sign = side == 0 ? 1.0 : -1.0;
        const double xa = x_lo + unit(rng) * (n - 1), xb = x_lo + unit(rng) * (n - 1);
        detail::accumulate_piece(portable, xa, xb, sign * h);
        detail::accumulate_piece(fast, xa, xb, sign * h);
      }
    }
    float cov[detail::kNarrowRowCoverage + 4], cov_fast[detail::kNarrowRowCoverage + 4];
    std::uint32_t bits = 0, bits_fast = 0;
    const float right = detail::sweep_narrow_row<FillRule::EvenOdd>(x_lo, x_hi, portable, cov, bits);
    for (int i = 0; i < 32; ++i) {
      ASSERT_EQ((bits >> i) & 1, i < n && cov[i] != 0 ? 1u : 0u) << "row " << row << " pixel " << i;
    }
    partly_zero += bits != 0 && bits != (n < 32 ? (1u << n) - 1 : ~0u);
    for (const double cell : portable) ASSERT_EQ(cell, 0.0);
#ifdef VRASTER_HAVE_AVX2_KERNELS
    if (__builtin_cpu_supports("avx2")) {
      const float right_fast = sweep_narrow_row_avx2<FillRule::EvenOdd>(x_lo, x_hi, fast, cov_fast, bits_fast);
      ASSERT_EQ(bits_fast, bits) << "row " << row;
      ASSERT_EQ(right_fast, right) << "row " << row;
      for (int i = 0; i < n; ++i) ASSERT_EQ(cov_fast[i], cov[i]) << "row " << row << " pixel " << i;
      for (const double cell : fast) ASSERT_EQ(cell, 0.0);
    }
#endif
  }
  EXPECT_GT(partly_zero, 1000);
}

// Coverage within kSnap of 0 or 1 is snapped to it. The AVX2 block snaps only towards 0 in doubles and leaves the
// snap to 1 to the conversion to float (the floats below 1 are 2^-24 apart); both must give snapped()'s floats and
// the same nonzero bits for sums at and around both thresholds, under every rule (EvenOdd folds sums near 2 and 3
// onto coverage near 0 and 1).
TEST(NarrowRowSweep, CoverageNearZeroAndOneIsSnappedAlikeWithAndWithoutAvx2) {
  const double snap = detail::kSnap;
  std::vector<double> sums;
  for (const double base : {0.0, 1.0, 2.0, 3.0, -1.0, -2.0}) {
    for (const double off : {0.0, snap / 4, snap / 2, snap * 0.999, snap, snap * 1.001, 2 * snap, 0x1p-30, 0x1p-26,
                             0x1p-25, 0x1p-24, 0x1p-20}) {
      sums.push_back(base + off);
      sums.push_back(base - off);
    }
  }
  int compared = 0;
  auto check = [&](auto rule) {
    constexpr FillRule R = decltype(rule)::value;
    for (const double s : sums) {
      // A narrow row of four cells whose running sums are 0.25 s, 0.5 s, 0.75 s and s (a quarter of s per cell).
      double portable[4 + detail::kRowPadding] = {}, fast[4 + detail::kRowPadding] = {};
      for (int i = 0; i < 4; ++i) portable[i] = fast[i] = s / 4;
      float cov[detail::kNarrowRowCoverage + 4] = {}, cov_fast[detail::kNarrowRowCoverage + 4] = {};
      std::uint32_t bits = 0, bits_fast = 0;
      detail::sweep_narrow_row<R>(0, 3, portable, cov, bits);
      const double q = s / 4;
      const double prefix[4] = {q, q + q, (q + q) + q, (q + q) + (q + q)};  // sweep_block_scalar's order
      for (int i = 0; i < 4; ++i) {
        ASSERT_EQ(cov[i], detail::coverage_of<R>(prefix[i])) << to_string(R) << " sum " << s << " cell " << i;
      }
#ifdef VRASTER_HAVE_AVX2_KERNELS
      if (__builtin_cpu_supports("avx2")) {
        sweep_narrow_row_avx2<R>(0, 3, fast, cov_fast, bits_fast);
        ASSERT_EQ(bits_fast, bits) << to_string(R) << " sum " << s;
        for (int i = 0; i < 4; ++i) ASSERT_EQ(cov_fast[i], cov[i]) << to_string(R) << " sum " << s << " cell " << i;
      }
#endif
      ++compared;
    }
  };
  for (FillRule rule : kRules) detail::with_rule(rule, check);
  EXPECT_EQ(compared, static_cast<int>(5 * sums.size()));
}

}  // namespace
}  // namespace vraster::test
