// Image patterns against the slow per-pixel reference (tests/support/paint_reference): 8- and 16-bit tiles onto 8-
// and 16-bit targets, every filter, every extend mode on each axis, with the pattern's own transform.
//
// Tolerance: one level of the target per channel (the fast code accumulates in float, the reference in double).
// Nearest sampling is a step function of the position: where a pixel centre maps exactly onto a texel border the
// two may pick different sides, so a pixel also passes when it matches the reference 1e-6 px away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>

#include "paint/shade.hpp"
#include "support/paint_reference.hpp"
#include "vraster/composite.hpp"

namespace vraster {
namespace {

using test::Rgba;

template <class S>
std::shared_ptr<BasicImage<S>> random_tile(int w, int h, unsigned seed) {
  auto tile = std::make_shared<BasicImage<S>>(w, h);
  std::mt19937 rng(seed);
  const std::uint32_t m = BasicImage<S>::kMax;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      S* p = tile->pixel(x, y);
      const std::uint32_t a = (x + y) % 3 == 0 ? m : static_cast<std::uint32_t>(rng() % (m + 1));
      p[3] = static_cast<S>(a);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<S>(rng() % (a + 1));
    }
  }
  return tile;
}

const char* extend_name(Extend e) {
  switch (e) {
    case Extend::Pad: return "pad";
    case Extend::Repeat: return "repeat";
    case Extend::Reflect: return "reflect";
    default: return "none";
  }
}
const char* filter_name(ImageFilter f) {
  return f == ImageFilter::Nearest ? "nearest" : f == ImageFilter::Bilinear ? "bilinear" : "bicubic";
}

template <class T>
int check_pattern(const Paint& paint, const Affine& device, const std::string& what) {
  constexpr int kW = 40, kH = 32;
  const double m = BasicImage<T>::kMax;
  BasicImage<T> image(kW, kH);
  Compositor<T> comp;
  comp.set(ImageView<T>::of(image), paint, device, CompositeOp::Copy);
  for (int y = 0; y < kH; ++y) comp.span(y, 0, kW, 1.f);
  int wrong = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const T* px = image.pixel(x, y);
      bool ok = false;
      Rgba ref{};
      for (double e : {0.0, 1e-6, -1e-6}) {
        for (double f : {0.0, 1e-6, -1e-6}) {
          if (ok) break;
          ref = test::reference_pattern(paint, device, x + 0.5 + e, y + 0.5 + f);
          ok = true;
          for (std::size_t c = 0; c < 4; ++c) ok = ok && std::abs(px[c] - ref[c] * m) <= 1.0;
        }
      }
      if (!ok && ++wrong <= 3) {
        ref = test::reference_pattern(paint, device, x + 0.5, y + 0.5);
        ADD_FAILURE() << what << " at (" << x << ", " << y << "): " << px[0] << " " << px[1] << " " << px[2] << " "
                      << px[3] << ", reference " << ref[0] * m << " " << ref[1] * m << " " << ref[2] * m << " "
                      << ref[3] * m;
      }
    }
  }
  return wrong;
}

template <class T, class S>
void check_all_patterns() {
  const auto tile = random_tile<S>(7, 5, 11);
  const Extend extends[] = {Extend::None, Extend::Pad, Extend::Repeat, Extend::Reflect};
  const ImageFilter filters[] = {ImageFilter::Nearest, ImageFilter::Bilinear, ImageFilter::Bicubic};
  const Affine device = Affine::translate(4, 3) * Affine::scale(1.25);
  const Affine owns[] = {Affine::translate(6, 5), Affine::translate(6.3, 4.7) * Affine::scale(2.5, 1.75),
                         Affine::rotate(30, 10, 8) * Affine::scale(1.5) * Affine::translate(2, 1),
                         Affine::scale(0.4)};
  for (ImageFilter f : filters) {
    for (Extend ex : extends) {
      for (Extend ey : extends) {
        for (std::size_t k = 0; k < std::size(owns); ++k) {
          Paint p = Paint::pattern(std::shared_ptr<const BasicImage<S>>(tile));
          p.set_filter(f);
          p.set_extend(ex, ey);
          p.set_transform(owns[k]);
          if (k == 2) p.set_opacity(0.6f);
          const std::string what = std::string(filter_name(f)) + " " + extend_name(ex) + "/" + extend_name(ey) +
                                   " transform " + std::to_string(k);
          if (check_pattern<T>(p, device, what) > 0) return;
        }
      }
    }
  }
}

