// SolidCompositor (include/vraster/renderer.hpp) against a slow per-pixel reference written from the source-over
// formula, through its public interface only (construct with an image and a colour, hand it spans and rows).
//
// Source-over of a premultiplied source S (alpha Sa) with coverage c onto a premultiplied destination D:
//     out = c S + (1 - c Sa) D            (Porter and Duff, 1984)
// In 8 bits the compositor claims each step exactly rounded to nearest (src/paint/compositor.cpp):
//     coverage  c8 = round(255 c)                       colour   P  = round(255 a r), Pa = round(255 a)
//     source    s  = round(P c8 / 255)                  (s = P when c8 = 255)
//     result    o  = s + round(D (255 - sa) / 255)
// Every product x y / 255 of 8-bit integers is at least 1/510 from a half, so "round to nearest" has one answer.
// The tests go through every input pair of each step (65536 each) and random quadruples of all four inputs.
// 16 bits claims the same steps with 65535, coverage rounded with lround; it is checked on a grid and random inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "vraster/renderer.hpp"

namespace vraster {
namespace {

// round(x y / m) for integers, to nearest (no ties occur for m odd; computed as floor((2 x y + m) / (2 m))).
std::int64_t div_round(std::int64_t x, std::int64_t y, std::int64_t m) { return (2 * x * y + m) / (2 * m); }

struct Px {
  int c[4];
};

// The reference: one channel of the colour (k: straight channel value, a: colour alpha, both in 0..max), coverage
// level cov (0..max), destination channel d and destination alpha... only the source alpha enters the blend.
template <std::int64_t Max>
std::int64_t reference_channel(std::int64_t k, std::int64_t a, std::int64_t cov, std::int64_t d, std::int64_t src_alpha) {
  if (cov == 0 || a == 0) return d;  // nothing drawn
  const std::int64_t p = div_round(k, a, Max);  // premultiplied colour
  const std::int64_t s = cov == Max ? p : div_round(p, cov, Max);
  return s + div_round(d, Max - src_alpha, Max);
}

// The source alpha after coverage: round(Pa c8 / 255).
template <std::int64_t Max>
std::int64_t source_alpha(std::int64_t a, std::int64_t cov) {
  return cov == Max ? a : div_round(a, cov, Max);
}

Color color8(int r, int g, int b, int a) {
  return Color{static_cast<float>(r) / 255.f, static_cast<float>(g) / 255.f, static_cast<float>(b) / 255.f,
               static_cast<float>(a) / 255.f};
}

float coverage8(int level) { return static_cast<float>(level) / 255.f; }

// Expects pixel p == the reference for colour (r, g, b, a), coverage level cov and destination d.
::testing::AssertionResult matches8(const std::uint8_t* p, int r, int g, int b, int a, int cov, const Px& d) {
  const int sa = static_cast<int>(source_alpha<255>(a, cov));
  const int k[4] = {r, g, b, 255};
  for (int ch = 0; ch < 4; ++ch) {
    const auto want = reference_channel<255>(k[ch], a, cov, d.c[ch], sa);
    if (p[ch] != want) {
      return ::testing::AssertionFailure()
             << "channel " << ch << ": got " << int{p[ch]} << ", want " << want << " (colour " << r << "," << g << ","
             << b << "," << a << ", coverage " << cov << ", destination " << d.c[0] << "," << d.c[1] << ","
             << d.c[2] << "," << d.c[3] << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

void set(Image& image, int x, int y, const Px& v) {
  for (int ch = 0; ch < 4; ++ch) image.pixel(x, y)[ch] = static_cast<std::uint8_t>(v.c[ch]);
}

}  // namespace

// Step 1, every (colour channel, colour alpha) pair: opaque coverage on a transparent image leaves the premultiplied
// colour, round(k a / 255).
TEST(SolidCompositor8, PremultipliesEveryChannelAlphaPairExactly) {
  Image image(256, 1);
  for (int a = 0; a < 256; ++a) {
    image.clear(Color::transparent());
    for (int k = 0; k < 256; ++k) {
      SolidCompositor<std::uint8_t> comp(image, color8(k, 255 - k, (k * 7) & 255, a));
      comp.span(0, k, k + 1, 1.0f);
    }
    for (int k = 0; k < 256; ++k) {
      ASSERT_TRUE(matches8(image.pixel(k, 0), k, 255 - k, (k * 7) & 255, a, 255, Px{{0, 0, 0, 0}})) << "k " << k;
    }
  }
}

// Step 2, every (premultiplied value, coverage) pair, through span() and row(): an opaque colour scaled by coverage
// onto a transparent image gives round(P c8 / 255), alpha c8.
TEST(SolidCompositor8, ScalesEveryValueByEveryCoverageExactly) {
  Image spans(256, 256), rows(256, 256);
  for (int k = 0; k < 256; ++k) {
    spans.clear(Color::transparent());
    rows.clear(Color::transparent());
    const Color colour = color8(k, 255 - k, (k * 7) & 255, 255);
    SolidCompositor<std::uint8_t> by_span(spans, colour), by_row(rows, colour);
    for (int cov = 0; cov < 256; ++cov) {
      by_span.span(cov, 0, 256, coverage8(cov));
      const float c = coverage8(cov);
      by_row.row(cov, 5, 6, &c);
    }
    for (int cov = 0; cov < 256; ++cov) {
      ASSERT_TRUE(matches8(spans.pixel(17, cov), k, 255 - k, (k * 7) & 255, 255, cov, Px{{0, 0, 0, 0}})) << "span";
      ASSERT_TRUE(matches8(rows.pixel(5, cov), k, 255 - k, (k * 7) & 255, 255, cov, Px{{0, 0, 0, 0}})) << "row";
      EXPECT_EQ(rows.pixel(4, cov)[3], 0);  // outside the row: untouched
      EXPECT_EQ(rows.pixel(6, cov)[3], 0);
    }
  }
}

// Step 3, every (destination value, source alpha) pair: a colour of alpha a at full coverage over destination
// pixels (d, d/2, 255 - d... premultiplied: no channel above the alpha) gives s + round(d (255 - a) / 255).
TEST(SolidCompositor8, BlendsEveryDestinationUnderEverySourceAlphaExactly) {
  Image image(256, 256);
  auto dest = [](int d) { return Px{{d, d / 2, d / 3, d}}; };
  for (int y = 0; y < 256; ++y) {
    for (int d = 0; d < 256; ++d) set(image, d, y, dest(d));
  }
  for (int a = 0; a < 256; ++a) {
    SolidCompositor<std::uint8_t> comp(image, color8(40, 200, 255, a));
    comp.span(a, 0, 256, 1.0f);
  }
  for (int a = 0; a < 256; ++a) {
    for (int d = 0; d < 256; ++d) ASSERT_TRUE(matches8(image.pixel(d, a), 40, 200, 255, a, 255, dest(d)));
  }
}

// All four inputs at once, random (colour, alpha, coverage, destination) through span() and row().
TEST(SolidCompositor8, RandomColourCoverageAndDestinationMatchTheReference) {
  std::mt19937 rng(20261201);
  std::uniform_int_distribution<int> byte(0, 255);
  Image image(256, 1);
  std::vector<Px> dst(256);
  std::vector<float> cov(256);
  for (int round = 0; round < 4000; ++round) {
    const int r = byte(rng), g = byte(rng), b = byte(rng), a = byte(rng);
    for (int x = 0; x < 256; ++x) {
      const int da = byte(rng);
      dst[x] = Px{{byte(rng) * da / 255, byte(rng) * da / 255, byte(rng) * da / 255, da}};
      set(image, x, 0, dst[x]);
      cov[x] = coverage8(byte(rng));
    }
    SolidCompositor<std::uint8_t> comp(image, color8(r, g, b, a));
    const bool by_row = round % 2 == 0;
    const int level = byte(rng);
    if (by_row) {
      comp.row(0, 0, 256, cov.data());
    } else {
      comp.span(0, 0, 256, coverage8(level));
    }
    for (int x = 0; x < 256; ++x) {
      const int c = by_row ? static_cast<int>(std::lround(cov[x] * 255)) : level;
      ASSERT_TRUE(matches8(image.pixel(x, 0), r, g, b, a, c, dst[x])) << (by_row ? "row" : "span") << ", x " << x;
    }
  }
}

// A batch of rows (CoverageSink::rows, how the rasterizer hands over thin shapes' rows) blends each row as the
// reference does: random rows of 1 to 40 pixels in rows of a 64 x 48 image (coverage levels 0 to 255: zeros leave pixels as they are).
TEST(SolidCompositor8, RowsInABatchMatchTheReference) {
  std::mt19937 rng(20261205);
  std::uniform_int_distribution<int> byte(0, 255);
  Image image(64, 48);
  std::vector<Px> dst(64 * 48);
  for (int round = 0; round < 200; ++round) {
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 64; ++x) {
        const int da = byte(rng);
        dst[y * 64 + x] = Px{{byte(rng) * da / 255, byte(rng) * da / 255, byte(rng) * da / 255, da}};
        set(image, x, y, dst[y * 64 + x]);
      }
    }
    const int r = byte(rng), g = byte(rng), b = byte(rng), a = byte(rng);
    std::vector<CoverageRow> batch;
    std::vector<float> cov(64 * 48);
    std::vector<int> level(64 * 48, 0);
    for (int y = 0; y < 48; y += 1 + static_cast<int>(rng() % 3)) {
      const int n = 1 + static_cast<int>(rng() % 40), x0 = static_cast<int>(rng() % (64 - n + 1));
      for (int x = x0; x < x0 + n; ++x) {
        level[y * 64 + x] = byte(rng);
        cov[y * 64 + x] = coverage8(level[y * 64 + x]);
      }
      batch.push_back({y, x0, x0 + n, cov.data() + y * 64 + x0});
    }
    SolidCompositor<std::uint8_t> comp(image, color8(r, g, b, a));
    comp.rows(batch.data(), batch.size());
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 64; ++x) {
        ASSERT_TRUE(matches8(image.pixel(x, y), r, g, b, a, level[y * 64 + x], dst[y * 64 + x]))
            << "round " << round << ", pixel " << x << "," << y;
      }
    }
  }
}

