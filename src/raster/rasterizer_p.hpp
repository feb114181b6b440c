// The rasterizer's private state (the Blend2D foo_p.h style): its buffers and the stages that use them.
// include/vraster/raster.hpp shows only the public API; everything that scan conversion keeps between calls lives
// here, allocated once per Rasterizer and reused, so steady-state fills allocate nothing.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <climits>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "raster/band_pool.hpp"
#include "raster/boundary.hpp"
#include "raster/unit_winding.hpp"
#include "vraster/raster.hpp"

namespace vraster::detail {

/// An edge table as the sweeps read it: edges bucketed by their first row (bucket r of rows [y_min, y_max) is
/// order[bucket_start[r] .. bucket_start[r + 1])). Read-only while swept, so bands on several threads share it.
struct EdgeTableView {
  const std::vector<Edge>& edges;
  const std::vector<std::uint32_t>& order;
  const std::vector<std::uint32_t>& bucket_start;
  int y_min, y_max;
  int x_end = INT_MAX;  // analytic: past the last column the edges reach (edge_columns), where that is known
};

/// The analytic row sweep's active edges as columns, one array per number, in active-list order: every row reads
/// them for every edge, so they lie contiguous and four edges go at once (sweep.cpp). Columns hold kPadding entries
/// past `size` for the last step of four.
struct ActiveEdges {
  static constexpr std::size_t kPadding = 3;
  // The edge: its top, slope, bottom and winding.
  std::vector<double> x0, y0, dxdy, y1, x1, winding;
  std::vector<double> x;   // where the edge enters the current row
  std::vector<double> xb;  // the current row: where it leaves the row
  std::vector<double> h;   // the current row: the piece's height times the winding (0: no piece)
  std::vector<std::uint64_t> ranges;  // a wide row's pieces: first cell << 32 | last cell (not a column: scratch)
  std::size_t size = 0;

