// Glyph rendering: cache equals outline drawing, subpixel phases, LRU bound, transformed text from outlines,
// antialiasing modes and fill rules, ink bounds.
#include <gtest/gtest.h>

#include <cmath>

#include "text_support.hpp"
#include "vraster/error.hpp"
#include "vraster/png.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;
using namespace vraster::text::testing;

namespace {

const FontList& default_fonts() {
  static const FontList fonts = FontList::default_list();  // one Font, so glyph cache keys repeat across calls
  return fonts;
}

Image draw_text(const std::string& text, double size, Point origin, const GlyphRenderOptions& options,
                const Affine& transform = {}, int w = 240, int h = 80, TextRenderer* renderer = nullptr) {
  TextStyle style;
  style.size = size;
  const TextLayout layout = layout_text(text, default_fonts(), style, {}, origin);
  Image image(w, h);
  TextRenderer local;
  (renderer ? *renderer : local).draw(image, layout, Color::rgb8(0, 0, 0), transform, options);
  return image;
}

int max_alpha_diff(const Image& a, const Image& b) {
  int m = 0;
  for (std::size_t i = 3; i < a.data.size(); i += 4) m = std::max(m, std::abs(a.data[i] - b.data[i]));
  return m;
}

}  // namespace

TEST(GlyphRender, CachedGlyphsEqualOutlinesDrawnAtTheSamePhase) {
  GlyphRenderOptions cached, direct;
  direct.use_cache = false;
  // Pen positions on the quarter-pixel grid: the cache's phase is then the exact position.
  for (double x : {10.0, 10.25, 10.5, 10.75}) {
    TextStyle style;
    style.size = 20;
    auto fonts = FontList::default_list();
    TextLayout layout = layout_text("Hamburgefonstiv", fonts, style);
    for (auto& g : layout.glyphs) g.position.x = std::round(g.position.x * 4) / 4;  // snap every pen to 1/4 px
    Image a(240, 40), b(240, 40);
    TextRenderer r1, r2;
    r1.draw(a, layout, Color::rgb8(0, 0, 0), Affine::translate(x, 28), cached);
    r2.draw(b, layout, Color::rgb8(0, 0, 0), Affine::translate(x, 28), direct);
    // Same outline, same rasterizer, same position; only round-off differs, which can flip Wang's segment count
    // of a curve (n = ceil(...)) and so move a polyline by up to the 0.1 px tolerance: at most 0.1 * 255 = 26 levels
    // on a pixel an edge crosses, and on very few pixels.
    int differing = 0;
    for (std::size_t i = 3; i < a.data.size(); i += 4) differing += std::abs(a.data[i] - b.data[i]) > 1;
    EXPECT_LE(max_alpha_diff(a, b), 26) << x;
    EXPECT_LE(differing, 4) << x;
    EXPECT_GT(r1.cache().stats().entries, 0u);
    EXPECT_EQ(r2.cache().stats().entries, 0u);
  }
}

TEST(GlyphRender, SubpixelPhasesMoveTheStemByAQuarterPixel) {
  // The stem of "l" is a rectangle about 2.1 px wide: in a row through it, the left edge lies at
  // x + 1 - coverage(x) for the first inked pixel x (the pixel after it is fully covered).
  GlyphRenderOptions options;
  const auto left_edge = [&](double pen_x) {
    const Image img = draw_text("l", 24, {pen_x, 40}, options);
    for (int x = 0; x < img.width; ++x) {
      const int c = img.pixel(x, 30)[3];
      if (c > 0) return x + 1 - c / 255.0;
    }
    return -1.0;
  };
  const double e0 = left_edge(20.0);
  const double q = 1.0 / 255;  // one coverage level
  EXPECT_NEAR(left_edge(20.25) - e0, 0.25, q);
  EXPECT_NEAR(left_edge(20.5) - e0, 0.5, q);
  EXPECT_NEAR(left_edge(20.75) - e0, 0.75, q);
  EXPECT_NEAR(left_edge(21.0) - e0, 1.0, q);
  // Positions between phases are rounded to the nearest quarter.
  EXPECT_NEAR(left_edge(20.30) - e0, 0.25, q);
  EXPECT_NEAR(left_edge(20.40) - e0, 0.5, q);
  // With one phase, positions snap to whole pixels.
  options.subpixel_phases = 1;
  EXPECT_NEAR(left_edge(20.4) - left_edge(20.0), 0.0, 1e-12);
  // Without the cache the pen position is exact.
  options.use_cache = false;
  EXPECT_NEAR(left_edge(20.1) - e0, 0.1, q);
}

