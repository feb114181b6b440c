// Cross-check of compositing and paint against Cairo (tests only): the same picture drawn through both.
//
// Compiled to nothing unless VRASTER_WITH_CAIRO is defined (tests/*_test.cpp are globbed into vraster_tests, which
// does not link Cairo; tests/CMakeLists.txt builds this file on its own with Cairo).
//
// What is compared, with what tolerance, and why (per channel, 8-bit levels):
//  - Operators: every pixel of a random premultiplied source image composited onto a random destination with
//    cairo_paint (full coverage) and with cairo_mask (random 8-bit coverage), against blend_row. Porter-Duff and
//    lighter: 1 level (pixman rounds each product separately, vraster rounds the whole formula once). Separable
//    blend modes: 2 levels (pixman's integer blend arithmetic). Non-separable (HSL) modes: 3 levels (pixman
//    computes them in integer steps with truncation), at full coverage only: through a mask, pixman 0.42's HSL
//    results differ from the W3C formula with the source scaled by coverage by up to ~90 levels, while ours
//    match that formula to 0.51 of a level (tests/composite_test.cpp). Cairo's SOURCE and CLEAR lerp by the mask
//    where the HTML canvas scales the source by coverage, so copy and clear are compared at full coverage only.
//    Color-dodge and color-burn through a mask are left out too: they divide by 1 - Cs or Cs, so the rounding of
//    the masked source (we round it to 8 bits as the first of our three steps) is amplified to 10+ levels; both
//    are checked against the stepwise rule in tests/composite_test.cpp.
//  - Gradients: linear and two-circle radial (focal inside, concentric, focal outside) with a translucent stop and
//    a hard step, in pad, repeat and reflect, with a paint transform. 2 levels (pixman interpolates in 16.16 fixed
//    point), except pixels within 1/256 in t of a discontinuity (hard step, repeat wrap, cone edge), which may
//    fall on either side and are left out: at most 8% of the pixels of a picture.
//  - Image patterns: nearest and bilinear, extend none / pad / repeat / reflect (both axes, as Cairo has it),
//    scaled and rotated: nearest 1 level, bilinear 4 levels (pixman quantizes bilinear weights to 7 bits and
//    rounds after each of its lerps; we weight in float and round once, within 1 level of the exact value). Nearest at texel borders may pick
//    either side: pixels whose sample point is within 1e-3 of a texel border are left out. Bicubic is compared with
//    the slow reference only (tests/pattern_test.cpp): Cairo's GOOD and BEST pick their kernels by scale factor
//    and quantize filter phases, so no fixed Cairo setting is our Catmull-Rom.
//  - Conic gradients: Cairo has none; tests/gradient_test.cpp checks them against the slow reference.
#ifdef VRASTER_WITH_CAIRO

#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "support/paint_reference.hpp"
#include "vraster/composite.hpp"