  void clear() { size = 0; }
  /// Room for n edges (and the padding) in every column.
  void reserve(std::size_t n) {
    if (x.size() >= n + kPadding) return;
    const std::size_t room = std::max<std::size_t>(2 * x.size(), n + kPadding);
    for (std::vector<double>* c : {&x0, &y0, &dxdy, &y1, &x1, &winding, &x, &xb, &h}) c->resize(room);
    ranges.resize(room);
  }
  /// Appends edge e entering the current row at x_enter (call reserve first).
  void push(const Edge& e, double x_enter) {
    const std::size_t k = size++;
    x0[k] = e.x0;
    y0[k] = e.y0;
    dxdy[k] = e.dxdy;
    y1[k] = e.y1;
    x1[k] = e.x1;
    winding[k] = e.winding;
    x[k] = x_enter;
  }
  /// Edge `from` moves to slot `to` <= from (the list shrinks in place, keeping its order).
  void move(std::size_t from, std::size_t to) {
    x0[to] = x0[from];
    y0[to] = y0[from];
    dxdy[to] = dxdy[from];
    y1[to] = y1[from];
    x1[to] = x1[from];
    winding[to] = winding[from];
  }
};

/// Scratch of bucket_edges (a counting sort), kept between calls so that it allocates nothing in steady state.
struct BucketScratch {
  std::vector<std::uint32_t> edge_row, cursor;
};

// Edge building and the edge table (edges.cpp): free functions, so that the fill queue can build many fills' tables
// on several threads at once, each into its own vectors.

/// Polylines -> edges clipped to [0, width] x [0, height] (top to bottom, with winding), and the rows
/// [y_min, y_max) they touch. With `work`: also band_work's estimate of the fill (sweep.cpp), taken as the
/// segments go by where nothing is clipped (the fill queue's choice between drawing a fill now and queuing it).
void build_edges(const Polylines& lines, int width, int height, std::vector<Edge>& edges, int& y_min, int& y_max,
                 double* work = nullptr);
/// Segment p -> q clipped as build_edges clips it, appended to `edges`.
void add_clipped_segment(std::vector<Edge>& edges, Point p, Point q, int width, int height);
/// The rows [y_min, y_max) that clipped `edges` touch.
void row_range(const std::vector<Edge>& edges, int height, int& y_min, int& y_max);
/// The edge table: edges bucketed by first row (analytic: floor(y0); aliased, by_sample_row: ceil(y0 - 0.5)).
void bucket_edges(const std::vector<Edge>& edges, int y_min, int y_max, bool by_sample_row,
                  std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& bucket_start, BucketScratch& scratch);

// Measures of an edge list (sweep.cpp).

/// The edges' summed height and width: about the number of cells they touch.
double outline_cells(const std::vector<Edge>& edges);
/// The work estimate behind banding (units of about 10 ns): the edges' height and width (the sweep) and the area
/// inside (compositing, kAreaPerUnit pixels a unit).
double band_work(const std::vector<Edge>& edges);
/// band_work from its two sums: outline (summed |dy| + |dx|) and signed area.
double work_of(double outline, double signed_area);
/// band_work's two sums taken over segments as they come (an outline before or while its edges are built).
struct WorkSums {
  double outline = 0, signed_area = 0;
  void add(Point p, Point q) {
    outline += std::abs(q.y - p.y) + std::abs(q.x - p.x);
    signed_area += 0.5 * (p.x + q.x) * (q.y - p.y);
  }
  double work() const { return work_of(outline, signed_area); }
};
/// The cells [x_base, x_base + columns) that (non-empty) `edges` can write.
void edge_columns(const std::vector<Edge>& edges, int& x_base, int& columns);
/// Where a sweep puts its rows for the sink (CoverageSink::rows, cells.hpp's RowBatch): the batch, and a slot of
/// coverage for each row.
struct RowBatchBuffers {
  CoverageRow* batch;
  float* coverage;  // `slot` floats per row
};
/// Sizes `batch` and `coverage` for batches of up to `rows` rows (kBatchRows at most) of `slot` floats each.
RowBatchBuffers row_batch_buffers(std::vector<CoverageRow>& batch, std::vector<float>& coverage, int rows, int slot);
/// Which dense sweep `edges` (rows [y_min, y_max), `columns` columns) take, if any: Dense for small paths, a few
/// thousand cells, and thin shapes of any size; Ranged for fills whose rows hold few pieces (convex shapes), whose
/// rows note each piece so that pieces far apart are swept as clusters with spans between them.
enum class DenseKind : std::uint8_t { None, Dense, Ranged };
DenseKind dense_kind(const std::vector<Edge>& edges, int y_min, int y_max, int columns, std::int64_t dense_limit);
/// The buffers of a dense sweep (kept from fill to fill; the block stays zero between fills).
struct DenseScratch {
  std::vector<double>& block;       // rows x columns of cells
  std::vector<std::int32_t>& fixed_block;  // the same in fixed point (fixed_cells.hpp), for fills of few edges
  std::vector<std::int64_t>& wide_block;   // the same in wide cells (fixed_cells.hpp), for fills of more
  std::vector<int>& notes;          // per row: first and last cell written (and pieces' ranges: DenseRows)
  std::vector<CoverageRow>& batch;  // rows handed to the sink together
  std::vector<float>& coverage;     // their coverage, a slot per row
};
/// The dense sweep of rows [y_from, y_to) of `edges` (cells [x_base, x_base + columns)).
/// The cells a dense fill's rows take (fixed_cells.hpp), as the row sweep's rows do: where `fixed_cells` allows
/// integer cells, its wide blocks (Trimmed, Ranged) with at most kFixedRowEdges pieces in every row take fixed-point
/// cells, those of fills of up to kWideRowEdges edges wide cells; narrow blocks and the rest double cells. Once per
/// fill (`scratch`: any vector), so that its bands and strips all decide alike.
enum class DenseCells : std::uint8_t { Double, Fixed, Wide };
DenseCells dense_cell_type(bool fixed_cells, DenseKind kind, int columns, const std::vector<Edge>& edges,
                           std::vector<int>& scratch);
/// cell_type: dense_cell_type's answer for the fill.
void sweep_dense_range(FillRule rule, DenseKind kind, const std::vector<Edge>& edges, int y_from, int y_to,
                       int x_base, int columns, int width, DenseCells cell_type, DenseScratch s, CoverageSink& sink);

/// Crossings of `edges` (clipped to rows [0, height)) inside pixel rows: per row, the pairs of edges whose x order
/// at the row's top (ties by x at the bottom) differs from their order at its bottom. Counting stops once it
/// passes `limit` (the result is then some number above it). exact_budget.cpp.
std::uint64_t row_crossings(const std::vector<Edge>& edges, int height, std::uint64_t limit);

/// Coverage calls kept for later (a queued rectangle: cheaper computed at once than kept as edges), replayed row
/// range by row range. Calls are kept in the order they came, which is increasing y.
class CoverageRecording final : public CoverageSink {
 public:
  void span(int y, int x0, int x1, float coverage) override;
  void row(int y, int x0, int x1, const float* coverage) override;
  bool takes_concurrent_rows() const override { return false; }  // recorded from one thread, in order
  /// The calls recorded for row y (the last row so far) stand for rows [y, y_end) alike: a rectangle's inside rows
  /// are recorded once. Nothing happens when the last calls are not row y's (row y had none).
  void repeat_row(int y, int y_end);
  /// Hands the calls of rows [y_from, y_to) to `sink`, in the order they came (a repeated row's calls once for each
  /// of its rows).
  void replay(int y_from, int y_to, CoverageSink& sink) const;
  void clear();
  bool empty() const { return calls_.empty(); }
  std::size_t calls() const { return replayed_calls_; }  // calls a replay of every row makes
  std::size_t pixels() const { return pixels_; }  // pixels the calls cover
  std::size_t bytes() const;
  int y_min() const { return calls_.empty() ? 0 : calls_.front().y; }
  int y_max() const { return calls_.empty() ? 0 : calls_.back().y_end; }

