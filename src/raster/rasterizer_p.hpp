// The rasterizer's private state (the Blend2D foo_p.h style): its buffers and the stages that use them.
// include/vraster/raster.hpp shows only the public API; everything that scan conversion keeps between calls lives
// here, allocated once per Rasterizer and reused, so steady-state fills allocate nothing.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "raster/band_pool.hpp"
#include "raster/boundary.hpp"
#include "raster/unit_winding.hpp"
#include "vraster/raster.hpp"

namespace vraster::detail {

class RasterizerImpl {
 public:
  void fill(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink);
  void fill_mask(const Polylines& lines, FillRule rule, int width, int height, std::uint8_t* mask,
                 std::ptrdiff_t stride);

  std::vector<Edge> edges_;
  std::int64_t dense_limit_ = Rasterizer::kDefaultDenseLimit;
  bool exact_shortcut_ = true;
  bool rect_shortcut_ = true;
  std::uint64_t exact_fallbacks_ = 0;  // exact fills over the crossing budget, drawn analytic instead

  /// Up to `threads` threads sweep the bands of one fill (1: no pool).
  void set_threads(int threads);
  int threads() const { return pool_ ? pool_->threads() : 1; }
  int last_fill_bands_ = 1;

 private:
  /// Whether edges_ (clipped) have at most Rasterizer::kMaxExactCrossings crossings inside pixel rows
  /// (exact_budget.cpp).
  bool exact_within_budget(int height);
  /// One axis-aligned rectangle: its coverage without a sweep (rect.cpp). False when `lines` is not one.
  bool fill_rect(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height, CoverageSink& sink);
  void build_edges(const Polylines& lines, int width, int height);
  void build_unclipped_edges(const Polylines& lines);
  void clip_pieces(int width, int height);
  void compute_row_range(int height);
  struct Crossing {
    double x;
    std::uint32_t edge;
  };
  // What one thread needs to sweep a band of rows (one per thread; the caller's is bands_[0]). Each on cache lines
  // of its own: the sweeps write their vectors' sizes every row, and two threads must not share those lines.
  struct alignas(64) BandScratch {
    std::vector<std::uint32_t> active;    // the active edge list (indices into edges_)
    std::vector<Crossing> crossings;      // aliased sweep: active edges with their x at the sample row
    std::vector<double> accumulation;     // analytic sweep: one row of signed area deltas, width + 2 cells
    std::vector<std::uint64_t> touched;   // analytic sweep: one bit per cell written in the current row
    std::vector<float> coverage;          // analytic sweep: coverage handed to the sink
  };
  /// How many bands rows [y_min_, y_max_) of edges_ are cut into: 1 without threads, for a sink that wants its
  /// calls in order, or where the fill is too small for bands to pay (estimated from the edges).
  int band_count(const CoverageSink& sink) const;
  /// Calls sweep(y0, y1, scratch) for every band of rows [y_min_, y_max_), on the pool's threads.
  template <class Sweep>
  void in_bands(int bands, Sweep&& sweep);
  /// The active list at the top of row y_from, as a sweep from y_min_ would have it (same edges, same order):
  /// the edges bucketed in rows before y_from that still reach below `retire_at`.
  void start_active(int y_from, double retire_at, std::vector<std::uint32_t>& active) const;
  void sweep_aliased(FillRule rule, int width, CoverageSink& sink);
  void sweep_aliased_rows(FillRule rule, int width, int y_from, int y_to, BandScratch& s, CoverageSink& sink);
  void sweep_analytic(FillRule rule, int width, CoverageSink& sink);
  void sweep_sampled(FillRule rule, AntiAlias aa, int width, CoverageSink& sink);
  void edge_columns(int& x_base, int& columns) const;
  bool sweep_dense(FillRule rule, int width, int x_base, int columns, CoverageSink& sink);
  void bucket_edges(bool by_sample_row);
  void add_edge(Point top, Point bottom, int winding);
  void add_clipped_segment(Point p, Point q, int width, int height);

  std::vector<std::int64_t> budget_rows_;    // exact budget: active-edge count changes per row
  std::vector<std::uint32_t> budget_order_;  // exact budget: edges by top
  std::vector<Edge> horizontals_;            // NonExterior: horizontal segments (they matter for connectivity)
  std::vector<Edge> pieces_;                 // boundary pieces from the boundary sweep
  int y_min_ = 0, y_max_ = 0;               // rows touched by edges_, [y_min_, y_max_)
  std::vector<std::uint32_t> bucket_start_;  // edge table: edges starting in row r are order_[bucket_start_[r-y_min_] ..]
  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> edge_row_;      // first row of each edge (relative to y_min_)
  std::vector<std::uint32_t> cursor_;        // fill positions while bucketing
  std::vector<BandScratch> bands_{1};       // per thread: the sweeps' row buffers
  std::unique_ptr<BandPool> pool_;           // set_threads(n > 1): the workers that sweep bands
  std::vector<float> row_coverage_;          // dense sweep: coverage handed to the sink
  std::vector<double> dense_block_;          // small paths: rows x columns of cells, zero between fills
  std::vector<float> rect_coverage_;         // fill_rect: the coverage of up to three rows
  std::vector<double> rect_cells_;           // fill_rect: analytic cells of one row, zero between fills
  std::vector<float> mask_cells_;            // fill_mask: rows x stride float cells, zero between fills
  BoundarySweep boundary_;
  UnitWindingTest unit_winding_;             // exact mode: whether analytic is already exact
};

}  // namespace vraster::detail