TEST(GlyphRender, CacheIsBoundedAndEvictsLeastRecentlyUsed) {
  GlyphCache cache(64 * 1024);
  const auto font = Font::load_default();
  GlyphRasterizer raster;
  std::size_t peak = 0;
  for (std::uint32_t g = 1; g < 400; ++g) {
    GlyphCache::Key key{font->id(), g, 0, 0, 0, 0};
    if (!cache.find(key)) cache.insert(key, raster.rasterize(*font, g, 32, 32, 0, 0, {}));
    peak = std::max(peak, cache.stats().bytes);
    if (g > 2) {  // keep glyph 1 in use: it must survive
      GlyphCache::Key one{font->id(), 1, 0, 0, 0, 0};
      EXPECT_NE(cache.find(one), nullptr) << g;
    }
  }
  EXPECT_LE(peak, cache.max_bytes());
  EXPECT_GT(cache.stats().evictions, 0u);
  GlyphCache::Key early{font->id(), 5, 0, 0, 0, 0};
  EXPECT_EQ(cache.find(early), nullptr);  // long unused: evicted
  cache.set_max_bytes(0);
  EXPECT_EQ(cache.stats().bytes, 0u);
}

TEST(GlyphRender, DrawingTwiceHitsTheCache) {
  TextRenderer renderer;
  GlyphRenderOptions options;
  draw_text("abcabc", 16, {4, 40}, options, {}, 240, 80, &renderer);
  const auto first = renderer.cache().stats();
  EXPECT_LE(first.misses, 6u);
  EXPECT_EQ(first.hits + first.misses, 6u);
  draw_text("abcabc", 16, {4, 40}, options, {}, 240, 80, &renderer);
  EXPECT_EQ(renderer.cache().stats().misses, first.misses);
  EXPECT_EQ(renderer.cache().stats().hits, first.hits + 6);
}

TEST(GlyphRender, TransformedTextIsDrawnFromOutlinesNotTheCache) {
  TextRenderer renderer;
  GlyphRenderOptions options;
  draw_text("Rotate", 20, {0, 0}, options, Affine::translate(60, 40) * Affine::rotate(30), 240, 120, &renderer);
  draw_text("Skew", 20, {0, 0}, options, Affine::translate(60, 90) * Affine::skew_x(-20), 240, 120, &renderer);
  const auto s = renderer.cache().stats();
  EXPECT_EQ(s.hits + s.misses, 0u);
  EXPECT_EQ(s.entries, 0u);
}

TEST(GlyphRender, QuarterTurnIsTheTransposedImage) {
  // Rotating by 90 degrees about the origin maps pixel (x, y) to (-y, x): the rotated rendering, read back through
  // that map, must equal the upright one up to float rounding (coverage is computed exactly either way).
  GlyphRenderOptions options;
  options.use_cache = false;
  const Image up = draw_text("Quay", 24, {0, 0}, options, Affine::translate(10, 40), 100, 100);
  const Image turned = draw_text("Quay", 24, {0, 0}, options, Affine::translate(60, 10) * Affine::rotate(90) *
                                                                    Affine::translate(10, 40) * Affine::translate(-10, -40),
                                 100, 100);
  // turned = T(60,10) R90 applied to the layout at origin 0; up = T(10,40). Point p drawn at (10 + px, 40 + py) in
  // `up` lands at (60 - py, 10 + px) in `turned`: pixel (X, Y) of up <-> pixel (60 - (Y - 40) - 1, 10 + X - 10).
  int worst = 0;
  double ink_up = 0, ink_turned = 0;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      const int tx = 60 - (y - 40) - 1, ty = x;
      const int a = up.pixel(x, y)[3];
      ink_up += a;
      if (tx >= 0 && tx < 100 && ty >= 0 && ty < 100) worst = std::max(worst, std::abs(a - turned.pixel(tx, ty)[3]));
    }
  }
  for (std::size_t i = 3; i < turned.data.size(); i += 4) ink_turned += turned.data[i];
  EXPECT_LE(worst, 2);
  EXPECT_NEAR(ink_turned / ink_up, 1.0, 1e-3);
}