 private:
  struct Call {
    int y, y_end;         // for rows [y, y_end): y + 1 unless repeat_row made it more
    int x0, x1;
    float coverage;       // a span's coverage
    std::uint32_t first;  // a row's coverage: values_[first .. first + x1 - x0); kSpan for a span
  };
  static constexpr std::uint32_t kSpan = 0xFFFFFFFF;
  std::vector<Call> calls_;
  std::vector<float> values_;
  std::size_t pixels_ = 0;
  std::size_t replayed_calls_ = 0;
};

/// One fill of a rasterizer's queue (Rasterizer::fill_queued): everything its rows need, owned, so that the
/// rasterizer's own buffers are free for the next fill. Entries are reused from flush to flush (their vectors keep
/// their capacity).
struct QueuedFill {
  // Unbuilt: only `lines` so far (or, with `prebuilt`, the edges already); flush() builds the edges (on the pool's
  // threads) and picks one of the kinds after it (Empty: no edge inside the image).
  enum class Kind : std::uint8_t { Unbuilt, Empty, Analytic, Aliased, Sampled, Dense, Ranged, Recorded };
  Kind kind = Kind::Analytic;
  Polylines lines;  // Unbuilt: the fill's outline, as fill_queued got it
  bool prebuilt = false;  // Unbuilt: edges, y_min and y_max are built already (the fill that started the queue)
  int x_base = 0, columns = 0;  // Dense, Ranged: the cells the edges reach (edge_columns)
  bool fixed_cells = false;     // Analytic: rows of few (and of many) edges in integer cells (the rasterizer's
                                // setting when it was built)
  DenseCells dense_cells = DenseCells::Double;  // Dense, Ranged: the cells of its rows (dense_cell_type)
  FillRule rule = FillRule::NonZero;
  AntiAlias aa = AntiAlias::Analytic;
  int width = 0, height = 0;
  int y_min = 0, y_max = 0;  // rows the fill touches (once built)
  double work = 0;           // band_work's estimate (of the outline while unbuilt)
  std::vector<Edge> edges;   // Analytic / Aliased / Sampled / Dense / Ranged
  std::vector<std::uint32_t> order, bucket_start;  // Analytic / Aliased: the edge table
  CoverageRecording recording;                      // Recorded
  CoverageSink* sink = nullptr;  // the fill's sink while it waits: in sink_storage_, or owned_sink_

