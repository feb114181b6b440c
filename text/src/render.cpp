// Glyph rendering through the core rasterizer.
//
//   1. per glyph:  outline (font units, cached per glyph in the Font) -> device transform
//   2a. axis-aligned transform, size <= kMaxCachedGlyphSize, caching on:
//        pen x rounded to 1/phases px, y to 1 px -> cache key -> mask (on a miss: flatten -> Rasterizer::fill_mask)
//        -> Renderer::mask -> the caller's CoverageSink
//   2b. otherwise: Renderer::fill of the outline with the full transform (rotation, skew, mirror, huge sizes)
//        -> the caller's CoverageSink
// Either way the glyph's coverage goes to one sink: the compositor decides the colour, the operator and the clip.
#include <algorithm>
#include <bit>
#include <cmath>

#include "vraster/error.hpp"
#include "vraster_text/render.hpp"

namespace vraster::text {
namespace {

// Coverage into an 8-bit mask, rounded the way the 8-bit compositor rounds (so a cached glyph composites exactly
// like the same glyph filled straight onto the image).
class MaskSink final : public CoverageSink {
 public:
  explicit MaskSink(GlyphMask& mask) : mask_(mask) {}
  void span(int y, int x0, int x1, float coverage) override {
    const auto v = static_cast<std::uint8_t>(static_cast<std::uint32_t>(coverage * 255.f + 0.5f));
    std::fill_n(mask_.coverage.data() + static_cast<std::size_t>(y) * mask_.width + x0, x1 - x0, v);
  }
  void row(int y, int x0, int x1, const float* coverage) override {
    std::uint8_t* out = mask_.coverage.data() + static_cast<std::size_t>(y) * mask_.width + x0;
    for (int i = 0; i < x1 - x0; ++i) out[i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(coverage[i] * 255.f + 0.5f));
  }

 private:
  GlyphMask& mask_;
};

std::uint32_t options_code(const GlyphRenderOptions& o, int phases) {
  const auto tol = static_cast<std::uint32_t>(std::clamp(std::lround(o.tolerance * 1000.0), 0l, 0xFFFFl));
  // aa: 4 bits (11 modes), rule: 3, hinting: 2, phases (up to 16): 5, tolerance in 1/1000 px: 16 -> 30 bits.
  return static_cast<std::uint32_t>(o.aa) | static_cast<std::uint32_t>(o.rule) << 4 |
         static_cast<std::uint32_t>(o.hinting) << 7 | static_cast<std::uint32_t>(phases) << 9 | tol << 14;
}

bool axis_aligned(const Affine& m) { return m.b == 0 && m.c == 0 && m.a > 0 && m.d > 0; }

}  // namespace

GlyphMask GlyphRasterizer::rasterize(const Font& font, std::uint32_t glyph, double size_x, double size_y,
                                     double phase_x, double phase_y, const GlyphRenderOptions& options) {
  check_font_size(size_x);
  check_font_size(size_y);
  GlyphMask mask;
  // The outline and its map to device pixels (pen at the phase).
  Path hinted;
  const Path* path = nullptr;
  Rect cb;
  Affine to_device;
  if (options.hinting == Hinting::Light) {
    hinted = font.outline(glyph, size_y, Hinting::Light);
    path = &hinted;
    cb = hinted.control_bounds();
    to_device = Affine::translate(phase_x, phase_y) * Affine::scale(size_x / size_y, 1.0);
  } else {
    const GlyphOutline& outline = font.glyph_outline(glyph);  // the box comes cached with the outline
    path = &outline.path;
    cb = outline.control_box;
    const double upem = font.units_per_em();
    to_device = Affine::translate(phase_x, phase_y) * Affine::scale(size_x / upem, size_y / upem);
  }
  if (path->empty()) return mask;
  const Point p0 = to_device.apply({cb.x0, cb.y0}), p1 = to_device.apply({cb.x1, cb.y1});
  const int left = static_cast<int>(std::floor(std::min(p0.x, p1.x)));
  const int top = static_cast<int>(std::floor(std::min(p0.y, p1.y)));
  const int right = static_cast<int>(std::ceil(std::max(p0.x, p1.x)));
  const int bottom = static_cast<int>(std::ceil(std::max(p0.y, p1.y)));
  if (right <= left || bottom <= top) return mask;
  if (static_cast<double>(right - left) * static_cast<double>(bottom - top) > kMaxMaskPixels) {
    throw Error("glyph " + std::to_string(glyph) + " of font '" + font.name() + "' is too large for a coverage mask (" +
                std::to_string(right - left) + " x " + std::to_string(bottom - top) + " px)");
  }
  mask.left = left;
  mask.top = top;
  mask.width = right - left;
  mask.height = bottom - top;
  mask.coverage.resize(static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height));
  lines_.clear();
  // No clip: the mask is the control box, so every point lies inside it (the clip only guards huge geometry).
  FlattenOptions fo;
  fo.tolerance = options.tolerance;
  flatten(*path, Affine::translate(-left, -top) * to_device, fo, lines_);
  if (options.aa == AntiAlias::Analytic) {
    // The core's 8-bit mask path: same coverage as the sink below to within one level, without per-row calls.
    rasterizer_.fill_mask(lines_, options.rule, mask.width, mask.height, mask.coverage.data(), mask.width);
  } else {
    MaskSink sink(mask);
    rasterizer_.fill(lines_, options.rule, options.aa, mask.width, mask.height, sink);
  }
  return mask;
}