TEST(GlyphRender, AliasedModeGivesOnlyFullOrNoCoverage) {
  GlyphRenderOptions options;
  options.aa = AntiAlias::None;
  const Image img = draw_text("Aliased text", 18, {4, 30}, options);
  int full = 0;
  for (std::size_t i = 3; i < img.data.size(); i += 4) {
    EXPECT_TRUE(img.data[i] == 0 || img.data[i] == 255);
    full += img.data[i] == 255;
  }
  EXPECT_GT(full, 100);
}

TEST(GlyphRender, EveryFillRuleRendersGlyphs) {
  // These Noto Sans outlines ("O", "B", "D") neither overlap nor cross themselves. TrueType outer contours run
  // clockwise in y-up font space, so after the y flip they run clockwise on screen, which the core's convention
  // (+1 for a downward edge left of the point) counts as winding -1; holes are 0. So even-odd and negative give
  // the non-zero pixels and positive gives nothing. (CFF outlines run the other way round: positive would fill.)
  GlyphRenderOptions nz;
  const Image ref = draw_text("OBD", 30, {4, 40}, nz);
  for (FillRule rule : {FillRule::EvenOdd, FillRule::Negative}) {
    GlyphRenderOptions o;
    o.rule = rule;
    EXPECT_LE(max_alpha_diff(ref, draw_text("OBD", 30, {4, 40}, o)), 1) << to_string(rule);
  }
  GlyphRenderOptions neg;
  neg.rule = FillRule::Positive;
  const Image none = draw_text("OBD", 30, {4, 40}, neg);
  EXPECT_EQ(ink_stats(ink_of(none, false), none.width, none.height).total, 0.0);
}

TEST(GlyphRender, InkBoundsContainTheDrawnPixels) {
  TextStyle style;
  style.size = 32;
  const TextLayout layout = layout_text("Ink: gjpqy", FontList::default_list(), style, {}, {10.3, 50.6});
  Image img(260, 90);
  GlyphRenderOptions options;
  options.use_cache = false;
  TextRenderer().draw(img, layout, Color::rgb8(0, 0, 0), {}, options);
  const InkStats s = ink_stats(ink_of(img, false), img.width, img.height);
  // Pixel boxes: every inked pixel lies in the ink box; the box's edges are within one pixel of inked pixels.
  EXPECT_GE(s.x0, std::floor(layout.ink.x0));
  EXPECT_LE(s.x1 + 1, std::ceil(layout.ink.x1));
  EXPECT_GE(s.y0, std::floor(layout.ink.y0));
  EXPECT_LE(s.y1 + 1, std::ceil(layout.ink.y1));
  EXPECT_LE(s.x0, std::floor(layout.ink.x0) + 1);
  EXPECT_GE(s.x1 + 1, std::ceil(layout.ink.x1) - 1);
  EXPECT_LE(s.y0, std::floor(layout.ink.y0) + 1);
  EXPECT_GE(s.y1 + 1, std::ceil(layout.ink.y1) - 1);
}

TEST(GlyphRender, HugeTextIsClippedNotAllocated) {
  TextStyle style;
  style.size = kMaxFontSize;  // the largest size: drawn from outlines (never cached), clipped to the image
  const TextLayout layout = layout_text("W", FontList::default_list(), style, {}, {-1000, 3000});
  Image img(64, 64);
  TextRenderer renderer;
  renderer.draw(img, layout, Color::rgb8(0, 0, 0));
  EXPECT_EQ(renderer.cache().stats().entries, 0u);
  EXPECT_THROW(renderer.draw(img, layout, Color{}, Affine{std::nan(""), 0, 0, 1, 0, 0}), Error);
}