  QueuedFill() = default;
  QueuedFill(const QueuedFill&) = delete;  // (a sink in sink_storage_ stays where it was made: entries never move)
  QueuedFill& operator=(const QueuedFill&) = delete;
  ~QueuedFill() { drop_sink(); }
  EdgeTableView table() const { return {edges, order, bucket_start, y_min, y_max, x_base + columns}; }
  std::size_t bytes() const;
  /// Keeps `owned` if given, else a copy of `s` (in the entry's own storage where it fits: no allocation); false for
  /// a sink that cannot be copied.
  bool keep_sink(const CoverageSink& s, std::unique_ptr<CoverageSink> owned);
  void drop_sink();

 private:
  static constexpr std::size_t kSinkStorageBytes = 128;  // SolidCompositor's size and then some
  alignas(std::max_align_t) std::byte sink_storage_[kSinkStorageBytes];
  bool sink_in_storage_ = false;
  std::unique_ptr<CoverageSink> owned_sink_;
};

class RasterizerImpl {
 public:
  RasterizerImpl() = default;
  ~RasterizerImpl() { flush(); }  // queued fills are drawn, not dropped
  RasterizerImpl(const RasterizerImpl&) = delete;
  RasterizerImpl& operator=(const RasterizerImpl&) = delete;

  void fill(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink);
  void fill_mask(const Polylines& lines, FillRule rule, int width, int height, std::uint8_t* mask,
                 std::ptrdiff_t stride);

  std::vector<Edge> edges_;
  std::int64_t dense_limit_ = Rasterizer::kDefaultDenseLimit;
  bool exact_shortcut_ = true;
  bool rect_shortcut_ = true;
  bool fixed_cells_ = true;
  std::uint64_t exact_fallbacks_ = 0;  // exact fills over the crossing budget, drawn analytic instead

  /// Up to `threads` threads sweep the bands of one fill (1: no pool).
  void set_threads(int threads);
  int threads() const { return pool_ ? pool_->threads() : 1; }
  int last_fill_bands_ = 1;

  /// Rasterizer::fill_queued / flush (fill_queue.cpp): `sink` draws what is drawn at once; a queued fill keeps
  /// `owned` (when given) or sink.clone() (none: drawn at once).
  void fill_queued(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink,
                   std::unique_ptr<CoverageSink> owned);
  void flush();
  std::size_t queued_fills() const { return queued_; }
  int last_flush_bands_ = 0;