namespace vraster {
namespace {

constexpr int kW = 64, kH = 48;

cairo_operator_t cairo_op(CompositeOp op) {
  switch (op) {
    case CompositeOp::SourceOver: return CAIRO_OPERATOR_OVER;
    case CompositeOp::Copy: return CAIRO_OPERATOR_SOURCE;
    case CompositeOp::SourceIn: return CAIRO_OPERATOR_IN;
    case CompositeOp::SourceOut: return CAIRO_OPERATOR_OUT;
    case CompositeOp::SourceAtop: return CAIRO_OPERATOR_ATOP;
    case CompositeOp::DestinationOver: return CAIRO_OPERATOR_DEST_OVER;
    case CompositeOp::DestinationIn: return CAIRO_OPERATOR_DEST_IN;
    case CompositeOp::DestinationOut: return CAIRO_OPERATOR_DEST_OUT;
    case CompositeOp::DestinationAtop: return CAIRO_OPERATOR_DEST_ATOP;
    case CompositeOp::Xor: return CAIRO_OPERATOR_XOR;
    case CompositeOp::Lighter: return CAIRO_OPERATOR_ADD;
    case CompositeOp::Clear: return CAIRO_OPERATOR_CLEAR;
    case CompositeOp::Multiply: return CAIRO_OPERATOR_MULTIPLY;
    case CompositeOp::Screen: return CAIRO_OPERATOR_SCREEN;
    case CompositeOp::Overlay: return CAIRO_OPERATOR_OVERLAY;
    case CompositeOp::Darken: return CAIRO_OPERATOR_DARKEN;
    case CompositeOp::Lighten: return CAIRO_OPERATOR_LIGHTEN;
    case CompositeOp::ColorDodge: return CAIRO_OPERATOR_COLOR_DODGE;
    case CompositeOp::ColorBurn: return CAIRO_OPERATOR_COLOR_BURN;
    case CompositeOp::HardLight: return CAIRO_OPERATOR_HARD_LIGHT;
    case CompositeOp::SoftLight: return CAIRO_OPERATOR_SOFT_LIGHT;
    case CompositeOp::Difference: return CAIRO_OPERATOR_DIFFERENCE;
    case CompositeOp::Exclusion: return CAIRO_OPERATOR_EXCLUSION;
    case CompositeOp::Hue: return CAIRO_OPERATOR_HSL_HUE;
    case CompositeOp::Saturation: return CAIRO_OPERATOR_HSL_SATURATION;
    case CompositeOp::Color: return CAIRO_OPERATOR_HSL_COLOR;
    case CompositeOp::Luminosity: return CAIRO_OPERATOR_HSL_LUMINOSITY;
  }
  return CAIRO_OPERATOR_OVER;
}

// An ARGB32 Cairo surface <-> RGBA bytes.
struct CairoImage {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, kW, kH);
  ~CairoImage() { cairo_surface_destroy(surface); }
  CairoImage() = default;
  CairoImage(const CairoImage&) = delete;
  CairoImage& operator=(const CairoImage&) = delete;

  void load(const Image& image) {
    cairo_surface_flush(surface);
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        const std::uint8_t* p = image.pixel(x, y);
        const std::uint32_t v = std::uint32_t{p[3]} << 24 | std::uint32_t{p[0]} << 16 | std::uint32_t{p[1]} << 8 | p[2];
        std::memcpy(data + y * stride + x * 4, &v, 4);
      }
    }
    cairo_surface_mark_dirty(surface);
  }
  Image read() const {
    cairo_surface_flush(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    Image out(kW, kH);
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        std::uint32_t v;
        std::memcpy(&v, data + y * stride + x * 4, 4);
        std::uint8_t* p = out.pixel(x, y);
        p[0] = static_cast<std::uint8_t>(v >> 16);
        p[1] = static_cast<std::uint8_t>(v >> 8);
        p[2] = static_cast<std::uint8_t>(v);
        p[3] = static_cast<std::uint8_t>(v >> 24);
      }
    }
    return out;
  }
};

Image random_image(unsigned seed) {
  Image image(kW, kH);
  std::mt19937 rng(seed);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      const unsigned pick = rng() % 8;
      const std::uint32_t a = pick == 0 ? 255 : pick == 1 ? 0 : rng() % 256;
      p[3] = static_cast<std::uint8_t>(a);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(rng() % (a + 1));
    }
  }
  return image;
}

// Compares two images; pixels where `skip` says so are left out. Returns the number of channels off by more
// than `tolerance` (first few reported).
int compare(const Image& ours, const Image& cairo, int tolerance, const std::string& what,
            const std::vector<bool>* skip = nullptr) {
  int bad = 0, worst = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (skip && (*skip)[static_cast<std::size_t>(y * kW + x)]) continue;
      for (int c = 0; c < 4; ++c) {
        const int d = std::abs(ours.pixel(x, y)[c] - cairo.pixel(x, y)[c]);
        worst = std::max(worst, d);
        if (d > tolerance && ++bad <= 3) {
          ADD_FAILURE() << what << ": (" << x << ", " << y << ") channel " << c << ": vraster "
                        << int(ours.pixel(x, y)[c]) << ", cairo " << int(cairo.pixel(x, y)[c]);
        }
      }
    }
  }
  ::testing::Test::RecordProperty(what, worst);
  return bad;
}