TEST(GlyphRender, ExactCoverageMatchesAnalyticWhereContoursDoNotOverlap) {
  // Analytic coverage is exact unless edges of different winding cross inside a pixel; these outlines have no such
  // pixels, so the core's exact mode must give the same pixels (up to one level of rounding).
  GlyphRenderOptions analytic, exact;
  exact.aa = AntiAlias::Exact;
  const Image a = draw_text("OBD", 30, {4, 40}, analytic);
  const Image e = draw_text("OBD", 30, {4, 40}, exact);
  EXPECT_LE(max_alpha_diff(a, e), 1);
  EXPECT_GT(ink_stats(ink_of(e, false), e.width, e.height).total, 100);
}

TEST(GlyphRender, NonExteriorRuleFillsTheCounters) {
  // Non-exterior: everything the outside cannot reach, so the hole of "O" is filled.
  GlyphRenderOptions nz, ne;
  ne.rule = FillRule::NonExterior;
  ne.use_cache = false;
  const Image a = draw_text("O", 40, {4, 50}, nz, {}, 60, 60);
  const Image b = draw_text("O", 40, {4, 50}, ne, {}, 60, 60);
  const InkStats sa = ink_stats(ink_of(a, false), 60, 60), sb = ink_stats(ink_of(b, false), 60, 60);
  const int cx = static_cast<int>(sa.cx), cy = static_cast<int>(sa.cy);  // the middle of the counter
  EXPECT_EQ(a.pixel(cx, cy)[3], 0);
  EXPECT_EQ(b.pixel(cx, cy)[3], 255);
  EXPECT_GT(sb.total, 1.5 * sa.total);
}

TEST(GlyphRender, LightHintingMakesTheTopOfStemsCrisp) {
  // At 13 px the cap height of Noto Sans is 9.3 px: unhinted, the top row of the "H" stems is partly covered;
  // FreeType's light hinting moves it onto a pixel boundary, so the stem's top pixel is as dark as its middle.
  // Returns how much lighter the topmost inked pixel of the stem column is than the stem's middle.
  auto top_fade = [&](Hinting hinting, bool cache) {
    GlyphRenderOptions o;
    o.hinting = hinting;
    o.use_cache = cache;
    const Image img = draw_text("H", 13, {4, 30}, o, {}, 30, 40);
    int x_stem = 0;  // the darkest column of a row below the crossbar: inside the left stem
    for (int x = 0; x < 12; ++x) {
      if (img.pixel(x, 28)[3] > img.pixel(x_stem, 28)[3]) x_stem = x;
    }
    int y = 0;
    while (y < img.height && img.pixel(x_stem, y)[3] == 0) ++y;
    return img.pixel(x_stem, 28)[3] - img.pixel(x_stem, y)[3];
  };
  EXPECT_GT(top_fade(Hinting::None, true), 40);
  EXPECT_LE(top_fade(Hinting::Light, true), 1);
  EXPECT_LE(top_fade(Hinting::Light, false), 1);
}

TEST(GlyphRender, InkIsConservedAcrossSubpixelPhases) {
  // Moving a glyph by a fraction of a pixel moves its coverage, never adds or removes any: the summed coverage of
  // the mask is the glyph's area at every phase (to within rounding of each pixel to 1/255). Glyphs whose right or
  // left edge falls exactly on the mask border at one phase (U+2046 at 16 px ends at x = 4.0) are included: a
  // rasterizer that drops the last column there loses ink at that phase only.
  const auto font = default_fonts().fonts[0];
  GlyphRasterizer raster;
  std::u32string chars = U"\u2046\u2045[]|lIHEmMW#";
  for (char32_t c : chars) {
    const auto g = font->glyph_index(c);
    double ink[4];
    long pixels = 0;
    for (int phase = 0; phase < 4; ++phase) {
      const GlyphMask m = raster.rasterize(*font, g, 16, 16, phase * 0.25, 0, {});
      ink[phase] = 0;
      for (auto v : m.coverage) ink[phase] += v;
      pixels = std::max(pixels, static_cast<long>(m.coverage.size()));
    }
    for (int phase = 1; phase < 4; ++phase) {
      // Each pixel is rounded to 1/255: the sums may differ by at most half a level per pixel.
      EXPECT_NEAR(ink[phase], ink[0], 0.5 * static_cast<double>(pixels) + 1) << "U+" << std::hex << static_cast<int>(c)
                                                                            << " phase " << phase;
    }
  }
}

