// The canvas's clip mask in levels of the channel type (8 bits: 0 .. 255; 16 bits: 0 .. 65535) against what the
// float mask did before: the rasterizer's float coverage of the clip, multiplied in float for nested clips, then
// quantized by the compositor as round(M * c) and lerped. One clip: the same levels (the quantization only moved
// from use to creation). Nested clips: the product is now rounded per clip, so a level may differ by one, and so
// may a pixel (a lerp by c +- 1 / M moves the result by at most |r - d| / M <= 1 level, plus its rounding).
// The tolerance is therefore one level, and most pixels must match exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "support/capture.hpp"
#include "vraster/canvas.hpp"

namespace vraster::test {
namespace {

constexpr int kW = 120, kH = 90;

Path clip_a() {
  Path p;
  p.add_circle({55.3, 44.7}, 38.2);
  return p;
}
Path clip_b() {
  Path p;
  p.move_to(5.5, 80.25);
  p.line_to(110.75, 12.5);
  p.line_to(100.2, 85.9);
  p.close();
  return p;
}

// The float coverage the rasterizer gives a clip path (the old mask's contents).
std::vector<float> float_coverage(const Path& path, AntiAlias aa) {
  Polylines lines;
  flatten(path, Affine{}, FlattenOptions{}, lines);
  CoverageGrid grid(kW, kH);
  Rasterizer r;
  r.fill(lines, FillRule::NonZero, aa, kW, kH, grid);
  std::vector<float> out(static_cast<std::size_t>(kW) * kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) out[static_cast<std::size_t>(y) * kW + x] = grid.at(x, y);
  }
  return out;
}

template <class T>
void prepare(BasicImage<T>& image) {
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    image.data[i] = static_cast<T>((i * 37 % 101) * BasicImage<T>::kMax / 100);  // opaque-ish varied background
    if (i % 4 == 3) image.data[i] = BasicImage<T>::kMax;
  }
}

// Draws `draw` on a canvas clipped by `clips`, and on an unclipped one; the clipped result must be the unclipped
// one lerped by the old float mask's quantized level, to within `tolerance` levels. Returns the share of exact pixels.
template <class T, class Draw>
double compare(const std::vector<const Path*>& clips, AntiAlias aa, Draw draw, int tolerance) {
  constexpr double M = BasicImage<T>::kMax;
  BasicImage<T> clipped(kW, kH), plain(kW, kH);
  prepare(clipped);
  prepare(plain);
  const BasicImage<T> before = clipped;
  {
    Canvas c(clipped);
    c.set_anti_alias(aa);
    for (const Path* p : clips) c.clip(*p, FillRule::NonZero);
    draw(c);
  }
  {
    Canvas c(plain);
    c.set_anti_alias(aa);
    draw(c);
  }
  std::vector<float> mask(static_cast<std::size_t>(kW) * kH, 1.f);
  for (const Path* p : clips) {
    const std::vector<float> m = float_coverage(*p, aa);
    for (std::size_t i = 0; i < mask.size(); ++i) mask[i] *= m[i];
  }
  std::size_t exact = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const float m = mask[i];
    const double c = !(m > 0) ? 0 : m >= 1 ? M : std::floor(static_cast<double>(m) * M + 0.5);
    for (std::size_t ch = 0; ch < 4; ++ch) {
      const double d = before.data[i * 4 + ch], r = plain.data[i * 4 + ch];
      const double expect = std::round((d * (M - c) + r * c) / M);
      const double got = clipped.data[i * 4 + ch];
      EXPECT_LE(std::abs(got - expect), tolerance) << "pixel " << i % kW << "," << i / kW << " channel " << ch;
      exact += got == expect;
    }
  }
  return static_cast<double>(exact) / (mask.size() * 4);
}

void fill_translucent(Canvas& c) {
  c.set_fill_color({0.9f, 0.3f, 0.2f, 0.7f});
  c.fill_rect(-10, -10, 200, 200);
}
void fill_opaque_shape(Canvas& c) {
  Path p;
  p.add_ellipse({60, 45}, 50, 35);
  c.set_fill_color({0.1f, 0.6f, 0.3f, 1});
  c.fill(p);
}
void copy_shape(Canvas& c) {  // unbounded: the whole clip region is composited
  Path p;
  p.add_ellipse({50, 40}, 30, 25);
  c.set_composite(CompositeOp::Copy);
  c.set_fill_color({0.3f, 0.3f, 0.9f, 0.6f});
  c.fill(p);
}

template <class T>
void check_all() {
  const Path a = clip_a(), b = clip_b();
  for (AntiAlias aa : {AntiAlias::Analytic, AntiAlias::Ssaa4, AntiAlias::None}) {
    for (auto draw : {fill_translucent, fill_opaque_shape, copy_shape}) {
      // One clip: the old float mask quantized at use gives these levels; the tolerance only absorbs the round-off
      // of rasterizing the clip relative to its mask's corner instead of the image's.
      EXPECT_GT(compare<T>({&a}, aa, draw, 1), 0.999) << to_string(aa);
      EXPECT_GT(compare<T>({&a, &b}, aa, draw, 1), 0.99) << to_string(aa) << " nested";
    }
  }
}

TEST(ClipMask, LevelsMatchTheFloatMask8) { check_all<std::uint8_t>(); }
TEST(ClipMask, LevelsMatchTheFloatMask16) { check_all<std::uint16_t>(); }

}  // namespace
}  // namespace vraster::test
