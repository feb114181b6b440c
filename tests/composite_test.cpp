// Composite operators and the solid-paint compositor against the slow reference (tests/support/paint_reference).
//
// What is claimed (docs/design.md, "Paint and compositing"), and tested here:
//  - Porter-Duff operators and lighter at full coverage without clip: each channel is the exact formula on the
//    integer inputs, rounded to nearest (8 bits: every (as, ab, cs) triple with two colour values per triple;
//    16 bits: a million random valid pixel pairs). Equality, no tolerance.
//  - Blend modes: within 0.51 of a level of the formula (float in 8 bits, double in 16), i.e. rounded to nearest
//    except within 0.01 of a tie.
//  - With coverage and clip: the stepwise rule of docs/design.md (source scaled and rounded, operator rounded,
//    clip lerp rounded) exactly for Porter-Duff and the polynomial blend modes; within 2 levels of the formula
//    with unquantized coverage and clip, in 8 and in 16 bits alike.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "support/paint_reference.hpp"
#include "vraster/composite.hpp"
#include "vraster/renderer.hpp"

namespace vraster {
namespace {

using test::Rgba;

constexpr CompositeOp kPorterDuff[] = {
    CompositeOp::SourceOver, CompositeOp::Copy, CompositeOp::SourceIn, CompositeOp::SourceOut,
    CompositeOp::SourceAtop, CompositeOp::DestinationOver, CompositeOp::DestinationIn, CompositeOp::DestinationOut,
    CompositeOp::DestinationAtop, CompositeOp::Xor, CompositeOp::Lighter, CompositeOp::Clear,
};
constexpr CompositeOp kBlendModes[] = {
    CompositeOp::Multiply, CompositeOp::Screen, CompositeOp::Overlay, CompositeOp::Darken, CompositeOp::Lighten,
    CompositeOp::ColorDodge, CompositeOp::ColorBurn, CompositeOp::HardLight, CompositeOp::SoftLight,
    CompositeOp::Difference, CompositeOp::Exclusion, CompositeOp::Hue, CompositeOp::Saturation, CompositeOp::Color,
    CompositeOp::Luminosity,
};

template <class T>
Rgba to_unit(const T* p) {
  const double m = sizeof(T) == 1 ? 255.0 : 65535.0;
  return {p[0] / m, p[1] / m, p[2] / m, p[3] / m};
}

// A random valid premultiplied pixel (channels <= alpha), with a bias towards the extremes.
template <class T>
void random_pixel(std::mt19937& rng, T* p) {
  const std::uint32_t m = sizeof(T) == 1 ? 255u : 65535u;
  std::uniform_int_distribution<std::uint32_t> any(0, m);
  std::uint32_t a = any(rng);
  const std::uint32_t pick = rng() % 8;
  if (pick == 0) a = m;
  if (pick == 1) a = 0;
  p[3] = static_cast<T>(a);
  for (int c = 0; c < 3; ++c) {
    std::uint32_t v = std::uniform_int_distribution<std::uint32_t>(0, a)(rng);
    if (rng() % 6 == 0) v = (rng() & 1) ? a : 0;
    p[c] = static_cast<T>(v);
  }
}

TEST(CompositeNames, EveryOperatorRoundTripsThroughItsName) {
  for (int i = 0; i < kCompositeOpCount; ++i) {
    const auto op = static_cast<CompositeOp>(i);
    CompositeOp parsed = CompositeOp::Clear;
    ASSERT_TRUE(parse_composite_op(to_string(op), parsed)) << to_string(op);
    EXPECT_EQ(parsed, op);
  }
  CompositeOp out = CompositeOp::Xor;
  EXPECT_TRUE(parse_composite_op("plus-lighter", out));
  EXPECT_EQ(out, CompositeOp::Lighter);
  out = CompositeOp::Xor;
  EXPECT_FALSE(parse_composite_op("Source-Over", out));
  EXPECT_FALSE(parse_composite_op("", out));
  EXPECT_FALSE(parse_composite_op("normal", out));
  EXPECT_EQ(out, CompositeOp::Xor);
  EXPECT_EQ(to_string(CompositeOp::ColorDodge), "color-dodge");
  EXPECT_EQ(to_string(CompositeOp::DestinationAtop), "destination-atop");
}

// A transparent source leaves the destination unchanged exactly for the bounded operators.
TEST(CompositeNames, BoundedMeansATransparentSourceChangesNothing) {
  const std::uint8_t src[4] = {0, 0, 0, 0};
  for (int i = 0; i < kCompositeOpCount; ++i) {
    const auto op = static_cast<CompositeOp>(i);
    std::uint8_t dst[4] = {40, 80, 120, 200};
    blend_row(op, dst, src, nullptr, nullptr, 1);
    const bool unchanged = dst[0] == 40 && dst[1] == 80 && dst[2] == 120 && dst[3] == 200;
    EXPECT_EQ(is_bounded(op), unchanged) << to_string(op);
  }
  EXPECT_FALSE(is_bounded(CompositeOp::Copy));
  EXPECT_FALSE(is_bounded(CompositeOp::SourceIn));
  EXPECT_TRUE(is_bounded(CompositeOp::SourceOver));
  EXPECT_TRUE(is_bounded(CompositeOp::Multiply));
}

// Source-over, 8 bits: every (source colour, source alpha, destination colour) triple, exact.
TEST(Composite8, SourceOverIsCorrectlyRoundedForEveryTriple) {
  std::vector<std::uint8_t> src, dst;
  for (int as = 0; as < 256; ++as) {
    for (int cs = 0; cs <= as; ++cs) {
      for (int cb = 0; cb < 256; cb += 3) {  // three destination values a pixel: R = cb, G = cb + 1, B = cb + 2
        src.insert(src.end(), {static_cast<std::uint8_t>(cs), static_cast<std::uint8_t>(cs),
                               static_cast<std::uint8_t>(cs), static_cast<std::uint8_t>(as)});
        dst.insert(dst.end(), {static_cast<std::uint8_t>(cb), static_cast<std::uint8_t>(std::min(cb + 1, 255)),
                               static_cast<std::uint8_t>(std::min(cb + 2, 255)), 255});
      }
    }
  }
  const std::vector<std::uint8_t> before = dst;
  blend_row(CompositeOp::SourceOver, dst.data(), src.data(), nullptr, nullptr, static_cast<int>(dst.size() / 4));
  for (std::size_t i = 0; i < dst.size(); i += 4) {
    const Rgba r = test::reference_composite(CompositeOp::SourceOver, to_unit(&src[i]), to_unit(&before[i]));
    for (std::size_t c = 0; c < 4; ++c) {
      ASSERT_EQ(dst[i + c], std::lround(r[c] * 255)) << "src " << int(src[i]) << "/" << int(src[i + 3]) << " dst "
                                                     << int(before[i + c]) << " channel " << c;
    }
  }
}

// Every Porter-Duff operator, 8 bits: every (as, ab) pair, every cs <= as, two destination colours a triple.
TEST(Composite8, PorterDuffOperatorsAreCorrectlyRounded) {
  std::vector<std::uint8_t> src, dst;
  for (int as = 0; as < 256; as += 1) {
    for (int ab = 0; ab < 256; ab += 1) {
      for (int cs = 0; cs <= as; cs += (as > 64 ? 7 : 1)) {
        const int cb1 = (cs * 7 + as) % (ab + 1), cb2 = ab - (cs * 3) % (ab + 1);
        src.insert(src.end(), {static_cast<std::uint8_t>(cs), static_cast<std::uint8_t>(cs),
                               static_cast<std::uint8_t>(as - cs), static_cast<std::uint8_t>(as)});
        dst.insert(dst.end(), {static_cast<std::uint8_t>(cb1), static_cast<std::uint8_t>(cb2),
                               static_cast<std::uint8_t>(ab), static_cast<std::uint8_t>(ab)});
      }
    }
  }
  std::vector<std::uint8_t> out;
  for (CompositeOp op : kPorterDuff) {
    out = dst;
    blend_row(op, out.data(), src.data(), nullptr, nullptr, static_cast<int>(out.size() / 4));
    for (std::size_t i = 0; i < out.size(); i += 4) {
      const Rgba r = test::reference_composite(op, to_unit(&src[i]), to_unit(&dst[i]));
      for (std::size_t c = 0; c < 4; ++c) {
        ASSERT_EQ(out[i + c], std::lround(r[c] * 255))
            << to_string(op) << " src " << int(src[i + c]) << "/" << int(src[i + 3]) << " dst " << int(dst[i + c])
            << "/" << int(dst[i + 3]) << " channel " << c;
      }
    }
  }
}

template <class T>
void check_random_pairs(const CompositeOp* ops, std::size_t nops, int count, double tolerance_levels,
                        bool exact) {
  const double m = sizeof(T) == 1 ? 255.0 : 65535.0;
  std::mt19937 rng(1234);
  std::vector<T> src(static_cast<std::size_t>(count) * 4), dst(src.size()), out;
  for (int i = 0; i < count; ++i) {
    random_pixel(rng, &src[static_cast<std::size_t>(i) * 4]);
    random_pixel(rng, &dst[static_cast<std::size_t>(i) * 4]);
  }
  for (std::size_t k = 0; k < nops; ++k) {
    const CompositeOp op = ops[k];
    out = dst;
    blend_row(op, out.data(), src.data(), nullptr, nullptr, count);
    double worst = 0;
    for (std::size_t i = 0; i < out.size(); i += 4) {
      const Rgba r = test::reference_composite(op, to_unit(&src[i]), to_unit(&dst[i]));
      for (std::size_t c = 0; c < 4; ++c) {
        const double err = std::abs(out[i + c] - r[c] * m);
        worst = std::max(worst, err);
        if (exact) {
          ASSERT_EQ(out[i + c], std::lround(r[c] * m)) << to_string(op) << " pixel " << i / 4 << " channel " << c;
        } else {
          ASSERT_LE(err, tolerance_levels) << to_string(op) << " pixel " << i / 4 << " channel " << c << " src "
                                           << src[i + c] << "/" << src[i + 3] << " dst " << dst[i + c] << "/"
                                           << dst[i + 3];
        }
      }
    }
    ::testing::Test::RecordProperty(std::string(to_string(op)), std::to_string(worst));
  }
}

TEST(Composite16, PorterDuffOperatorsAreCorrectlyRounded) {
  check_random_pairs<std::uint16_t>(kPorterDuff, std::size(kPorterDuff), 200000, 0, true);
}

TEST(Composite8, BlendModesAreWithinHalfALevel) {
  check_random_pairs<std::uint8_t>(kBlendModes, std::size(kBlendModes), 100000, 0.51, false);
}

TEST(Composite16, BlendModesAreWithinHalfALevel) {
  check_random_pairs<std::uint16_t>(kBlendModes, std::size(kBlendModes), 100000, 0.51, false);
}

// Blend modes on every pair of a grid of 8-bit pixels that includes the extremes and the branch points of the
// blend functions (0.25, 0.5 of alpha).
TEST(Composite8, BlendModesOnAGridOfBranchPoints) {
  const int alphas[] = {0, 1, 64, 128, 200, 254, 255};
  const double fractions[] = {0, 0.25, 0.5, 0.501, 0.75, 1};
  std::vector<std::uint8_t> pixels;
  for (int a : alphas) {
    for (double f0 : fractions) {
      for (double f1 : fractions) {
        pixels.insert(pixels.end(), {static_cast<std::uint8_t>(std::lround(a * f0)),
                                     static_cast<std::uint8_t>(std::lround(a * f1)),
                                     static_cast<std::uint8_t>(std::lround(a * (1 - f0))), static_cast<std::uint8_t>(a)});
      }
    }
  }
  const std::size_t n = pixels.size() / 4;
  std::vector<std::uint8_t> src, dst;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      src.insert(src.end(), pixels.begin() + static_cast<std::ptrdiff_t>(4 * i), pixels.begin() + static_cast<std::ptrdiff_t>(4 * i + 4));
      dst.insert(dst.end(), pixels.begin() + static_cast<std::ptrdiff_t>(4 * j), pixels.begin() + static_cast<std::ptrdiff_t>(4 * j + 4));
    }
  }
  for (CompositeOp op : kBlendModes) {
    std::vector<std::uint8_t> out = dst;
    blend_row(op, out.data(), src.data(), nullptr, nullptr, static_cast<int>(out.size() / 4));
    for (std::size_t i = 0; i < out.size(); i += 4) {
      const Rgba r = test::reference_composite(op, to_unit(&src[i]), to_unit(&dst[i]));
      for (std::size_t c = 0; c < 4; ++c) {
        ASSERT_LE(std::abs(out[i + c] - r[c] * 255), 0.51) << to_string(op) << " channel " << c;
      }
    }
  }
}