int op_tolerance(CompositeOp op) {
  if (op < CompositeOp::Multiply) return 1;
  if (op < CompositeOp::Hue) return 2;
  return 3;
}

TEST(PaintCairo, EveryOperatorAtFullCoverage) {
  const Image src = random_image(1), dst = random_image(2);
  for (int k = 0; k < kCompositeOpCount; ++k) {
    const auto op = static_cast<CompositeOp>(k);
    Image ours = dst;
    blend_row(op, ours.data.data(), src.data.data(), nullptr, nullptr, kW * kH);
    CairoImage target, source;
    target.load(dst);
    source.load(src);
    cairo_t* cr = cairo_create(target.surface);
    cairo_set_source_surface(cr, source.surface, 0, 0);
    cairo_set_operator(cr, cairo_op(op));
    cairo_paint(cr);
    cairo_destroy(cr);
    compare(ours, target.read(), op_tolerance(op), std::string(to_string(op)));
  }
}

TEST(PaintCairo, EveryOperatorThroughACoverageMask) {
  const Image src = random_image(3), dst = random_image(4);
  std::mt19937 rng(5);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(kW * kH));
  for (auto& m : mask) m = static_cast<std::uint8_t>(rng() % 3 == 0 ? 255 : rng() % 256);
  std::vector<float> coverage(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) coverage[i] = mask[i] / 255.f;
  cairo_surface_t* mask_surface = cairo_image_surface_create(CAIRO_FORMAT_A8, kW, kH);
  cairo_surface_flush(mask_surface);
  for (int y = 0; y < kH; ++y) {
    std::memcpy(cairo_image_surface_get_data(mask_surface) + y * cairo_image_surface_get_stride(mask_surface),
                &mask[static_cast<std::size_t>(y * kW)], kW);
  }
  cairo_surface_mark_dirty(mask_surface);
  for (int k = 0; k < kCompositeOpCount; ++k) {
    const auto op = static_cast<CompositeOp>(k);
    if (op == CompositeOp::Copy || op == CompositeOp::Clear) continue;  // Cairo lerps these by the mask
    if (op >= CompositeOp::Hue) continue;  // pixman's masked HSL path disagrees with the formula (see the top)
    if (op == CompositeOp::ColorDodge || op == CompositeOp::ColorBurn) continue;  // ill-conditioned (see the top)
    Image ours = dst;
    blend_row(op, ours.data.data(), src.data.data(), coverage.data(), nullptr, kW * kH);
    CairoImage target, source;
    target.load(dst);
    source.load(src);
    cairo_t* cr = cairo_create(target.surface);
    cairo_set_source_surface(cr, source.surface, 0, 0);
    cairo_set_operator(cr, cairo_op(op));
    cairo_mask_surface(cr, mask_surface, 0, 0);
    cairo_destroy(cr);
    compare(ours, target.read(), op_tolerance(op), std::string(to_string(op)) + " masked");
  }
  cairo_surface_destroy(mask_surface);
}

// Draws `paint` over the whole target with copy (vraster) and SOURCE (Cairo).
Image draw_ours(const Paint& paint, const Affine& device) {
  Image image(kW, kH);
  Compositor<std::uint8_t> comp;
  comp.set(ImageView<std::uint8_t>::of(image), paint, device, CompositeOp::Copy);
  for (int y = 0; y < kH; ++y) comp.span(y, 0, kW, 1.f);
  return image;
}

cairo_matrix_t to_cairo(const Affine& m) { return {m.a, m.b, m.c, m.d, m.e, m.f}; }

