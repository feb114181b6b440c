// The canvas against Cairo drawing the same pictures (tests only): path clips in each antialiasing mode,
// intersected clips, layers with opacity, draw_image scaling. Compared per premultiplied channel.
//
// Compiled to nothing unless VRASTER_WITH_CAIRO is defined: tests/*_test.cpp are globbed into vraster_tests
// (which does not link Cairo); tests/CMakeLists.txt builds this file on its own with Cairo.
//
// Tolerances, and why:
//  - Antialiased edges: Cairo's image backend samples 15 sub-scanlines per pixel where vraster computes areas, so
//    an edge pixel may differ by up to ~1/15 of full coverage (17/255); where a clip edge meets a fill edge both
//    errors multiply in, up to ~2/15. Interior pixels agree to rounding (1/255). Hence max 34/255 per channel and a
//    mean over the picture below 0.5/255.
//  - Aliased clips (and fills): both sample the pixel centre; coordinates are chosen off the tie lines, so the pixels agree
//    except where flattening differences (0.05 px tolerance in both) move an edge across a centre: at most 0.5% of
//    the pixels.
//  - Layers: premultiplied source-over of an 8-bit group scaled by the opacity, as cairo_paint_with_alpha; both
//    round to 8 bits between the steps, so 2/255 beyond the edge differences.
#ifdef VRASTER_WITH_CAIRO

#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

#include "vraster/canvas.hpp"

namespace vraster::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = 64;
constexpr double kTolerance = 0.05;

struct Diff {
  int max = 0;
  double mean = 0;
  double share_differing = 0;
};

// Cairo ARGB32 (premultiplied, native-endian 0xAARRGGBB words) against vraster RGBA bytes.
Diff compare(const Image& mine, cairo_surface_t* surface) {
  cairo_surface_flush(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  Diff d;
  double sum = 0;
  int differing = 0;
  for (int y = 0; y < mine.height; ++y) {
    for (int x = 0; x < mine.width; ++x) {
      std::uint32_t word;
      std::memcpy(&word, data + y * stride + x * 4, 4);
      const int theirs[4] = {int(word >> 16 & 255), int(word >> 8 & 255), int(word & 255), int(word >> 24)};
      const std::uint8_t* p = mine.pixel(x, y);
      int worst = 0;
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(p[c]) - theirs[c]));
      d.max = std::max(d.max, worst);
      sum += worst;
      differing += worst > 2;
    }
  }
  d.mean = sum / (mine.width * mine.height);
  d.share_differing = double(differing) / (mine.width * mine.height);
  return d;
}

struct Pair {
  Image image{kSize, kSize};
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, kSize, kSize);
  cairo_t* cr = cairo_create(surface);
  Pair() {
    image.clear(Color::transparent());
    cairo_set_tolerance(cr, kTolerance);
  }
  ~Pair() {
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
};

// A star (self-intersecting: its centre has winding 2) around (cx, cy).
void star_points(double cx, double cy, double r, const std::function<void(double, double, bool)>& emit) {
  for (int i = 0; i < 5; ++i) {
    const double a = -kPi / 2 + i * 4 * kPi / 5;
    emit(cx + r * std::cos(a), cy + r * std::sin(a), i == 0);
  }
}

void star_canvas(Canvas& c, double cx, double cy, double r) {
  star_points(cx, cy, r, [&](double x, double y, bool first) { first ? c.move_to(x, y) : c.line_to(x, y); });
  c.close_path();
}

void star_cairo(cairo_t* cr, double cx, double cy, double r) {
  star_points(cx, cy, r, [&](double x, double y, bool first) { first ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y); });
  cairo_close_path(cr);
}

// The picture every clip case fills: a background and a rotated semi-transparent bar, both through the clip.
void paint_through_clip_canvas(Canvas& c) {
  c.set_fill_color({0.95f, 0.8f, 0.1f, 1});
  c.fill_rect(0, 0, kSize, kSize);
  c.save();
  c.translate(32, 32);
  c.rotate(0.6);
  c.set_fill_color({0.1f, 0.3f, 0.9f, 0.75f});
  c.fill_rect(-30, -7.3, 60, 14.6);
  c.restore();
}

void paint_through_clip_cairo(cairo_t* cr) {
  cairo_set_source_rgba(cr, 0.95, 0.8, 0.1, 1);
  cairo_paint(cr);
  cairo_save(cr);
  cairo_translate(cr, 32, 32);
  cairo_rotate(cr, 0.6);
  cairo_set_source_rgba(cr, 0.1, 0.3, 0.9, 0.75);
  cairo_rectangle(cr, -30, -7.3, 60, 14.6);
  cairo_fill(cr);
  cairo_restore(cr);
}