 private:
  /// Draws the queue (flush() without ending the frame: the count of small fills drawn at once goes on). In the
  /// background (`in_background`): the bands are handed to the workers and the call returns; the caller goes on
  /// queueing into the other queue while they draw, and whatever draws next waits for them (finish_running).
  void run_queue(bool in_background = false);
  /// Waits for the queue drawn in the background, if any, taking its bands that are left on this thread.
  void finish_running();
  /// Whether edges_ (clipped) have at most Rasterizer::kMaxExactCrossings crossings inside pixel rows
  /// (exact_budget.cpp).
  bool exact_within_budget(int height);
  /// One axis-aligned rectangle: its coverage without a sweep (rect.cpp). False when `lines` is not one. When
  /// `recording` is given it is `sink` itself, and takes the inside rows once (CoverageRecording::repeat_row).
  bool fill_rect(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink,
                 CoverageRecording* recording = nullptr);
  void build_edges(const Polylines& lines, int width, int height) {
    detail::build_edges(lines, width, height, edges_, y_min_, y_max_);
  }
  /// The sweep of the mode over edges_ (built; not Exact's boundary sweep), in bands where they pay.
  void sweep_edges(FillRule rule, AntiAlias aa, int width, CoverageSink& sink);
  void build_unclipped_edges(const Polylines& lines);
  void clip_pieces(int width, int height);
  struct Crossing {
    double x;
    std::uint32_t edge;
  };
  // What one thread needs to sweep a band of rows (one per thread; the caller's is bands_[0]). Each on cache lines
  // of its own: the sweeps write their vectors' sizes every row, and two threads must not share those lines.
  struct alignas(64) BandScratch {
    std::vector<std::uint32_t> active;    // the active edge list (indices into edges_)
    ActiveEdges columns;                  // analytic sweep: the active edges as columns
    std::vector<Crossing> crossings;      // aliased sweep: active edges with their x at the sample row
    std::vector<double> accumulation;     // analytic sweep: one row of signed area deltas, width + 2 cells
    std::vector<std::int32_t> fixed_cells;  // analytic sweep: the same in fixed point, for rows of few edges
    std::vector<std::int64_t> wide_cells;   // analytic sweep: the same in 64-bit integers, for rows of many edges
    std::vector<float> coverage;          // analytic sweep: coverage handed to the sink
    std::vector<CoverageRow> batch;       // analytic and queued dense sweeps: rows handed to the sink together
    std::vector<float> batch_coverage;    // analytic sweep: the narrow rows' coverage (queued dense: `coverage`)
    std::vector<double> dense_block;      // queued dense fills: rows x columns of cells, zero between fills
    std::vector<std::int32_t> dense_fixed_block;  // the same in fixed point, for fills of few edges
    std::vector<std::int64_t> dense_wide_block;   // the same in wide cells, for fills of more
    std::vector<int> dense_notes;         // queued dense fills: what each row's pieces wrote (DenseRows)
    BucketScratch bucket;                 // building queued fills
  };
  /// How many bands rows [y_min_, y_max_) of edges_ are cut into: 1 without threads, for a sink that wants its
  /// calls in order, or where the fill is too small for bands to pay (estimated from the edges).
  int band_count(const CoverageSink& sink) const;
  /// Calls sweep(y0, y1, scratch) for every band of rows [y_min_, y_max_), on the pool's threads.
  template <class Sweep>
  void in_bands(int bands, Sweep&& sweep);
  /// The active list at the top of row y_from, as a sweep from y_min_ would have it (same edges, same order):
  /// the edges bucketed in rows before y_from that still reach below `retire_at`.
  static void start_active(const EdgeTableView& table, int y_from, double retire_at,
                           std::vector<std::uint32_t>& active);
  EdgeTableView table() const { return {edges_, order_, bucket_start_, y_min_, y_max_}; }
  void sweep_aliased(FillRule rule, int width, CoverageSink& sink);
  /// Rows [y_from, y_to) of an aliased (bucketed by sample row) / analytic (bucketed by row) table, on one thread.
  static void sweep_aliased_rows(const EdgeTableView& table, FillRule rule, int width, int y_from, int y_to,
                                 BandScratch& s, CoverageSink& sink);
  /// fixed_cells: rows of few edges in fixed point (fixed_cells_, passed on to the queue's bands too).
  static void sweep_analytic_band(const EdgeTableView& table, FillRule rule, int width, int y_from, int y_to,
                                  bool fixed_cells, BandScratch& s, CoverageSink& sink);
  /// fixed_cells: the row sweep's rows of few edges in fixed point (analytic mode, unless turned off).
  void sweep_analytic(FillRule rule, int width, bool fixed_cells, CoverageSink& sink);
  void sweep_sampled(FillRule rule, AntiAlias aa, int width, CoverageSink& sink);
  /// fixed_cells: whether integer cells are allowed (dense_cell_type decides for the fill).
  bool sweep_dense(FillRule rule, int width, int x_base, int columns, bool fixed_cells, CoverageSink& sink);
  [[gnu::noinline]] void sweep_ranged(FillRule rule, int width, int x_base, int columns, DenseCells cell_type,
                                      CoverageSink& sink);
  /// The dense sweep of rows [y_from, y_to) of a queued fill, on one thread.
  static void sweep_dense_band(const QueuedFill& fill, int y_from, int y_to, BandScratch& s);
  void bucket_edges(bool by_sample_row) {
    detail::bucket_edges(edges_, y_min_, y_max_, by_sample_row, order_, bucket_start_, bands_[0].bucket);
  }
  /// Builds an Unbuilt entry of the queue (its edges, its kind, its table) with one thread's scratch.
  void build_queued(QueuedFill& q, BandScratch& s) const;