// Coverage and clip, every operator, both depths, against the rule written out step by step (docs/design.md):
// k and c quantized, s' = round(s k / M), r = round(Op(s', d)), out = round((d (M - c) + r c) / M). Exact for the
// Porter-Duff operators and the polynomial blend modes, within one level for the others (r within 0.51 of a
// level before the clip step). Against the formula with unquantized coverage and clip: within 2 levels (3 for
// the non-separable modes, whose SetSat divides by the colour's range), except color-dodge and color-burn, which divide by 1 - Cs or Cs and so amplify the rounding of the scaled source
// without bound near Cs = 1 or 0 (they are held to the stepwise rule only).
template <class T>
void check_coverage_and_clip() {
  const double m = sizeof(T) == 1 ? 255.0 : 65535.0;
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(0, 1);
  constexpr int kCount = 20000;
  std::vector<T> src(kCount * 4), dst(kCount * 4);
  std::vector<float> cov(kCount), clip(kCount);
  for (int i = 0; i < kCount; ++i) {
    random_pixel(rng, &src[static_cast<std::size_t>(i) * 4]);
    random_pixel(rng, &dst[static_cast<std::size_t>(i) * 4]);
    cov[static_cast<std::size_t>(i)] = i % 5 == 0 ? 1.f : unit(rng);
    clip[static_cast<std::size_t>(i)] = i % 3 == 0 ? 1.f : unit(rng);
  }
  for (int k = 0; k < kCompositeOpCount; ++k) {
    const auto op = static_cast<CompositeOp>(k);
    const bool exact = op < CompositeOp::Multiply || op == CompositeOp::Multiply || op == CompositeOp::Screen ||
                       op == CompositeOp::Darken || op == CompositeOp::Lighten || op == CompositeOp::Difference ||
                       op == CompositeOp::Exclusion;
    std::vector<T> out = dst;
    // The clip as levels (round(m * clip): how a clip mask is stored).
    std::vector<T> clip_levels(kCount);
    for (int i = 0; i < kCount; ++i) clip_levels[static_cast<std::size_t>(i)] = static_cast<T>(std::round(clip[static_cast<std::size_t>(i)] * m));
    blend_row(op, out.data(), src.data(), cov.data(), clip_levels.data(), kCount);
    for (std::size_t i = 0; i < out.size(); i += 4) {
      const float cv = cov[i / 4], cl = clip[i / 4];
      const double kq = std::round(cv * m), cq = std::round(cl * m);
      Rgba s, d = to_unit(&dst[i]);
      for (std::size_t c = 0; c < 4; ++c) s[c] = std::round(src[i + c] * kq / m) / m;
      const Rgba r = test::reference_composite(op, s, d);
      const Rgba unquantized = test::reference_draw(op, to_unit(&src[i]), d, cv, cl);
      for (std::size_t c = 0; c < 4; ++c) {
        const double rq = std::round(r[c] * m);
        const double expect = std::round((dst[i + c] * (m - cq) + rq * cq) / m);
        if (exact) {
          ASSERT_EQ(out[i + c], expect) << to_string(op) << " pixel " << i / 4 << " channel " << c << " coverage "
                                        << cv << " clip " << cl;
        } else {
          ASSERT_LE(std::abs(out[i + c] - expect), 1.0)
              << to_string(op) << " pixel " << i / 4 << " channel " << c << " coverage " << cv << " clip " << cl;
        }
        if (op == CompositeOp::ColorDodge || op == CompositeOp::ColorBurn || op >= CompositeOp::Hue) continue;
        ASSERT_LE(std::abs(out[i + c] - unquantized[c] * m), 2.0)
            << to_string(op) << " pixel " << i / 4 << " channel " << c << " coverage " << cv << " clip " << cl;
      }
    }
  }
}