TEST(CanvasCairo, PathClipsInEachAntialiasingMode) {
  for (FillRule rule : {FillRule::NonZero, FillRule::EvenOdd}) {
    for (bool aliased : {false, true}) {
      Pair p;
      {
        Canvas c(p.image);
        c.set_tolerance(kTolerance);
        // Exact area coverage: the star's edges cross inside pixels, where Analytic approximates (docs/design.md).
        c.set_anti_alias(aliased ? AntiAlias::None : AntiAlias::Exact);
        c.begin_path();
        star_canvas(c, 32.13, 31.87, 29.3);
        c.clip(rule);
        paint_through_clip_canvas(c);
      }
      cairo_set_antialias(p.cr, aliased ? CAIRO_ANTIALIAS_NONE : CAIRO_ANTIALIAS_DEFAULT);
      cairo_set_fill_rule(p.cr, rule == FillRule::EvenOdd ? CAIRO_FILL_RULE_EVEN_ODD : CAIRO_FILL_RULE_WINDING);
      star_cairo(p.cr, 32.13, 31.87, 29.3);
      cairo_clip(p.cr);
      paint_through_clip_cairo(p.cr);
      const Diff d = compare(p.image, p.surface);
      std::printf("[canvas vs cairo] clip %s %s: max %d/255, mean %.3f/255, differing %.2f%%\n", to_string(rule).data(),
                  aliased ? "aliased" : "antialiased", d.max, d.mean, 100 * d.share_differing);
      EXPECT_LE(d.max, aliased ? 255 : 34) << to_string(rule);
      EXPECT_LT(d.mean, aliased ? 2.0 : 0.5) << to_string(rule);
      if (aliased) {
        // Aliased pixels are all or nothing in both: a differing pixel is an edge crossing a centre.
        EXPECT_LE(d.share_differing, 0.005) << to_string(rule);
      }
    }
  }
}

TEST(CanvasCairo, IntersectedClips) {
  Pair p;
  {
    Canvas c(p.image);
    c.set_tolerance(kTolerance);
    c.begin_path();
    c.arc(28.3, 30.1, 22.7, 0, 2 * kPi);
    c.clip();
    c.begin_path();
    c.translate(36, 34);
    c.rotate(0.35);
    c.rect(-20.5, -17.25, 41, 34.5);
    c.reset_transform();
    c.clip();
    c.begin_path();
    c.rect(4, 4, 50, 50);  // pixel-aligned: no mask, intersects the box
    c.clip();
    paint_through_clip_canvas(c);
  }
  cairo_arc(p.cr, 28.3, 30.1, 22.7, 0, 2 * kPi);
  cairo_clip(p.cr);
  cairo_translate(p.cr, 36, 34);
  cairo_rotate(p.cr, 0.35);
  cairo_rectangle(p.cr, -20.5, -17.25, 41, 34.5);
  cairo_identity_matrix(p.cr);
  cairo_clip(p.cr);
  cairo_rectangle(p.cr, 4, 4, 50, 50);
  cairo_clip(p.cr);
  paint_through_clip_cairo(p.cr);
  const Diff d = compare(p.image, p.surface);
  std::printf("[canvas vs cairo] intersected clips: max %d/255, mean %.3f/255\n", d.max, d.mean);
  EXPECT_LE(d.max, 34);
  EXPECT_LT(d.mean, 0.5);
}

