// Gradients (linear, two-circle radial, conic) against the slow per-pixel reference of tests/support/paint_reference.
//
// Tolerance per pixel and channel, and why:
//  - 8 bits: the compositor reads colours from a 1024-entry table at t = i / 1023, so a pixel may show the colour
//    of any t within 0.5 / 1023 of its own (after the extend mode); its value must lie within one level of the
//    range of the reference colours over [t - h, t + h], h = 0.5 / 1023. Near a hard step that range spans both
//    sides, so the step may move by h, never more.
//  - 16 bits and dithered 8 bits: computed per pixel (no table): within one level of the reference at t itself.
//  - Both add 1e-9 to h: t is computed in a different order here and in the reference, so a pixel whose t is
//    exactly a step (a hard stop, or an integer under repeat) may land on either side.
//  - Where the reference finds no circle of a radial gradient's cone, the pixel must be transparent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "support/paint_reference.hpp"
#include "vraster/composite.hpp"

namespace vraster {
namespace {

using test::Rgba;

template <class T>
BasicImage<T> draw(const Paint& paint, const Affine& user_to_device, int w, int h) {
  BasicImage<T> image(w, h);
  Compositor<T> comp;
  comp.set(ImageView<T>::of(image), paint, user_to_device, CompositeOp::Copy);
  for (int y = 0; y < h; ++y) comp.span(y, 0, w, 1.f);
  return image;
}

template <class T>
void check_gradient(const Paint& paint, const Affine& user_to_device, const std::string& what, bool table) {
  constexpr int kW = 64, kH = 48;
  const double m = sizeof(T) == 1 ? 255.0 : 65535.0;
  const BasicImage<T> image = draw<T>(paint, user_to_device, kW, kH);
  const double h = (table ? 0.5 / 1023 : 0) + 1e-9;
  int wrong = 0;
  for (int y = 0; y < kH && wrong < 5; ++y) {
    for (int x = 0; x < kW && wrong < 5; ++x) {
      const T* px = image.pixel(x, y);
      double t;
      if (!test::reference_gradient_t(paint, user_to_device, x + 0.5, y + 0.5, t)) {
        if (px[3] != 0) {
          ADD_FAILURE() << what << ": (" << x << ", " << y << ") should be transparent, alpha " << px[3];
          ++wrong;
        }
        continue;
      }
      Rgba lo{1, 1, 1, 1}, hi{0, 0, 0, 0};
      for (double dt : {-h, 0.0, h}) {
        const Rgba c = test::reference_gradient_color(paint, t + dt);
        for (std::size_t ch = 0; ch < 4; ++ch) {
          lo[ch] = std::min(lo[ch], c[ch]);
          hi[ch] = std::max(hi[ch], c[ch]);
        }
      }
      for (std::size_t ch = 0; ch < 4; ++ch) {
        const double v = px[ch];
        if (v < lo[ch] * m - 1 || v > hi[ch] * m + 1) {
          ADD_FAILURE() << what << ": (" << x << ", " << y << ") channel " << ch << " is " << v << ", reference "
                        << lo[ch] * m << " .. " << hi[ch] * m << " at t = " << t;
          ++wrong;
        }
      }
    }
  }
}

Paint with_stops(Paint p) {
  p.add_stop(0, {1, 0, 0, 1});
  p.add_stop(0.3, {1, 1, 0, 0.5f});
  p.add_stop(0.55, {0, 1, 0.5f, 1});
  p.add_stop(0.55, {0.2f, 0.2f, 1, 1});  // a hard step
  p.add_stop(1, {0, 0, 0.3f, 0.8f});
  return p;
}

const Extend kExtends[] = {Extend::Pad, Extend::Repeat, Extend::Reflect};
const char* name(Extend e) { return e == Extend::Pad ? "pad" : e == Extend::Repeat ? "repeat" : "reflect"; }

template <class T>
void check_all_kinds(bool dither) {
  const Affine device = Affine::translate(3, -2) * Affine::scale(1.5, 1.25);
  const Affine own = Affine::rotate(20, 10, 10) * Affine::scale(1, 0.8);
  struct Geometry {
    std::string label;
    Paint paint;
  };
  const Geometry geometries[] = {
      {"linear", Paint::linear({5, 6}, {30, 20})},
      {"linear-short", Paint::linear({20, 10}, {24, 12})},
      {"radial-focal-inside", Paint::radial({18, 16}, 2, {22, 18}, 20)},
      {"radial-concentric", Paint::radial({20, 16}, 4, {20, 16}, 14)},
      {"radial-r0-bigger", Paint::radial({20, 16}, 18, {24, 14}, 3)},
      {"radial-focal-outside", Paint::radial({6, 8}, 2, {28, 20}, 8)},
      {"radial-focal-outside-shrinking", Paint::radial({6, 8}, 9, {30, 22}, 3)},
      {"radial-focal-on-circle", Paint::radial({10, 16}, 0, {20, 16}, 10)},
      {"radial-equal-radii", Paint::radial({8, 10}, 6, {26, 20}, 6)},
      {"conic", Paint::conic(0.7, {20, 15})},
  };
  for (const Geometry& g : geometries) {
    for (Extend e : kExtends) {
      for (bool transformed : {false, true}) {
        Paint p = with_stops(g.paint);
        p.set_extend(e);
        p.set_dither(dither);
        if (transformed) p.set_transform(own);
        const std::string what = g.label + " " + name(e) + (transformed ? " transformed" : "");
        check_gradient<T>(p, device, what, sizeof(T) == 1 && !dither);
      }
    }
  }
}

TEST(Gradient8, EveryKindAndExtendMatchesTheReference) { check_all_kinds<std::uint8_t>(false); }
TEST(Gradient8, DitheredEveryKindAndExtendIsWithinOneLevel) { check_all_kinds<std::uint8_t>(true); }
TEST(Gradient16, EveryKindAndExtendMatchesTheReference) { check_all_kinds<std::uint16_t>(false); }

TEST(Gradient, OneStopPaintsItsColourEverywhere) {
  Paint p = Paint::linear({0, 0}, {10, 0});
  p.add_stop(0.4, {0.2f, 0.4f, 0.6f, 1});
  const Image image = draw<std::uint8_t>(p, Affine{}, 8, 4);
  for (int x = 0; x < 8; ++x) {
    EXPECT_EQ(image.pixel(x, 2)[0], 51);
    EXPECT_EQ(image.pixel(x, 2)[1], 102);
    EXPECT_EQ(image.pixel(x, 2)[2], 153);
    EXPECT_EQ(image.pixel(x, 2)[3], 255);
  }
}

TEST(Gradient, StraightAlphaInterpolation) {
  // Opaque red to transparent black: halfway is (0.5, 0, 0) at alpha 0.5, i.e. premultiplied 0.25 red (the canvas
  // interpolates straight RGBA; premultiplied interpolation would give 0.5 red).
  Paint p = Paint::linear({0, 0}, {1000, 0});
  p.add_stop(0, {1, 0, 0, 1});
  p.add_stop(1, {0, 0, 0, 0});
  const Image16 image = draw<std::uint16_t>(p, Affine::translate(-499.5, 0), 1, 1);
  EXPECT_NEAR(image.pixel(0, 0)[3], 32767.5, 1.0);
  EXPECT_NEAR(image.pixel(0, 0)[0], 16383.75, 1.0);
}

// Dithering keeps the mean of every 8 x 8 block at the exact value where plain rounding would band.
TEST(Gradient8, DitheringKeepsTheMeanOfEachBlock) {
  Paint p = Paint::linear({0, 0}, {512, 0});
  p.add_stop(0, Color::rgb8(100, 100, 100));
  p.add_stop(1, Color::rgb8(101, 101, 101));
  p.set_dither(true);
  const Image image = draw<std::uint8_t>(p, Affine{}, 512, 8);
  for (int bx = 0; bx < 512; bx += 8) {
    double sum = 0, exact = 0;
    for (int y = 0; y < 8; ++y) {
      for (int x = bx; x < bx + 8; ++x) {
        sum += image.pixel(x, y)[0];
        exact += 100 + (x + 0.5) / 512;
      }
    }
    EXPECT_NEAR(sum / 64, exact / 64, 0.1) << "block at " << bx;
  }
}

}  // namespace
}  // namespace vraster