// The SWAR helpers of the 8-bit source-over loops are exact for every input.
TEST(Composite8, SourceOverWithCoverageAndClipFollowsTheRuleExactly) {
  // Every (source channel, source alpha, coverage) with destination and clip sampled: blend_row against the
  // stepwise rule above, through the vectorised source-over loops.
  std::vector<std::uint8_t> src, dst;
  std::vector<float> cov;
  std::vector<std::uint8_t> clip;  // levels
  for (int as = 0; as < 256; as += 5) {
    for (int cs = 0; cs <= as; cs += 3) {
      for (int k = 0; k < 256; k += 1) {
        src.insert(src.end(), {static_cast<std::uint8_t>(cs), static_cast<std::uint8_t>(as - cs),
                               static_cast<std::uint8_t>(cs / 2), static_cast<std::uint8_t>(as)});
        dst.insert(dst.end(), {static_cast<std::uint8_t>(k), static_cast<std::uint8_t>(255 - k),
                               static_cast<std::uint8_t>((k * 7) % 256), 255});
        cov.push_back(k / 255.f);
        clip.push_back(static_cast<std::uint8_t>((k * 13) % 256));
      }
    }
  }
  const int n = static_cast<int>(cov.size());
  for (bool with_clip : {false, true}) {
    std::vector<std::uint8_t> out = dst;
    blend_row(CompositeOp::SourceOver, out.data(), src.data(), cov.data(), with_clip ? clip.data() : nullptr, n);
    for (std::size_t i = 0; i < out.size(); i += 4) {
      const double kq = std::round(cov[i / 4] * 255.0), cq = with_clip ? clip[i / 4] : 255;
      double s[4];
      for (std::size_t c = 0; c < 4; ++c) s[c] = std::round(src[i + c] * kq / 255);
      for (std::size_t c = 0; c < 4; ++c) {
        const double r = std::round(s[c] + dst[i + c] * (255 - s[3]) / 255);
        const double expect = std::round((dst[i + c] * (255 - cq) + r * cq) / 255);
        ASSERT_EQ(out[i + c], expect) << "pixel " << i / 4 << " channel " << c << (with_clip ? " clipped" : "");
      }
    }
  }
}