Image draw_cairo(cairo_pattern_t* pattern, const Affine& device, const Affine& own) {
  CairoImage target;
  cairo_t* cr = cairo_create(target.surface);
  const cairo_matrix_t ctm = to_cairo(device);
  cairo_set_matrix(cr, &ctm);
  // Cairo's pattern matrix maps user space to pattern space: the inverse of ours.
  const cairo_matrix_t pm = to_cairo(own.inverse());
  cairo_pattern_set_matrix(pattern, &pm);
  cairo_set_source(cr, pattern);
  cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
  cairo_paint(cr);
  cairo_destroy(cr);
  return target.read();
}

cairo_extend_t cairo_extend(Extend e) {
  switch (e) {
    case Extend::Pad: return CAIRO_EXTEND_PAD;
    case Extend::Repeat: return CAIRO_EXTEND_REPEAT;
    case Extend::Reflect: return CAIRO_EXTEND_REFLECT;
    default: return CAIRO_EXTEND_NONE;
  }
}
const char* extend_name(Extend e) {
  switch (e) {
    case Extend::Pad: return "pad";
    case Extend::Repeat: return "repeat";
    case Extend::Reflect: return "reflect";
    default: return "none";
  }
}

TEST(PaintCairo, LinearAndRadialGradientsInEveryExtendMode) {
  const Affine device = Affine::translate(2, 1) * Affine::scale(1.5);
  const Affine own = Affine::rotate(15, 20, 15) * Affine::scale(1.1, 0.9);
  const ColorStop stops[] = {{0, {1, 0, 0, 1}}, {0.35, {1, 1, 0, 1}}, {0.6, {0, 0.6f, 1, 0.7f}},
                             {0.6, {0.2f, 0.9f, 0.3f, 1}}, {1, {0, 0, 0.5f, 1}}};
  struct Geometry {
    const char* label;
    bool radial;
    Point p0, p1;
    double r0, r1;
  };
  const Geometry geometries[] = {
      {"linear", false, {6, 6}, {30, 20}, 0, 0},
      {"radial-focal-inside", true, {18, 14}, {21, 16}, 2, 18},
      {"radial-concentric", true, {20, 15}, {20, 15}, 3, 12},
      {"radial-focal-outside", true, {6, 8}, {26, 20}, 2, 7},
  };
  int left_out = 0, total = 0;
  for (const Geometry& g : geometries) {
    for (Extend e : {Extend::Pad, Extend::Repeat, Extend::Reflect}) {
      Paint paint = g.radial ? Paint::radial(g.p0, g.r0, g.p1, g.r1) : Paint::linear(g.p0, g.p1);
      cairo_pattern_t* pattern = g.radial ? cairo_pattern_create_radial(g.p0.x, g.p0.y, g.r0, g.p1.x, g.p1.y, g.r1)
                                          : cairo_pattern_create_linear(g.p0.x, g.p0.y, g.p1.x, g.p1.y);
      for (const ColorStop& s : stops) {
        paint.add_stop(s.offset, s.color);
        cairo_pattern_add_color_stop_rgba(pattern, s.offset, s.color.r, s.color.g, s.color.b, s.color.a);
      }
      paint.set_extend(e);
      paint.set_transform(own);
      cairo_pattern_set_extend(pattern, cairo_extend(e));
      cairo_pattern_set_filter(pattern, CAIRO_FILTER_GOOD);
      const Image ours = draw_ours(paint, device);
      const Image theirs = draw_cairo(pattern, device, own);
      cairo_pattern_destroy(pattern);
      // Leave out pixels within 1/256 in t of a discontinuity: where the reference colour jumps across that range.
      std::vector<bool> skip(static_cast<std::size_t>(kW * kH), false);
      for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
          double t;
          bool near = false;
          const bool has = test::reference_gradient_t(paint, device, x + 0.5, y + 0.5, t);
          for (double dx : {-0.5, 0.5}) {
            for (double dy : {-0.5, 0.5}) {
              double t2;
              const bool has2 = test::reference_gradient_t(paint, device, x + 0.5 + dx, y + 0.5 + dy, t2);
              if (has != has2) near = true;
            }
          }
          if (has && !near) {
            const test::Rgba a = test::reference_gradient_color(paint, t - 1.0 / 256);
            const test::Rgba b = test::reference_gradient_color(paint, t + 1.0 / 256);
            for (std::size_t c = 0; c < 4; ++c) near = near || std::abs(a[c] - b[c]) > 24.0 / 255;
          }
          skip[static_cast<std::size_t>(y * kW + x)] = near;
          left_out += near;
          ++total;
        }
      }
      compare(ours, theirs, 2, std::string(g.label) + " " + extend_name(e), &skip);
    }
  }
  EXPECT_LT(left_out, total * 8 / 100) << "too many pixels left out near discontinuities";
}

