// vraster: the scanline rasterizer (edges -> active edge list -> coverage spans).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "vraster/flatten.hpp"
#include "vraster/geometry.hpp"

namespace vraster {

/// Which points of the plane a path fills. Most are predicates on the winding number w of a point
/// (w counts +1 for every crossing of a downward edge to the left of the point, -1 for upward ones).
enum class FillRule : std::uint8_t {
  EvenOdd,      ///< w is odd
  NonZero,      ///< w != 0
  NonExterior,  ///< the point cannot reach infinity without crossing the path (not a function of w)
  Positive,     ///< w > 0 (GLU's positive winding class)
  Negative,     ///< w < 0
  AbsGeq2,      ///< |w| >= 2
};

/// Whether a point of winding number `w` is filled under a winding rule. NonExterior is not a function of the
/// winding number: the rasterizer first reduces it to boundary pieces filled NonZero, which is what it answers here.
constexpr bool winding_fills(FillRule rule, int w) {
  switch (rule) {
    case FillRule::EvenOdd: return (w & 1) != 0;
    case FillRule::NonZero: return w != 0;
    case FillRule::Positive: return w > 0;
    case FillRule::Negative: return w < 0;
    case FillRule::AbsGeq2: return w >= 2 || w <= -2;
    case FillRule::NonExterior: return w != 0;
  }
  return false;
}

/// How coverage is computed for a pixel.
enum class AntiAlias : std::uint8_t {
  None,      ///< one sample at the pixel centre, top-left rule; coverage is 0 or 1
  Analytic,  ///< area of the pixel under the path by cell cover/area accumulation (exact unless edges cross
             ///< inside a pixel)
  Exact,     ///< true area of (filled region x pixel) for every rule: the boundary of the filled region is
             ///< extracted first (a sweep over the edges' crossings), then accumulated as in Analytic
  // Point-sampled modes (src/raster/supersample.cpp): coverage = share of a pixel's samples whose winding number
  // satisfies the rule; samples on edges follow the aliased mode's half-open rules (edges [y0, y1), spans [x0, x1)).
  Ssaa2,     ///< 2 x 2 regular grid of samples at ((i + 0.5) / 2, (j + 0.5) / 2) in each pixel
  Ssaa4,     ///< 4 x 4 regular grid
  Ssaa8,     ///< 8 x 8 regular grid
  Ssaa16,    ///< 16 x 16 regular grid
  Msaa4,     ///< 4 sparse samples, one per sub-row of a 4 x 4 grid (n-rooks; the Direct3D standard 4x pattern)
  Msaa8,     ///< 8 sparse samples on an 8 x 8 grid (n-rooks; the Direct3D standard 8x pattern)
  Msaa16,    ///< 16 sparse samples on a 16 x 16 grid (n-rooks; the Direct3D standard 16x pattern, cell-centred)
  // FXAA is not a coverage mode: it filters a finished image (vraster/fxaa.hpp: AntiAliasMethod, post_filter).
};

/// Parses "evenodd", "nonzero", ... ; returns false for an unknown name.
bool parse_fill_rule(std::string_view name, FillRule& out);
std::string_view to_string(FillRule rule);
bool parse_anti_alias(std::string_view name, AntiAlias& out);
std::string_view to_string(AntiAlias aa);

/// One row of a batch (CoverageSink::rows): pixels [x0, x1) of row y have coverage coverage[0 .. x1-x0).
struct CoverageRow {
  int y, x0, x1;
  const float* coverage;
};

/// Pixels a sink lets the rasterizer blend into itself (CoverageSink::solid_over8): one colour, source-over, onto 8-bit
/// premultiplied RGBA rows. `pixels` is the pixel (x0, y0) of the sink's coordinates, rows are `stride` bytes apart,
/// and the pixels cover [x0, x0 + width) x [y0, y0 + height); `color` is premultiplied, R in the low byte. The
/// rasterizer blends into them only when they start at (0, 0) and cover the whole fill.
struct SolidOver8 {
  std::uint8_t* pixels = nullptr;
  std::ptrdiff_t stride = 0;
  std::uint32_t color = 0;
  int x0 = 0, y0 = 0, width = 0, height = 0;
};

/// The one interface between the rasterizer and whoever turns coverage into pixels.
/// Calls come in increasing y; within a row in increasing, non-overlapping x. Coverage is in (0, 1].
/// Pixels not mentioned have coverage 0.
class CoverageSink {
 public:
  virtual ~CoverageSink() = default;
  /// Pixels [x0, x1) of row y all have coverage `coverage`.
  virtual void span(int y, int x0, int x1, float coverage) = 0;
  /// Pixels [x0, x1) of row y have coverage coverage[0 .. x1-x0) (entries may be 0).
  virtual void row(int y, int x0, int x1, const float* coverage) = 0;
  /// rows[0 .. count) as row() calls, in that order (increasing y, one call per row). The rasterizer hands over the
  /// short rows of thin shapes and small fills so, several at once: a sink that blends pixels can then do a batch in
  /// one loop, without a virtual call per row (the default makes the row() calls).
  virtual void rows(const CoverageRow* rows, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) row(rows[i].y, rows[i].x0, rows[i].x1, rows[i].coverage);
  }
  /// Whether span() and row() may be called from several threads at once, each thread with rows of its own (a
  /// rasterizer with set_threads(n > 1) sweeps large fills in bands of rows). Calls then come in increasing y within
  /// each band, and no two threads ever get the same row. Sinks that keep state across calls answer false (the
  /// default) and get every call on the caller's thread, in order.
  virtual bool takes_concurrent_rows() const { return false; }
  /// A copy of this sink that can be kept and called later (Rasterizer::fill_queued keeps one for each fill it
  /// queues), or null (the default) for a sink that cannot be copied so: fills into it are drawn at once.
  virtual std::unique_ptr<CoverageSink> clone() const { return nullptr; }
  /// clone() without the heap: a copy constructed in `storage` (`bytes` bytes, aligned for std::max_align_t), which
  /// the caller destroys but never deletes, or null where the sink does not fit or cannot be copied so (the default;
  /// clone() is then asked). The queue keeps small sinks so, in its entries: a frame of small fills allocates nothing.
  virtual CoverageSink* clone_into(void* /*storage*/, std::size_t /*bytes*/) const { return nullptr; }
  /// A hint before the calls of one small fill: they stay in rows [y0, y1) and columns [x0, x1). A sink that writes
  /// pixels may start fetching them into the cache while the rasterizer accumulates the fill (the default ignores
  /// it). Only a hint: it changes no result.
  virtual void expect(int /*y0*/, int /*y1*/, int /*x0*/, int /*x1*/) {}
  /// Whether the sink blends one colour source-over into 8-bit pixels (SolidCompositor, and Compositor with a solid
  /// paint, source-over, global alpha 1 and no clip mask): then it fills `target`, and
  /// the rasterizer may blend some runs itself, in the pass that turns its cells into coverage (no coverage row in
  /// between), with exactly the pixels row() would give them. Other sinks (the default) get every run as row().
  virtual bool solid_over8(SolidOver8& /*target*/) const { return false; }
};