// How far three roundings to nearest may take the result from the real formula: half a level in the premultiplied
// colour (scaled by the coverage), half in the scaled source, half in the destination term, and the source alpha's
// own error (half a level scaled by the coverage, plus half) carried through the destination.
namespace {
double rounding_bound(double cov, double d, double max) {
  const double alpha_error = 0.5 * cov / max + 0.5;
  return 0.5 * cov / max + 0.5 + d / max * alpha_error + 0.5 + 1e-9;
}
}  // namespace

// The rounded result stays within that bound of the unrounded source-over formula (real arithmetic on the same
// 8-bit inputs): a check of the reference itself, independent of its rounding steps.
TEST(SolidCompositor8, ReferenceIsWithinTheRoundingBoundOfTheRealFormula) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < 200000; ++i) {
    const int k = byte(rng), a = byte(rng), cov = byte(rng), da = byte(rng), d = byte(rng) * da / 255;
    const double real_src = k * (a / 255.0) * (cov / 255.0), real_sa = a * (cov / 255.0);
    const double real = real_src + d * (1 - real_sa / 255.0);
    const auto got = reference_channel<255>(k, a, cov, d, source_alpha<255>(a, cov));
    ASSERT_LE(std::abs(static_cast<double>(got) - real), rounding_bound(cov, d, 255))
        << k << " " << a << " " << cov << " " << d;
  }
}