TEST(GlyphRender, CachedGlyphsAreClippedAtEveryImageBorder) {
  // Text hanging over all four borders: the cached blit must clip exactly like the outline fill does.
  GlyphRenderOptions cached, direct;
  cached.subpixel_phases = 1;  // whole-pixel pens: both paths place glyphs identically
  direct.use_cache = false;
  TextStyle style;
  style.size = 24;
  TextLayout layout = layout_text("Wjgy@", default_fonts(), style);
  for (auto& g : layout.glyphs) g.position.x = std::round(g.position.x);  // whole-pixel pens
  for (Point origin : {Point{-7, 10}, Point{-3, 44}, Point{20, 5}, Point{30, 48}}) {
    Image a(64, 48), b(64, 48);
    TextRenderer().draw(a, layout, Color::rgb8(0, 0, 0), Affine::translate(origin.x, origin.y), cached);
    TextRenderer().draw(b, layout, Color::rgb8(0, 0, 0), Affine::translate(origin.x, origin.y), direct);
    int differing = 0;
    for (std::size_t i = 3; i < a.data.size(); i += 4) differing += std::abs(a.data[i] - b.data[i]) > 1;
    EXPECT_LE(max_alpha_diff(a, b), 26) << origin.x << "," << origin.y;  // see CachedGlyphsEqualOutlines...
    EXPECT_LE(differing, 4) << origin.x << "," << origin.y;
    EXPECT_GT(ink_stats(ink_of(a, false), 64, 48).total, 10);
  }
}

namespace {

// Records what a CoverageSink is given: every pixel's coverage combined as the compositor combines alpha (a over b).
class AlphaRecorder final : public CoverageSink {
 public:
  AlphaRecorder(int w, int h) : w_(w), h_(h), a_(static_cast<std::size_t>(w) * h, 0.0f) {}
  void span(int y, int x0, int x1, float c) override {
    for (int x = x0; x < x1; ++x) put(x, y, c);
  }
  void row(int y, int x0, int x1, const float* c) override {
    for (int x = x0; x < x1; ++x) put(x, y, c[x - x0]);
  }
  float at(int x, int y) const { return a_[static_cast<std::size_t>(y) * w_ + x]; }
  bool out_of_bounds = false;

 private:
  void put(int x, int y, float c) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) {
      out_of_bounds = true;
      return;
    }
    float& a = a_[static_cast<std::size_t>(y) * w_ + x];
    a = c + a * (1 - c);
  }
  int w_, h_;
  std::vector<float> a_;
};

}  // namespace

// Text hands its coverage to any sink (the seam every draw call takes): cached masks and outlines alike, clipped to
// the device; the solid-colour convenience draws exactly that coverage.
TEST(GlyphRender, CoverageThroughASinkEqualsTheDrawnImage) {
  TextStyle style;
  style.size = 24;
  for (bool cache : {true, false}) {
    GlyphRenderOptions options;
    options.use_cache = cache;
    // Starts left of the image and runs off its right edge: the sink must only see device pixels.
    const TextLayout layout = layout_text("Wavy glyphs", default_fonts(), style, {}, Point{-6, 30});
    Image image(100, 40);
    TextRenderer a, b;
    a.draw(image, layout, Color::rgb8(0, 0, 0), {}, options);
    AlphaRecorder rec(100, 40);
    b.draw(layout, Affine{}, options, 100, 40, rec);
    EXPECT_FALSE(rec.out_of_bounds);
    int lit = 0;
    for (int y = 0; y < 40; ++y) {
      for (int x = 0; x < 100; ++x) {
        ASSERT_NEAR(image.pixel(x, y)[3] / 255.0, rec.at(x, y), 1.5 / 255) << cache << " " << x << "," << y;
        lit += image.pixel(x, y)[3] > 0;
      }
    }
    EXPECT_GT(lit, 200);
  }
}