/// A device-space line segment, stored top to bottom (y0 < y1), with the direction of the original segment.
struct Edge {
  double x0, y0, x1, y1;
  double dxdy;  ///< (x1 - x0) / (y1 - y0)
  int winding;  ///< +1 when the original segment ran downward (increasing y), -1 when upward

  /// x where the edge crosses height y (clamped to the edge's x range so round-off never overshoots).
  double x_at(double y) const {
    const double x = x0 + (y - y0) * dxdy;
    const double lo = x1 < x0 ? x1 : x0, hi = x0 < x1 ? x1 : x0;  // (written so that they compile to min and max)
    const double above_lo = lo < x ? x : lo;
    return hi < above_lo ? hi : above_lo;
  }
};

namespace detail {
class RasterizerImpl;  // src/raster/rasterizer_p.hpp: the buffers and stages behind this API
}

/// Scan converts flattened contours. Keeps its buffers between calls, so one Rasterizer per thread,
/// reused across paths and frames, allocates nothing in steady state. (A moved-from Rasterizer may only be
/// assigned to or destroyed.)
class Rasterizer {
 public:
  Rasterizer();
  ~Rasterizer();
  Rasterizer(Rasterizer&&) noexcept;
  Rasterizer& operator=(Rasterizer&&) noexcept;

  /// Rasterizes every contour of `lines` (closed implicitly) into the pixels [0, width) x [0, height),
  /// handing coverage to `sink`. Geometry outside that rectangle costs almost nothing: edges are clipped to it
  /// (parts left of it become vertical edges at x = 0 so they keep their winding). NonExterior is the exception:
  /// whether a region reaches the outside can be decided far from the image, so its boundary is found on the
  /// unclipped edges first (cost grows with all the geometry), then clipped. A contour with a NaN or infinite
  /// point has no shape and is skipped (flatten() never makes one; polylines built by hand may hold them).
  void fill(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink);

  /// Analytic coverage of `lines` under `rule` straight into an 8-bit mask of width x height pixels: every byte
  /// mask[y * stride + x] is written with round(255 * coverage), rounded as the 8-bit compositor rounds. The same
  /// coverage as fill(lines, rule, AntiAlias::Analytic, ...) to within one level (cells are summed in float, not
  /// double). Fast for paths inside the mask (glyphs): every segment walks its rows into a block of float cells,
  /// then one vectorized pass per row sums, converts and stores. Paths reaching outside the mask, NonExterior, and
  /// masks above kMaskBlockLimit cells take the general sweep (same results, its speed).
  /// Throws vraster::Error when `mask` is null or `stride` < `width` (for a non-empty mask).
  void fill_mask(const Polylines& lines, FillRule rule, int width, int height, std::uint8_t* mask,
                 std::ptrdiff_t stride);
  static constexpr std::int64_t kMaskBlockLimit = std::int64_t{1} << 20;