// 16 bits: the same steps with 65535 (coverage rounded with lround), on a grid of every 257th value (0, 257, ...,
// 65535: the 8-bit levels widened) for colour, alpha, coverage and destination, and on random inputs.
TEST(SolidCompositor16, MatchesTheReferenceOnAGridAndRandomInputs) {
  auto check = [](int k, int a, int cov, int d) -> ::testing::AssertionResult {
    Image16 image(1, 1);
    const int da = 65535;
    std::uint16_t* p = image.pixel(0, 0);
    p[0] = static_cast<std::uint16_t>(d), p[1] = 0, p[2] = static_cast<std::uint16_t>(d / 2);
    p[3] = static_cast<std::uint16_t>(da);
    const Color colour{static_cast<float>(k / 65535.0), 0.f, 1.f, static_cast<float>(a / 65535.0)};
    SolidCompositor<std::uint16_t> comp(image, colour);
    comp.span(0, 0, 1, static_cast<float>(cov / 65535.0));
    // The colour is given as floats: use the level the compositor can see (float k / 65535 rounds back to k
    // when k is a multiple of 257, and for random k the reference premultiplies the float value the same way).
    const auto level = [](double v) { return static_cast<std::int64_t>(std::lround(v * 65535.0)); };
    const std::int64_t cl = level(static_cast<float>(cov / 65535.0));
    const std::int64_t alpha = level(static_cast<float>(a / 65535.0));
    const std::int64_t pr = std::lround(static_cast<double>(static_cast<float>(k / 65535.0)) *
                                        static_cast<double>(static_cast<float>(a / 65535.0)) * 65535.0);
    const std::int64_t pa = alpha;
    if (cl == 0 || pa == 0) {
      if (p[0] != d || p[3] != da) return ::testing::AssertionFailure() << "changed under zero coverage or alpha";
      return ::testing::AssertionSuccess();
    }
    const std::int64_t sr = div_round(pr, cl, 65535), sa = div_round(pa, cl, 65535);
    const std::int64_t want_r = sr + div_round(d, 65535 - sa, 65535);
    const std::int64_t want_a = sa + div_round(da, 65535 - sa, 65535);
    if (p[0] != want_r || p[3] != want_a) {
      return ::testing::AssertionFailure() << "got r " << p[0] << " a " << p[3] << ", want " << want_r << ", "
                                           << want_a << " (k " << k << ", a " << a << ", coverage " << cov << ", d "
                                           << d << ")";
    }
    // And within the rounding bound of the real formula.
    const double real = (k / 65535.0) * a * (cov / 65535.0) + d * (1 - (a / 65535.0) * (cov / 65535.0));
    if (std::abs(p[0] - real) > rounding_bound(cov, d, 65535) + 0.01) return ::testing::AssertionFailure() << "off the real formula by " << p[0] - real;
    return ::testing::AssertionSuccess();
  };
  for (int k = 0; k <= 65535; k += 257 * 15) {
    for (int a = 0; a <= 65535; a += 257 * 5) {
      for (int cov = 0; cov <= 65535; cov += 257 * 5) {
        for (int d = 0; d <= 65535; d += 257 * 15) ASSERT_TRUE(check(k, a, cov, d));
      }
    }
  }
  std::mt19937 rng(16);
  std::uniform_int_distribution<int> word(0, 65535);
  for (int i = 0; i < 100000; ++i) ASSERT_TRUE(check(word(rng), word(rng), word(rng), word(rng)));
}