// The 8-bit source-over loops run their first pixels apart until the destination is 32-byte aligned: every start
// offset and length must give what one-pixel calls give (every loop variant: constant / row source, with and
// without coverage and clip, opaque store).
TEST(Composite8, SourceOverIsTheSameAtEveryAlignment) {
  std::mt19937 rng(5);
  std::vector<std::uint8_t> src(64 * 4), base(80 * 4);
  std::vector<float> cov(64);
  std::vector<std::uint8_t> clip(64);
  for (auto& v : base) v = static_cast<std::uint8_t>(rng());
  for (std::size_t i = 0; i < 64; ++i) {
    random_pixel(rng, &src[i * 4]);
    cov[i] = static_cast<float>(rng() % 256) / 255.f;
    clip[i] = static_cast<std::uint8_t>(rng());
  }
  const std::uint8_t opaque[4] = {10, 20, 30, 255};
  for (int offset = 0; offset < 9; ++offset) {
    for (int n = 0; n <= 40; ++n) {
      for (int variant = 0; variant < 5; ++variant) {
        std::vector<std::uint8_t> whole = base, single = base;
        auto run = [&](std::uint8_t* dst, int first, int count) {
          const float* c = variant >= 1 && variant <= 2 ? cov.data() + first : nullptr;
          const std::uint8_t* k = variant == 2 || variant == 3 ? clip.data() + first : nullptr;
          if (variant == 4) {  // opaque pixels one by one (the store is checked against this)
            for (int i = 0; i < count; ++i) blend_row_alpha(CompositeOp::SourceOver, dst + 4 * i, opaque, 1.f, nullptr, 1);
          } else if (variant == 0) {
            blend_row_alpha(CompositeOp::SourceOver, dst, src.data() + 4 * first, 0.7f, nullptr, count);
          } else {
            blend_row(CompositeOp::SourceOver, dst, src.data() + 4 * first, c, k, count);
          }
        };
        if (variant == 4) {
          // The compositor's store: one colour, full coverage, opaque.
          Compositor<std::uint8_t> comp;
          ImageView<std::uint8_t> view{whole.data() + 4 * offset, 0, 0, n, 1, 4 * 64};
          comp.set(view, Paint::solid({10 / 255.f, 20 / 255.f, 30 / 255.f, 1}), Affine{}, CompositeOp::SourceOver);
          if (n > 0) comp.span(0, 0, n, 1.f);
        } else {
          run(whole.data() + 4 * offset, 0, n);
        }
        for (int i = 0; i < n; ++i) run(single.data() + 4 * (offset + i), i, 1);
        ASSERT_EQ(whole, single) << "offset " << offset << " n " << n << " variant " << variant;
      }
    }
  }
}

