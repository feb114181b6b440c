// vraster_text: drawing laid-out text with vraster's rasterizer.
//
//   glyph outline (FreeType, FT_Outline_Decompose) -> vraster::Path -> flatten -> Rasterizer -> CoverageSink
//     a) axis-aligned transforms: coverage mask per (font, glyph, size, subpixel phase, options), cached (LRU,
//        bounded bytes), handed on as coverage rows (Renderer::mask) to the caller's sink;
//     b) any other transform (rotation, skew, mirroring), huge glyphs, or caching off: the outline is filled
//        straight onto the image, never from the cache.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <unordered_map>
#include <vector>

#include "vraster/image.hpp"
#include "vraster/renderer.hpp"
#include "vraster/raster.hpp"
#include "vraster_text/font.hpp"
#include "vraster_text/layout.hpp"

namespace vraster::text {

/// How glyphs are drawn.
struct GlyphRenderOptions {
  AntiAlias aa = AntiAlias::Analytic;
  FillRule rule = FillRule::NonZero;   ///< glyph outlines are designed for non-zero
  Hinting hinting = Hinting::None;
  double tolerance = kDefaultTolerance; ///< flattening tolerance, device pixels
  bool use_cache = true;
  int subpixel_phases = 4;             ///< horizontal pen positions are rounded to 1/phases px (1..16); y to 1 px
};

/// A glyph's coverage in a small bitmap: pixel (i, j) of the mask lies at (left + i, top + j) relative to the
/// integer pen position. Coverage is 8-bit (what the 8-bit compositor uses anyway).
struct GlyphMask {
  int left = 0, top = 0, width = 0, height = 0;
  std::vector<std::uint8_t> coverage;
  std::size_t bytes() const { return coverage.size() + sizeof(GlyphMask); }
};

/// Rasterizes single glyphs into masks through the core rasterizer (flatten -> Rasterizer::fill_mask for analytic
/// coverage, Rasterizer::fill with a mask sink for the other modes).
/// Keeps its buffers between calls; one per thread.
class GlyphRasterizer {
 public:
  /// The glyph at `size_y` px per em (x stretched to `size_x`), its pen at (phase_x, phase_y) within pixel (0, 0).
  /// Hinting::Light loads FreeType's hinted outline at size_y. Throws vraster::Error for a bad size.
  GlyphMask rasterize(const Font& font, std::uint32_t glyph, double size_x, double size_y, double phase_x,
                      double phase_y, const GlyphRenderOptions& options);

 private:
  Polylines lines_;
  Rasterizer rasterizer_;
};

/// Sizes (px per em, after the transform's scale) above which glyphs are drawn from outlines, never cached.
inline constexpr double kMaxCachedGlyphSize = 256.0;
/// Glyphs whose outline box is wider or taller than this many device pixels are drawn from outlines, never cached.
inline constexpr double kMaxCachedGlyphExtent = 1024.0;
/// GlyphRasterizer::rasterize refuses masks with more pixels than this (throws vraster::Error).
inline constexpr double kMaxMaskPixels = 16.0 * 1024 * 1024;

/// Glyph coverage masks keyed by (font, glyph, size, phase, options), at most `max_bytes` in total; the least
/// recently used masks are evicted first.
class GlyphCache {
 public:
  struct Key {
    std::uint64_t font = 0;
    std::uint32_t glyph = 0;
    std::uint32_t phase = 0;
    std::uint64_t size_x_bits = 0, size_y_bits = 0;  ///< the doubles' bit patterns (axis-aligned transform class)
    std::uint32_t options = 0;                      ///< aa, rule, hinting, tolerance class
    friend bool operator==(const Key&, const Key&) = default;
  };
  struct Stats {
    std::uint64_t hits = 0, misses = 0, evictions = 0;
    std::size_t bytes = 0, entries = 0;
  };

  explicit GlyphCache(std::size_t max_bytes = std::size_t{4} << 20) : max_bytes_(max_bytes) {}
  /// The mask for key, or nullptr (counts a hit or a miss; a hit becomes most recently used).
  const GlyphMask* find(const Key& key);
  /// Stores a mask (evicting least recently used ones to stay within the budget); masks bigger than a quarter of
  /// the budget are not stored and nullptr is returned.
  const GlyphMask* insert(const Key& key, GlyphMask mask);
  void clear();
  void set_max_bytes(std::size_t max_bytes);
  std::size_t max_bytes() const { return max_bytes_; }
  const Stats& stats() const { return stats_; }

 private:
  struct KeyHash {
    std::size_t operator()(const Key& k) const;
  };
  struct Entry {
    Key key;
    GlyphMask mask;
  };
  void evict_to(std::size_t budget);

  std::size_t max_bytes_;
  std::list<Entry> lru_;  // front: most recently used
  std::unordered_map<Key, std::list<Entry>::iterator, KeyHash> index_;
  Stats stats_;
};

/// Draws text. Keeps the core Renderer, a rasterizer for masks and the glyph cache; one per thread.
class TextRenderer {
 public:
  explicit TextRenderer(std::size_t cache_bytes = std::size_t{4} << 20) : cache_(cache_bytes) {}

  /// The coverage of every glyph of `layout`, mapped by `transform`, on a width x height device, handed to `sink`
  /// (a compositor: it decides paint, operator and clip). Each glyph's coverage comes as its own sequence of rows
  /// (increasing y within a glyph; glyphs one after another). Throws vraster::Error for a non-finite transform or
  /// a bad size.
  void draw(const TextLayout& layout, const Affine& transform, const GlyphRenderOptions& options, int width,
            int height, CoverageSink& sink);
  /// The coverage of one glyph with its pen at `position` (user space, mapped by `transform`).
  void draw_glyph(const Font& font, std::uint32_t glyph, double size, Point position, const Affine& transform,
                  const GlyphRenderOptions& options, int width, int height, CoverageSink& sink);

  /// Convenience: draws every glyph of `layout`, mapped by `transform`, in one solid `color` (source-over).
  void draw(Image& image, const TextLayout& layout, Color color, const Affine& transform = {},
            const GlyphRenderOptions& options = {});
  /// Convenience: draws one glyph with its pen at `position` (user space, mapped by `transform`) in `color`.
  void draw_glyph(Image& image, const Font& font, std::uint32_t glyph, double size, Point position, Color color,
                  const Affine& transform = {}, const GlyphRenderOptions& options = {});
  /// Appends the outlines of a layout to `out` in user space (for callers that fill or stroke text as a path).
  static void append_outlines(const TextLayout& layout, Path& out, Hinting hinting = Hinting::None);

  GlyphCache& cache() { return cache_; }

 private:
  void draw_one(const Font& font, std::uint32_t glyph, double size, Point position, const Affine& transform,
                const GlyphRenderOptions& options, int width, int height, CoverageSink& sink);

  Renderer renderer_;
  GlyphRasterizer glyph_rasterizer_;
  GlyphCache cache_;
};

}  // namespace vraster::text
