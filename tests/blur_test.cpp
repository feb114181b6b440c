// Gaussian blur against a slow, direct 2-D convolution in double (no truncation short of 8 sigma, no separation):
// every channel within 0.6 of a level of the exact blur at 8 and 16 bits (rounding 0.5, truncation and float
// accumulation the rest; measured worst 0.53), the bound documented in blur.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "vraster/blur.hpp"

namespace vraster {
namespace {

// Gaussian mass over [i - 1/2, i + 1/2] for standard deviation sigma (sigma <= 0: a unit impulse).
double mass(int i, double sigma) {
  if (!(sigma > 0)) return i == 0 ? 1 : 0;
  const double s2 = sigma * std::sqrt(2.0);
  return 0.5 * (std::erf((i + 0.5) / s2) - std::erf((i - 0.5) / s2));
}

template <class T>
BasicImage<T> test_image(int w, int h) {
  BasicImage<T> image(w, h);
  std::mt19937 rng(3);
  const std::uint32_t m = BasicImage<T>::kMax;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      T* p = image.pixel(x, y);
      // A filled disc, a hard-edged bar, and sparse noise.
      std::uint32_t a = 0;
      if ((x - 14) * (x - 14) + (y - 12) * (y - 12) < 64) a = m;
      if (x > 24 && x < 30) a = m / 2;
      if (rng() % 9 == 0) a = rng() % (m + 1);
      p[3] = static_cast<T>(a);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<T>(a ? rng() % (a + 1) : 0);
    }
  }
  return image;
}

template <class T>
void check_blur(double sx, double sy) {
  constexpr int kW = 40, kH = 30;
  const double m = BasicImage<T>::kMax;
  const BasicImage<T> src = test_image<T>(kW, kH);
  BasicImage<T> out = src;
  GaussianBlur blur;
  blur.apply(ImageView<T>::of(out), sx, sy);
  const int rx = sx > 0 ? static_cast<int>(std::ceil(8 * sx)) : 0, ry = sy > 0 ? static_cast<int>(std::ceil(8 * sy)) : 0;
  double worst = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      double ref[4] = {0, 0, 0, 0};
      for (int v = std::max(0, y - ry); v <= std::min(kH - 1, y + ry); ++v) {
        for (int u = std::max(0, x - rx); u <= std::min(kW - 1, x + rx); ++u) {
          const double wgt = mass(u - x, sx) * mass(v - y, sy);
          for (int c = 0; c < 4; ++c) ref[c] += wgt * src.pixel(u, v)[c];
        }
      }
      for (int c = 0; c < 4; ++c) {
        const double err = std::abs(out.pixel(x, y)[c] - ref[c]);
        worst = std::max(worst, err);
        ASSERT_LE(err, 0.6) << "sigma " << sx << "," << sy << " at (" << x << ", " << y << ") channel " << c
                            << ": " << out.pixel(x, y)[c] << " vs " << ref[c] << " of " << m;
      }
    }
  }
  std::printf("[Blur] %zu-bit sigma (%.2f, %.2f): worst |error| %.3f levels\n", sizeof(T) * 8, sx, sy, worst);
}

TEST(GaussianBlur, EightBitsWithinOneLevelOfTheExactBlur) {
  for (auto [sx, sy] : {std::pair{0.3, 0.3}, {1.0, 2.5}, {4.0, 4.0}, {0.0, 3.0}, {6.0, 0.5}, {30.0, 30.0}}) {
    check_blur<std::uint8_t>(sx, sy);
  }
}

TEST(GaussianBlur, SixteenBitsWithinOneLevelOfTheExactBlur) {
  for (auto [sx, sy] : {std::pair{0.3, 0.3}, {1.0, 2.5}, {4.0, 4.0}, {2.0, 0.0}, {30.0, 30.0}}) {
    check_blur<std::uint16_t>(sx, sy);
  }
}

TEST(GaussianBlur, ConservesMassAwayFromTheBorderAndIgnoresBadSigmas) {
  Image image(64, 64);
  for (int y = 28; y < 36; ++y) {
    for (int x = 28; x < 36; ++x) image.pixel(x, y)[3] = 255;
  }
  Image same = image;
  GaussianBlur blur;
  blur.apply(ImageView<std::uint8_t>::of(same), NAN, -1);  // nothing to do
  EXPECT_EQ(same.data, image.data);
  blur.apply(ImageView<std::uint8_t>::of(image), 2.0, 2.0);
  double sum = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) sum += image.pixel(x, y)[3];
  }
  EXPECT_NEAR(sum, 64 * 255.0, 64 * 255.0 * 0.01);  // rounding of ~1000 pixels at +-0.5 each
  EXPECT_EQ(image.pixel(32, 32)[3], image.pixel(31, 31)[3]);  // symmetric about the square's centre
}

}  // namespace
}  // namespace vraster