TEST(Composite8, CoverageScalesTheSourceAndClipLerps) { check_coverage_and_clip<std::uint8_t>(); }
TEST(Composite16, CoverageScalesTheSourceAndClipLerps) { check_coverage_and_clip<std::uint16_t>(); }

// The same inputs at both depths (8-bit values v are 16-bit values 257 v): 16 bits within one 16-bit level of the
// formula wherever 8 bits are within one 8-bit level.
TEST(Composite16, SixteenBitsAreAsCloseInTheirLevelsAsEightBits) {
  std::mt19937 rng(5);
  constexpr int kCount = 20000;
  std::vector<std::uint8_t> s8(kCount * 4), d8(kCount * 4);
  for (int i = 0; i < kCount; ++i) {
    random_pixel(rng, &s8[static_cast<std::size_t>(i) * 4]);
    random_pixel(rng, &d8[static_cast<std::size_t>(i) * 4]);
  }
  std::vector<std::uint16_t> s16(s8.size()), d16(d8.size());
  for (std::size_t i = 0; i < s8.size(); ++i) {
    s16[i] = static_cast<std::uint16_t>(s8[i] * 257);
    d16[i] = static_cast<std::uint16_t>(d8[i] * 257);
  }
  for (int k = 0; k < kCompositeOpCount; ++k) {
    const auto op = static_cast<CompositeOp>(k);
    std::vector<std::uint8_t> o8 = d8;
    std::vector<std::uint16_t> o16 = d16;
    blend_row(op, o8.data(), s8.data(), nullptr, nullptr, kCount);
    blend_row(op, o16.data(), s16.data(), nullptr, nullptr, kCount);
    for (std::size_t i = 0; i < o8.size(); i += 4) {
      const Rgba r = test::reference_composite(op, to_unit(&s8[i]), to_unit(&d8[i]));
      for (std::size_t c = 0; c < 4; ++c) {
        if (std::abs(o8[i + c] / 255.0 - r[c]) <= 1 / 255.0) {
          ASSERT_LE(std::abs(o16[i + c] / 65535.0 - r[c]), 1 / 65535.0) << to_string(op) << " channel " << c;
        }
      }
    }
  }
}

// ---- Compositor with solid paint ----

template <class T>
struct Target {
  static constexpr double kM = sizeof(T) == 1 ? 255.0 : 65535.0;
  // A 24 x 10 buffer addressed as device pixels [100, 124) x [50, 60) (a layer's view).
  std::vector<T> pixels = std::vector<T>(24 * 10 * 4);
  ImageView<T> view{pixels.data(), 100, 50, 24, 10, 24 * 4};