// Colour values that fall on a half round up (std::lround's rule, which the compositor's inline rounding keeps), and
// a channel that is not a number counts as 0 instead of reaching the pixels as an undefined conversion.
TEST(SolidCompositor8, HalvesRoundUpAndNotANumberIsZero) {
  Image image(2, 1);
  image.clear(Color::transparent());
  SolidCompositor<std::uint8_t> comp(image, Color{0.5f, 0.25f, std::nanf(""), 1.0f});
  comp.span(0, 0, 1, 1.0f);
  EXPECT_EQ(int{image.pixel(0, 0)[0]}, 128);  // 127.5
  EXPECT_EQ(int{image.pixel(0, 0)[1]}, 64);   // 63.75
  EXPECT_EQ(int{image.pixel(0, 0)[2]}, 0);
  EXPECT_EQ(int{image.pixel(0, 0)[3]}, 255);
  Image16 deep(1, 1);
  deep.clear(Color::transparent());
  SolidCompositor<std::uint16_t> comp16(deep, Color{0.5f, 1.0f, 0.0f, 1.0f});
  comp16.span(0, 0, 1, 1.0f);
  EXPECT_EQ(int{deep.pixel(0, 0)[0]}, 32768);  // 32767.5
  EXPECT_EQ(int{deep.pixel(0, 0)[1]}, 65535);
}

}  // namespace vraster