TEST(Pattern, EightBitTileOnEightBitTarget) { check_all_patterns<std::uint8_t, std::uint8_t>(); }
TEST(Pattern, SixteenBitTileOnSixteenBitTarget) { check_all_patterns<std::uint16_t, std::uint16_t>(); }
TEST(Pattern, EightBitTileOnSixteenBitTarget) { check_all_patterns<std::uint16_t, std::uint8_t>(); }
TEST(Pattern, SixteenBitTileOnEightBitTarget) { check_all_patterns<std::uint8_t, std::uint16_t>(); }

// A tiny hand-made case: a 2 x 1 tile (red, blue) repeated, nearest, at one pixel per texel.
TEST(Pattern, RepeatedTileByHand) {
  auto tile = std::make_shared<Image>(2, 1);
  tile->pixel(0, 0)[0] = 255, tile->pixel(0, 0)[3] = 255;
  tile->pixel(1, 0)[2] = 255, tile->pixel(1, 0)[3] = 255;
  Paint p = Paint::pattern(std::shared_ptr<const Image>(tile));
  p.set_filter(ImageFilter::Nearest);
  Image image(5, 2);
  Compositor<std::uint8_t> comp;
  comp.set(ImageView<std::uint8_t>::of(image), p, Affine::translate(1, 0), CompositeOp::SourceOver);
  comp.span(1, 0, 5, 1.f);
  const int red[] = {0, 255, 0, 255, 0};
  for (int x = 0; x < 5; ++x) {
    EXPECT_EQ(image.pixel(x, 1)[0], red[x]) << x;
    EXPECT_EQ(image.pixel(x, 1)[2], 255 - red[x]) << x;
    EXPECT_EQ(image.pixel(x, 0)[3], 0) << x;
  }
}

// The 8-bit bilinear sampler's vectorised arithmetic (bilinear8_run: the AVX2 clone on machines that have AVX2,
// else the SSE2 one) against its scalar definition, exactly, on random texels and weights with the extremes mixed in
// (texels 0 and 255, weights 0 and 4095, opacity 0, opaque and in between), at run lengths that leave vector tails.
TEST(BilinearSampler, VectorisedArithmeticEqualsTheScalarOne) {
  std::mt19937 rng(2024);
  auto texel = [&] {
    std::uint32_t v = rng();
    if (rng() % 4 == 0) v = rng() % 2 ? 0xFFFFFFFFu : 0u;
    if (rng() % 4 == 0) v = (v & 0x00FFFFFFu) | 0xFF000000u;
    return v;
  };
  auto weight = [&] {
    const std::uint32_t r = rng() % 8;
    return r == 0 ? 0u : r == 1 ? 4095u : static_cast<std::uint32_t>(rng() % 4096);
  };
  std::size_t compared = 0;
  for (int n : {1, 3, 7, 8, 15, 16, 31, 33, 64}) {
    for (std::uint32_t opacity : {65536u, 0u, 32768u, 65535u, 12345u}) {
      for (int round = 0; round < 40; ++round) {
        std::vector<std::uint32_t> a(n), b(n), c(n), d(n), fx(n), fy(n), out(n);
        for (int i = 0; i < n; ++i) {
          a[i] = texel(), b[i] = texel(), c[i] = texel(), d[i] = texel();
          fx[i] = weight(), fy[i] = weight();
        }
        detail::bilinear8_run(a.data(), b.data(), c.data(), d.data(), fx.data(), fy.data(), opacity, n, out.data());
        for (int i = 0; i < n; ++i) {
          ASSERT_EQ(out[i], detail::bilinear8_pixel(a[i], b[i], c[i], d[i], fx[i], fy[i], opacity))
              << "n " << n << " pixel " << i << " opacity " << opacity;
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 30000u);
  // And the scalar definition is the documented formula (64-bit arithmetic, no overflow shortcuts).
  for (int i = 0; i < 20000; ++i) {
    const std::uint32_t a = texel(), b = texel(), c = texel(), d = texel(), fx = weight(), fy = weight();
    const std::uint32_t opacity = rng() % 65537;
    std::uint32_t expect = 0;
    for (int sh = 0; sh < 32; sh += 8) {
      const std::uint64_t top = std::uint64_t{a >> sh & 255} * (4096 - fx) + std::uint64_t{b >> sh & 255} * fx;
      const std::uint64_t bottom = std::uint64_t{c >> sh & 255} * (4096 - fx) + std::uint64_t{d >> sh & 255} * fx;
      const std::uint64_t q = (top * (4096 - fy) + bottom * fy + (1u << 23)) >> 24;
      expect |= static_cast<std::uint32_t>((q * opacity + 32768) >> 16) << sh;
    }
    ASSERT_EQ(detail::bilinear8_pixel(a, b, c, d, fx, fy, opacity), expect);
  }
}

}  // namespace
}  // namespace vraster