  void fill_pattern() {
    std::mt19937 rng(7);
    for (std::size_t i = 0; i < pixels.size(); i += 4) random_pixel(rng, &pixels[i]);
  }
};

template <class T>
void check_solid_compositor() {
  const Color colors[] = {{0.2f, 0.6f, 0.9f, 1.f}, {1.f, 0.3f, 0.1f, 0.55f}, {0.f, 0.f, 0.f, 0.f}};
  for (const Color& color : colors) {
    for (int k = 0; k < kCompositeOpCount; ++k) {
      const auto op = static_cast<CompositeOp>(k);
      Target<T> t;
      t.fill_pattern();
      const std::vector<T> before = t.pixels;
      Compositor<T> comp;
      const Paint paint = Paint::solid(color);
      comp.set(t.view, paint, Affine{}, op, 0.8f);
      // Row 52: a span; row 55: a row with varied coverage and a clip; other rows untouched.
      comp.span(52, 103, 115, 0.6f);
      comp.span(53, 100, 124, 1.f);
      std::vector<float> cov(24);
      std::vector<T> clip(24);  // levels
      for (int i = 0; i < 24; ++i) {
        cov[static_cast<std::size_t>(i)] = static_cast<float>(i % 6) / 5.f;
        clip[static_cast<std::size_t>(i)] = static_cast<T>(std::round((i * 7) % 11 / 10.0 * Target<T>::kM));
      }
      comp.row(55, 100, 124, cov.data(), clip.data());
      const double a = std::clamp(static_cast<double>(color.a), 0.0, 1.0);
      // The source as the target stores it: premultiplied and rounded to the channel depth.
      auto q = [](double v) { return std::round(v * Target<T>::kM) / Target<T>::kM; };
      const Rgba s{q(color.r * a), q(color.g * a), q(color.b * a), q(a)};
      for (int y = 50; y < 60; ++y) {
        for (int x = 100; x < 124; ++x) {
          const std::size_t i = static_cast<std::size_t>(((y - 50) * 24 + (x - 100)) * 4);
          double coverage = 0, clipv = 1;
          bool touched = false;
          if (y == 52 && x >= 103 && x < 115) coverage = 0.6, touched = true;
          if (y == 53) coverage = 1, touched = true;
          if (y == 55) coverage = cov[static_cast<std::size_t>(x - 100)], clipv = clip[static_cast<std::size_t>(x - 100)] / Target<T>::kM, touched = true;
          Rgba expect = to_unit(&before[i]);
          if (touched) expect = test::reference_draw(op, s, expect, coverage * 0.8, clipv);
          for (std::size_t c = 0; c < 4; ++c) {
            ASSERT_LE(std::abs(t.pixels[i + c] - expect[c] * Target<T>::kM), touched ? 2.0 : 0.0)
                << to_string(op) << " at " << x << "," << y << " channel " << c << " alpha " << color.a;
          }
        }
      }
    }
  }
}

TEST(Compositor8, SolidPaintEveryOperatorSpansRowsAndClip) { check_solid_compositor<std::uint8_t>(); }
TEST(Compositor16, SolidPaintEveryOperatorSpansRowsAndClip) { check_solid_compositor<std::uint16_t>(); }

TEST(Compositor8, OpaqueSourceOverStoresTheColour) {
  Target<std::uint8_t> t;
  t.fill_pattern();
  Compositor<std::uint8_t> comp;
  const Paint paint = Paint::solid(Color::rgb8(10, 20, 30));
  comp.set(t.view, paint, Affine{}, CompositeOp::SourceOver);
  comp.span(57, 100, 124, 1.f);
  for (int x = 100; x < 124; ++x) {
    const std::uint8_t* p = t.view.pixel(x, 57);
    EXPECT_EQ(p[0], 10);
    EXPECT_EQ(p[1], 20);
    EXPECT_EQ(p[2], 30);
    EXPECT_EQ(p[3], 255);
  }
}

TEST(Compositor8, UnboundedOperatorsChangePixelsWithZeroCoverage) {
  // copy with a row of zero coverage clears; source-in with zero coverage clears; source-over leaves them.
  for (CompositeOp op : {CompositeOp::Copy, CompositeOp::SourceIn, CompositeOp::DestinationIn,
                         CompositeOp::SourceOver, CompositeOp::Xor}) {
    Target<std::uint8_t> t;
    for (std::size_t i = 0; i < t.pixels.size(); i += 4) {
      t.pixels[i] = 50, t.pixels[i + 1] = 60, t.pixels[i + 2] = 70, t.pixels[i + 3] = 100;
    }
    Compositor<std::uint8_t> comp;
    const Paint paint = Paint::solid({1, 0, 0, 1});
    comp.set(t.view, paint, Affine{}, op);
    const std::vector<float> zero(24, 0.f);
    comp.row(51, 100, 124, zero.data());
    const std::uint8_t* p = t.view.pixel(110, 51);
    if (is_bounded(op)) {
      EXPECT_EQ(p[3], 100) << to_string(op);
    } else {
      EXPECT_EQ(p[0], 0) << to_string(op);
      EXPECT_EQ(p[3], 0) << to_string(op);
    }
  }
}