void TextRenderer::draw_one(const Font& font, std::uint32_t glyph, double size, Point position,
                            const Affine& transform, const GlyphRenderOptions& options, int width, int height,
                            CoverageSink& sink) {
  const GlyphOutline& outline = font.glyph_outline(glyph);
  const Path& units = outline.path;
  if (units.empty()) return;  // spaces, bitmap-only glyphs
  const bool aligned = axis_aligned(transform);
  const double size_x = size * transform.a, size_y = size * transform.d;
  const Point p = transform.apply(position);
  if (!is_finite(p)) return;
  // Far outside the image (4 em of margin covers every sane glyph): nothing to do.
  const double reach = 4.0 * std::max({std::abs(size_x), std::abs(size_y), size * std::hypot(transform.a, transform.b),
                                       size * std::hypot(transform.c, transform.d)});
  if (p.x + reach < 0 || p.x - reach > width || p.y + reach < 0 || p.y - reach > height) return;

  bool cacheable = options.use_cache && aligned && size_x <= kMaxCachedGlyphSize && size_y <= kMaxCachedGlyphSize &&
                   size_x > 0 && size_y > 0;
  if (cacheable) {
    // A (broken or decorative) glyph reaching far outside its em box is drawn from its outline, clipped to the image,
    // rather than as a giant mask.
    const Rect cb = outline.control_box;
    const double upem = font.units_per_em();
    cacheable = cb.width() * size_x / upem <= kMaxCachedGlyphExtent && cb.height() * size_y / upem <= kMaxCachedGlyphExtent;
  }
  if (cacheable) {
    const int phases = std::clamp(options.subpixel_phases, 1, 16);
    const double xq = std::round(p.x * phases);
    const double ixd = std::floor(xq / phases);
    const int ix = static_cast<int>(ixd);
    const int phase = static_cast<int>(xq - ixd * phases);
    const int iy = static_cast<int>(std::lround(p.y));
    const GlyphCache::Key key{font.id(), glyph, static_cast<std::uint32_t>(phase), std::bit_cast<std::uint64_t>(size_x),
                              std::bit_cast<std::uint64_t>(size_y), options_code(options, phases)};
    auto put = [&](const GlyphMask& m) {  // the mask takes the same seam as paths: coverage -> the sink
      renderer_.mask(m.coverage.data(), m.width, m.height, m.width, ix + m.left, iy + m.top, width, height, sink);
    };
    const GlyphMask* mask = cache_.find(key);
    if (!mask) {
      GlyphMask fresh = glyph_rasterizer_.rasterize(font, glyph, size_x, size_y, static_cast<double>(phase) / phases,
                                                    0.0, options);
      mask = cache_.insert(key, std::move(fresh));
      if (!mask) {  // larger than the cache takes: draw it once, uncached
        put(glyph_rasterizer_.rasterize(font, glyph, size_x, size_y, static_cast<double>(phase) / phases, 0.0,
                                        options));
        return;
      }
    }
    put(*mask);
    return;
  }
  // From outlines: the full transform, exact pen position.
  FillOptions fo;
  fo.rule = options.rule;
  fo.aa = options.aa;
  fo.tolerance = options.tolerance;
  if (options.hinting == Hinting::Light && aligned) {
    const Path hinted = font.outline(glyph, size_y, Hinting::Light);
    renderer_.fill(hinted, Affine::translate(p.x, p.y) * Affine::scale(size_x / size_y, 1.0), fo, width, height, sink);
  } else {
    const double s = size / font.units_per_em();
    renderer_.fill(units, transform * Affine::translate(position.x, position.y) * Affine::scale(s), fo, width, height,
                   sink);
  }
}

void TextRenderer::draw(const TextLayout& layout, const Affine& transform, const GlyphRenderOptions& options,
                        int width, int height, CoverageSink& sink) {
  if (!transform.is_finite()) throw Error("text transform is not finite");
  if (layout.glyphs.empty()) return;
  check_font_size(layout.size);
  for (const PositionedGlyph& g : layout.glyphs) {
    draw_one(*layout.fonts.at(g.font), g.glyph, layout.size, g.position, transform, options, width, height, sink);
  }
}

void TextRenderer::draw_glyph(const Font& font, std::uint32_t glyph, double size, Point position,
                              const Affine& transform, const GlyphRenderOptions& options, int width, int height,
                              CoverageSink& sink) {
  if (!transform.is_finite()) throw Error("text transform is not finite");
  check_font_size(size);
  draw_one(font, glyph, size, position, transform, options, width, height, sink);
}

void TextRenderer::draw(Image& image, const TextLayout& layout, Color color, const Affine& transform,
                        const GlyphRenderOptions& options) {
  if (!transform.is_finite()) throw Error("text transform is not finite");
  if (!(color.a > 0) || layout.glyphs.empty()) return;
  SolidCompositor<std::uint8_t> out(image, color);
  draw(layout, transform, options, image.width, image.height, out);
}

void TextRenderer::draw_glyph(Image& image, const Font& font, std::uint32_t glyph, double size, Point position,
                              Color color, const Affine& transform, const GlyphRenderOptions& options) {
  if (!transform.is_finite()) throw Error("text transform is not finite");
  check_font_size(size);
  if (!(color.a > 0)) return;
  SolidCompositor<std::uint8_t> out(image, color);
  draw_one(font, glyph, size, position, transform, options, image.width, image.height, out);
}

void TextRenderer::append_outlines(const TextLayout& layout, Path& out, Hinting hinting) {
  for (const PositionedGlyph& g : layout.glyphs) {
    const Font& font = *layout.fonts.at(g.font);
    if (hinting == Hinting::Light) {
      out.add_path(font.outline(g.glyph, layout.size, Hinting::Light)
                       .transformed(Affine::translate(g.position.x, g.position.y)));
    } else {
      const double s = layout.size / font.units_per_em();
      out.add_path(font.outline_units(g.glyph).transformed(Affine::translate(g.position.x, g.position.y) *
                                                          Affine::scale(s)));
    }
  }
}

}  // namespace vraster::text