TEST(PaintCairo, ImagePatternsNearestAndBilinearInEveryExtendMode) {
  auto tile = std::make_shared<Image>(9, 7);
  std::mt19937 rng(8);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 9; ++x) {
      std::uint8_t* p = tile->pixel(x, y);
      const std::uint32_t a = (x + y) % 4 == 0 ? 255 : rng() % 256;
      p[3] = static_cast<std::uint8_t>(a);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(rng() % (a + 1));
    }
  }
  cairo_surface_t* tile_surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 9, 7);
  cairo_surface_flush(tile_surface);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 9; ++x) {
      const std::uint8_t* p = tile->pixel(x, y);
      const std::uint32_t v = std::uint32_t{p[3]} << 24 | std::uint32_t{p[0]} << 16 | std::uint32_t{p[1]} << 8 | p[2];
      std::memcpy(cairo_image_surface_get_data(tile_surface) + y * cairo_image_surface_get_stride(tile_surface) + x * 4,
                  &v, 4);
    }
  }
  cairo_surface_mark_dirty(tile_surface);
  const Affine device = Affine::translate(3, 2) * Affine::scale(1.25);
  const Affine owns[] = {Affine::translate(5.3, 4.1) * Affine::scale(2.6, 1.9),
                         Affine::rotate(25, 12, 10) * Affine::scale(1.7) * Affine::translate(1.2, 0.7)};
  for (ImageFilter f : {ImageFilter::Nearest, ImageFilter::Bilinear}) {
    for (Extend e : {Extend::None, Extend::Pad, Extend::Repeat, Extend::Reflect}) {
      for (std::size_t k = 0; k < std::size(owns); ++k) {
        Paint paint = Paint::pattern(std::shared_ptr<const Image>(tile));
        paint.set_filter(f);
        paint.set_extend(e);
        paint.set_transform(owns[k]);
        cairo_pattern_t* pattern = cairo_pattern_create_for_surface(tile_surface);
        cairo_pattern_set_extend(pattern, cairo_extend(e));
        cairo_pattern_set_filter(pattern, f == ImageFilter::Nearest ? CAIRO_FILTER_NEAREST : CAIRO_FILTER_BILINEAR);
        const Image ours = draw_ours(paint, device);
        const Image theirs = draw_cairo(pattern, device, owns[k]);
        cairo_pattern_destroy(pattern);
        std::vector<bool> skip(static_cast<std::size_t>(kW * kH), false);
        if (f == ImageFilter::Nearest) {
          const Affine to_paint = (device * owns[k]).inverse();
          for (int y = 0; y < kH; ++y) {
            for (int x = 0; x < kW; ++x) {
              const Point p = to_paint.apply({x + 0.5, y + 0.5});
              const double fx = p.x - std::floor(p.x), fy = p.y - std::floor(p.y);
              skip[static_cast<std::size_t>(y * kW + x)] =
                  std::min(fx, 1 - fx) < 1e-3 || std::min(fy, 1 - fy) < 1e-3;
            }
          }
        }
        compare(ours, theirs, f == ImageFilter::Nearest ? 1 : 4,
                std::string(f == ImageFilter::Nearest ? "nearest " : "bilinear ") + extend_name(e) + " " +
                    std::to_string(k),
                &skip);
      }
    }
  }
  cairo_surface_destroy(tile_surface);
}

}  // namespace
}  // namespace vraster

#endif  // VRASTER_WITH_CAIRO