TEST(Compositor, DrawsNothingOnlyWhenNothingCanChange) {
  Target<std::uint8_t> t;
  Compositor<std::uint8_t> comp;
  const Paint clear = Paint::solid(Color::transparent());
  const Paint red = Paint::solid({1, 0, 0, 1});
  comp.set(t.view, clear, Affine{}, CompositeOp::SourceOver);
  EXPECT_TRUE(comp.draws_nothing());
  comp.set(t.view, clear, Affine{}, CompositeOp::Copy);  // copy of transparent clears the shape
  EXPECT_FALSE(comp.draws_nothing());
  comp.set(t.view, red, Affine{}, CompositeOp::SourceOver, 0.f);
  EXPECT_TRUE(comp.draws_nothing());
  comp.set(t.view, red, Affine{}, CompositeOp::DestinationIn, 0.f);
  EXPECT_FALSE(comp.draws_nothing());
  comp.set(t.view, red, Affine{}, CompositeOp::SourceOver, 1.f);
  EXPECT_FALSE(comp.draws_nothing());
  Paint faded = red;
  faded.set_opacity(0);
  comp.set(t.view, faded, Affine{}, CompositeOp::Multiply);
  EXPECT_TRUE(comp.draws_nothing());
  Paint grad = Paint::linear({0, 0}, {10, 0});
  grad.add_stop(0, {1, 0, 0, 1});
  grad.set_transform(Affine::scale(0));  // singular: paints nothing
  comp.set(t.view, grad, Affine{}, CompositeOp::SourceOver);
  EXPECT_TRUE(comp.draws_nothing());
}