  std::vector<std::int64_t> budget_rows_;    // exact budget: active-edge count changes per row
  std::vector<Edge> horizontals_;            // NonExterior: horizontal segments (they matter for connectivity)
  std::vector<Edge> pieces_;                 // boundary pieces from the boundary sweep
  int y_min_ = 0, y_max_ = 0;               // rows touched by edges_, [y_min_, y_max_)
  std::vector<std::uint32_t> bucket_start_;  // edge table: edges starting in row r are order_[bucket_start_[r-y_min_] ..]
  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> cursor_;        // flush: fill positions in band_entries_
  std::vector<BandScratch> bands_{1};       // per thread: the sweeps' row buffers
  std::unique_ptr<BandPool> pool_;           // set_threads(n > 1): the workers that sweep bands
  std::vector<float> row_coverage_;          // dense sweep: coverage handed to the sink, a slot per batched row
  std::vector<CoverageRow> dense_batch_;     // dense sweep: the rows of a batch
  std::vector<double> dense_block_;          // small paths: rows x columns of cells, zero between fills
  std::vector<std::int32_t> dense_fixed_block_;  // the same in fixed point, for fills of few edges
  std::vector<std::int64_t> dense_wide_block_;   // the same in wide cells, for fills of more
  std::vector<int> dense_notes_;             // dense fills: what each row's pieces wrote (DenseRows)
  std::vector<float> rect_coverage_;         // fill_rect: the coverage of up to three rows
  std::vector<double> rect_cells_;           // fill_rect: analytic cells of one row, zero between fills
  std::vector<float> mask_cells_;            // fill_mask: rows x stride float cells, zero between fills
  BoundarySweep boundary_;
  UnitWindingTest unit_winding_;             // exact mode: whether analytic is already exact
  // fill_queued: entries [0, queued_) of queues_[filling_] wait for flush() (they never move); the other queue may
  // be drawing in the background (running_: queues_[filling_ ^ 1], its first running_count_ entries).
  std::deque<QueuedFill> queues_[2];
  int filling_ = 0;
  bool running_ = false;
  std::size_t running_count_ = 0;
  int running_bands_ = 0;
  bool workers_starved_ = false;  // a queue in the background was drawn by the caller alone (finish_running)
  std::size_t queued_ = 0;
  std::size_t queued_bytes_ = 0;
  double queued_work_ = 0;
  double drawn_at_once_ = 0;  // work of the small fills fill_queued drew at once since the last flush
  std::vector<int> band_top_;                // flush: the first row of every band, and the end of the last
  std::vector<double> row_work_;             // flush: the queue's work summed row by row
  std::vector<double> band_cuts_;            // flush: the work above each band's bottom
  std::vector<std::uint32_t> band_first_;    // flush: band b runs entries band_entries_[band_first_[b] .. [b + 1])
  std::vector<std::uint32_t> band_entries_;
  struct FillRows {  // flush: a visible entry's rows, work and bands [first_band, last_band)
    std::uint32_t entry;
    int y_min, y_max;
    double work;
    int first_band = 0, last_band = 0;
  };
  std::vector<FillRows> fill_rows_;
  std::vector<std::uint16_t> row_band_;      // flush: the band of every row from the queue's top
  void run_queued_band(const std::deque<QueuedFill>& queue, int band, BandScratch& s);
  struct BandJob {  // the bands of a queue drawn in the background (it outlives run_queue)
    RasterizerImpl* self = nullptr;
    const std::deque<QueuedFill>* queue = nullptr;
    void operator()(int band, int worker) const {
      self->run_queued_band(*queue, band, self->bands_[static_cast<std::size_t>(worker)]);
    }
  };
  BandJob band_job_;
  /// After a flush: the entries' sinks released (their buffers kept for the next fills), the counts at zero.
  void empty_queue();
  /// The first `count` entries' sinks released.
  static void drop_sinks(std::deque<QueuedFill>& queue, std::size_t count);
};

}  // namespace vraster::detail