  /// The clipped edges of the last fill() (for tests and tools).
  const std::vector<Edge>& edges() const;

  /// Analytic fills of paths whose box spans at most this many cells may skip the edge table: each edge walks its
  /// own rows into a dense block (cheaper for glyph-sized paths and small shapes; same coverage). Boxes over 8192
  /// cells go dense only where the edges pass through a good share of the box. Thin shapes (slivers, thin strokes'
  /// outlines) go dense whatever their box, in strips of kDefaultDenseLimit cells. 0 turns it off (tests use that
  /// to compare both paths).
  void set_dense_limit(std::int64_t cells);
  static constexpr std::int64_t kDefaultDenseLimit = 32768;

  /// Exact fills of paths whose winding is only ever 0 and one other value take the analytic sweep, which is exact
  /// for them (same coverage up to round-off). false sends every exact fill through the boundary sweep (tests and
  /// the fuzzer use that to compare both paths).
  void set_exact_shortcut(bool on);

  /// A path that is one axis-aligned rectangle after its transform (any fill rule and anti-aliasing mode) skips the
  /// sweep: the rows inside it reach the sink as one full-coverage span each, only its border pixels as rows, with
  /// the coverage the sweep gives (the same arithmetic). false sends rectangles through the sweep (tests compare).
  void set_rect_shortcut(bool on);
  /// The analytic row sweep keeps the rows of at most 31 active edges in fixed-point cells (2^-26 of a pixel, under
  /// 1e-6 from the double cells; docs/design.md). false keeps every row in doubles (tests compare).
  void set_fixed_cells(bool on);

  /// Work budget of AntiAlias::Exact (and of NonExterior, which resolves the same arrangement): a fill whose
  /// edges cross more than this many times inside pixel rows is drawn with AntiAlias::Analytic instead (and
  /// NonExterior as NonZero), and counted in exact_fallbacks() so that callers can warn.
  static constexpr std::uint64_t kMaxExactCrossings = std::uint64_t{1} << 22;
  /// NonExterior resolves its arrangement on all of the geometry, visible or not (clipping would change what
  /// connects to infinity): a path of more flattened points than this takes the NonZero fallback too.
  static constexpr std::size_t kMaxNonExteriorPoints = std::size_t{1} << 18;
  /// How many fills of this rasterizer took that fallback so far.
  std::uint64_t exact_fallbacks() const;

  /// Sweeps large fills on up to `threads` threads (clamped to [1, 64]; 1, the default, starts no thread): the
  /// edges are built once, then bands of rows are swept by a small pool of workers owned by this rasterizer, when
  /// the sink takes concurrent rows (CoverageSink::takes_concurrent_rows) and the fill is large enough to gain.
  /// The coverage is the same, bit for bit, as with one thread. Every mode but Exact's boundary sweep is banded
  /// (exact fills that analytic coverage already resolves exactly take the analytic sweep, which is).
  void set_threads(int threads);
  int threads() const;
  /// How many bands of rows the last fill() was swept in (1: on the caller's thread alone; for tests and tools).
  int last_fill_bands() const;

  /// As fill(), but with threads (set_threads(n > 1)) the fill may wait in a queue until flush(): the edges are
  /// built now, and flush() cuts the rows of every queued fill into bands that the threads take, each band running
  /// the whole queue over its rows in order. One fork and join for the queue instead of one per fill, and small
  /// fills are spread over the threads too. The coverage is the same, bit for bit, as fill() one by one.
  ///
  /// The rasterizer owns `sink` until its fill has run. Queued: fills whose sink takes concurrent rows, in every
  /// mode but Exact, under every rule but NonExterior; the others (and every fill without threads) are drawn at
  /// once, after what is queued, as are small fills with nothing queued before them until the frame shows many of
  /// them (queueing would cost more than it saves; once a large fill waits, small ones join it). Whatever the sinks
  /// write (the image) or read must not be read or written otherwise before flush(); fill(), set_threads() and the
  /// destructor flush first. When the queue holds more than a memory budget (2 MiB) it is drawn by the other
  /// threads in the background while the caller queues the next fills (which are drawn after it).
  void fill_queued(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                   std::unique_ptr<CoverageSink> sink);
  /// As above with a borrowed sink: a fill that waits keeps a copy (sink.clone_into the queue's own storage, else
  /// sink.clone(); a sink that gives none is drawn at once);
  /// one drawn at once uses `sink` itself, so no copy is made for it.
  void fill_queued(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink);
  /// Runs the queued fills (nothing when none is queued).
  void flush();
  /// Fills waiting in the queue (for tests and tools; a queue being drawn in the background no longer counts).
  std::size_t queued_fills() const;
  /// How many bands of rows the last flush ran its queue in (1: on the caller's thread alone; 0: no flush yet).
  int last_flush_bands() const;

 private:
  std::unique_ptr<detail::RasterizerImpl> impl_;  // one allocation per Rasterizer, none per fill
};

}  // namespace vraster