// span(coverage, clip) and row(nullptr, clip) are row(coverage row, clip) with a constant coverage.
TEST(Compositor, ClippedSpansEqualClippedRows) {
  for (CompositeOp op : {CompositeOp::SourceOver, CompositeOp::Multiply, CompositeOp::Copy, CompositeOp::Xor}) {
    Target<std::uint8_t> a, b, c;
    a.fill_pattern();
    b.fill_pattern();
    c.fill_pattern();
    Paint paint = Paint::linear({100, 0}, {124, 0});
    paint.add_stop(0, {1, 0, 0, 0.8f});
    paint.add_stop(1, {0, 0, 1, 1});
    std::vector<float> cov(24, 0.7f), ones(24, 1.f);
    std::vector<std::uint8_t> clip(24);  // levels
    for (int i = 0; i < 24; ++i) clip[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>((i * 5) % 9 * 255 / 8);
    Compositor<std::uint8_t> comp;
    comp.set(a.view, paint, Affine{}, op, 0.9f);
    comp.span(54, 100, 124, 0.7f, clip.data());
    comp.set(b.view, paint, Affine{}, op, 0.9f);
    comp.row(54, 100, 124, cov.data(), clip.data());
    EXPECT_EQ(a.pixels, b.pixels) << to_string(op);
    Target<std::uint8_t> d;
    d.fill_pattern();
    comp.set(c.view, paint, Affine{}, op, 0.9f);
    comp.row(54, 100, 124, nullptr, clip.data());
    comp.set(d.view, paint, Affine{}, op, 0.9f);
    comp.row(54, 100, 124, ones.data(), clip.data());
    EXPECT_EQ(c.pixels, d.pixels) << to_string(op);
  }
}

TEST(Compositor, SpansOutsideTheViewAreIgnored) {
  Target<std::uint8_t> t;
  Compositor<std::uint8_t> comp;
  const Paint red = Paint::solid({1, 0, 0, 1});
  comp.set(t.view, red, Affine{}, CompositeOp::SourceOver);
  comp.span(10, 0, 500, 1.f);  // row outside
  comp.span(50, 0, 102, 1.f);  // partly left of the view
  comp.span(50, 122, 500, 1.f);  // partly right
  for (int x = 100; x < 124; ++x) {
    EXPECT_EQ(t.view.pixel(x, 50)[3], (x < 102 || x >= 122) ? 255 : 0) << x;
  }
}

// ---- Paint ----

TEST(Paint, StopsKeepOffsetOrderAndEqualOffsetsKeepInsertionOrder) {
  Paint p = Paint::linear({0, 0}, {1, 0});
  EXPECT_TRUE(p.add_stop(0.5, {1, 0, 0, 1}));
  EXPECT_TRUE(p.add_stop(0.2, {0, 1, 0, 1}));
  EXPECT_TRUE(p.add_stop(0.5, {0, 0, 1, 1}));
  EXPECT_FALSE(p.add_stop(1.5, {0, 0, 1, 1}));
  EXPECT_FALSE(p.add_stop(NAN, {0, 0, 1, 1}));
  EXPECT_FALSE(p.add_stop(0.3, {NAN, 0, 1, 1}));
  ASSERT_EQ(p.stops().size(), 3u);
  EXPECT_EQ(p.stops()[0].offset, 0.2);
  EXPECT_EQ(p.stops()[1].color.r, 1.f);
  EXPECT_EQ(p.stops()[2].color.b, 1.f);
  Paint s = Paint::solid({1, 1, 1, 1});
  EXPECT_FALSE(s.add_stop(0.5, {1, 0, 0, 1}));
}

TEST(Paint, OpaqueAndInvisible) {
  EXPECT_TRUE(Paint().is_opaque());
  EXPECT_TRUE(Paint::solid({1, 0, 0, 1}).is_opaque());
  EXPECT_FALSE(Paint::solid({1, 0, 0, 0.5f}).is_opaque());
  EXPECT_TRUE(Paint::solid({1, 0, 0, 0}).is_invisible());
  Paint lin = Paint::linear({0, 0}, {10, 0});
  EXPECT_TRUE(lin.is_invisible());  // no stops
  lin.add_stop(0, {1, 0, 0, 1});
  lin.add_stop(1, {0, 0, 1, 1});
  EXPECT_TRUE(lin.is_opaque());
  lin.set_opacity(0.5f);
  EXPECT_FALSE(lin.is_opaque());
  EXPECT_FALSE(lin.is_invisible());
  Paint same = Paint::linear({3, 3}, {3, 3});
  same.add_stop(0, {1, 0, 0, 1});
  EXPECT_TRUE(same.is_invisible());  // canvas: x0 = x1 and y0 = y1 paints nothing
  Paint ring = Paint::radial({0, 0}, 10, {30, 0}, 5);  // circles apart: the cone leaves the plane partly empty
  ring.add_stop(0, {1, 0, 0, 1});
  EXPECT_FALSE(ring.is_opaque());
  EXPECT_FALSE(ring.is_invisible());
  Paint inside = Paint::radial({1, 0}, 0, {0, 0}, 20);
  inside.add_stop(0, {1, 0, 0, 1});
  EXPECT_TRUE(inside.is_opaque());
  Paint degenerate = Paint::radial({1, 1}, 4, {1, 1}, 4);
  degenerate.add_stop(0, {1, 0, 0, 1});
  EXPECT_TRUE(degenerate.is_invisible());
  Paint conic = Paint::conic(0, {0, 0});
  conic.add_stop(0.5, {1, 1, 1, 1});
  EXPECT_TRUE(conic.is_opaque());
  conic.set_transform(Affine::scale(0, 1));
  EXPECT_TRUE(conic.is_invisible());
  EXPECT_TRUE(Paint::pattern(std::shared_ptr<const Image>()).is_invisible());
}

// CoverageSink::expect is a hint before a small fill (the sinks that write pixels start fetching them): it must change
// no pixel, whatever box it is given, including boxes beyond the image or the view and at the ends of int.
TEST(CompositorExpect, IsOnlyAHintForEveryBox) {
  std::mt19937 rng(11);
  Image image(37, 29);
  for (auto& v : image.data) v = static_cast<std::uint8_t>(rng());
  const Image before = image;
  const int big = std::numeric_limits<int>::max(), small = std::numeric_limits<int>::min();
  const int boxes[][4] = {{0, 29, 0, 37},   {-5, 40, -9, 50},   {28, 29, 36, 37}, {5, 5, 3, 20},   {10, 2, 8, 4},
                          {small, big, small, big}, {big - 1, big, big - 1, big}, {small, small + 1, small, small + 1},
                          {29, 100, 0, 37}, {0, 29, 37, 100}, {0, 200, 0, 200}};
  Compositor<std::uint8_t> general;
  ImageView<std::uint8_t> view = ImageView<std::uint8_t>::of(image);
  view.x0 = -3;  // a view placed off the origin, as a layer is
  view.y0 = 4;
  general.set(view, Paint::solid({0.2f, 0.4f, 0.6f, 0.8f}), Affine{}, CompositeOp::SourceOver);
  SolidCompositor<std::uint8_t> solid(image, Color{0.2f, 0.4f, 0.6f, 0.8f});
  for (const auto& b : boxes) {
    general.expect(b[0], b[1], b[2], b[3]);
    solid.expect(b[0], b[1], b[2], b[3]);
  }
  EXPECT_EQ(image.data, before.data);
}

}  // namespace
}  // namespace vraster