TEST(CanvasCairo, LayersWithOpacity) {
  for (float opacity : {1.0f, 0.6f, 0.25f}) {
    Pair p;
    {
      Canvas c(p.image);
      c.set_tolerance(kTolerance);
      c.set_anti_alias(AntiAlias::Exact);  // the star's edges cross inside pixels
      c.set_fill_color({0.2f, 0.7f, 0.3f, 1});
      c.fill_rect(0, 20, kSize, 24);
      c.begin_path();
      c.arc(32, 32, 26.4, 0, 2 * kPi);
      c.clip();
      c.begin_layer(opacity);
      c.set_fill_color({0.9f, 0.1f, 0.2f, 0.9f});
      c.begin_path();
      star_canvas(c, 30.6, 33.2, 27.1);
      c.fill();
      c.set_fill_color({0.1f, 0.2f, 0.95f, 1});
      c.fill_rect(10.5, 8.25, 30, 20);
      c.end_layer();
    }
    cairo_set_source_rgba(p.cr, 0.2, 0.7, 0.3, 1);
    cairo_rectangle(p.cr, 0, 20, kSize, 24);
    cairo_fill(p.cr);
    cairo_arc(p.cr, 32, 32, 26.4, 0, 2 * kPi);
    cairo_clip(p.cr);
    cairo_push_group(p.cr);
    cairo_reset_clip(p.cr);  // the clip applies once, to the group (vraster's layers)
    cairo_set_source_rgba(p.cr, 0.9, 0.1, 0.2, 0.9);
    star_cairo(p.cr, 30.6, 33.2, 27.1);
    cairo_fill(p.cr);
    cairo_set_source_rgba(p.cr, 0.1, 0.2, 0.95, 1);
    cairo_rectangle(p.cr, 10.5, 8.25, 30, 20);
    cairo_fill(p.cr);
    cairo_pop_group_to_source(p.cr);
    cairo_paint_with_alpha(p.cr, opacity);
    const Diff d = compare(p.image, p.surface);
    std::printf("[canvas vs cairo] layer opacity %.2f: max %d/255, mean %.3f/255\n", opacity, d.max, d.mean);
    EXPECT_LE(d.max, 20) << opacity;
    EXPECT_LT(d.mean, 1.0) << opacity;  // interiors: one unit of rounding of the 8-bit group, twice
  }
}

TEST(CanvasCairo, DrawImageScaling) {
  // A 6 x 5 image of distinct opaque and translucent pixels, scaled up (non-integer factors, a fractional
  // destination) with nearest and bilinear filtering; Cairo with the same filter and EXTEND_PAD.
  Image src(6, 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 6; ++x) {
      std::uint8_t* q = src.pixel(x, y);
      const int a = (x + y) % 3 == 0 ? 128 : 255;
      q[0] = static_cast<std::uint8_t>((x * 45 % 256) * a / 255);
      q[1] = static_cast<std::uint8_t>((y * 60 % 256) * a / 255);
      q[2] = static_cast<std::uint8_t>(((x + y) * 30 % 256) * a / 255);
      q[3] = static_cast<std::uint8_t>(a);
    }
  }
  cairo_surface_t* source = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 6, 5);
  {
    cairo_surface_flush(source);
    unsigned char* data = cairo_image_surface_get_data(source);
    const int stride = cairo_image_surface_get_stride(source);
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 6; ++x) {
        const std::uint8_t* q = src.pixel(x, y);
        const std::uint32_t word = std::uint32_t(q[3]) << 24 | std::uint32_t(q[0]) << 16 | std::uint32_t(q[1]) << 8 | q[2];
        std::memcpy(data + y * stride + x * 4, &word, 4);
      }
    }
    cairo_surface_mark_dirty(source);
  }
  for (bool smooth : {false, true}) {
    Pair p;
    const double dx = 3.5, dy = 5.25, dw = 53, dh = 41.5;
    {
      Canvas c(p.image);
      c.set_image_smoothing(smooth);
      c.draw_image(src, dx, dy, dw, dh);
    }
    cairo_rectangle(p.cr, dx, dy, dw, dh);
    cairo_translate(p.cr, dx, dy);
    cairo_scale(p.cr, dw / 6, dh / 5);
    cairo_set_source_surface(p.cr, source, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(p.cr), smooth ? CAIRO_FILTER_BILINEAR : CAIRO_FILTER_NEAREST);
    cairo_pattern_set_extend(cairo_get_source(p.cr), CAIRO_EXTEND_PAD);
    cairo_identity_matrix(p.cr);
    cairo_fill(p.cr);
    const Diff d = compare(p.image, p.surface);
    std::printf("[canvas vs cairo] draw_image %s: max %d/255, mean %.3f/255\n", smooth ? "bilinear" : "nearest",
                d.max, d.mean);
    // The destination edges (x 3.5 / 56.5, y 5.25 / 46.75) give exact quarter and half coverage in both; the
    // filters agree to rounding (Cairo's bilinear weights are 8-bit fixed point: a few units).
    EXPECT_LE(d.max, smooth ? 4 : 1) << smooth;
    EXPECT_LT(d.mean, smooth ? 1.0 : 0.1) << smooth;
  }
  cairo_surface_destroy(source);
}

}  // namespace
}  // namespace vraster::test

#endif  // VRASTER_WITH_CAIRO
