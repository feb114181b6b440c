// Scanline sweeps over the edge table with an active edge list.
//
//   1. build_edges:   polylines -> clipped edges (top to bottom, with winding)
//   2. bucket_edges:  edge table, edges bucketed by their first row
//   3. per row:       add the row's bucket to the active list, let every active edge contribute, retire edges
//                     that end in the row
//   4. per row:       turn the contributions into coverage under the fill rule -> CoverageSink spans
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

#include "raster/blend_cells.hpp"
#include "raster/boundary.hpp"
#include "raster/cells.hpp"
#include "raster/fixed_cells.hpp"
#include "raster/supersample.hpp"
#include "raster/unit_winding.hpp"
#include "raster/rasterizer_p.hpp"
#include "vraster/raster.hpp"

namespace vraster {
namespace {

using detail::accumulate_piece;
using detail::coverage_of;
using detail::with_rule;

// The row loop (instantiated for AVX2 and for any x86-64 below, picked per fill; no FMA, so both give the same
// bits). Sweeps rows [y_from, y_to) starting from `active` (start_active); every row's arithmetic is a function of
// the edges and the row alone (x_at from each edge's own start, pieces added in active-list order), so a band gives
// the bits a sweep of the whole range gives. Per row: where every active edge leaves the row, four edges at once
// from the active edges kept as columns (leave_row; a branch per edge on whether it ends in the row was
// mispredicted often enough to cost stars a quarter of their time), then the pieces one by one, then the edges that
// end are dropped.
// Short rows go to the sink in batches of this many (CoverageSink::rows): a thin shape's rows are a few pixels each,
// and a call for each row cost about as much as the row's sweep (docs/performance.md).
constexpr int kBatchRows = 32;

// Rows for CoverageSink::rows, each with a slot of `slot` floats of its own for its coverage (kBatchRows slots).
// Anything else the sweep hands to the sink goes after hand_over(), so that the calls stay in increasing y.
class RowBatch {
 public:
  RowBatch(CoverageSink& sink, const detail::RowBatchBuffers& buffers, std::size_t slot)
      : sink_(sink), rows_(buffers.batch), coverage_(buffers.coverage), slot_(slot) {}
  /// Where the next row's coverage goes.
  float* slot() const { return coverage_ + static_cast<std::size_t>(count_) * slot_; }
  /// Pixels [x0, x1) of row y, coverage from c (in the current slot).
  void add(int y, int x0, int x1, const float* c) {
    rows_[count_++] = {y, x0, x1, c};
    if (count_ == kBatchRows) hand_over();
  }
  /// The rows added so far, to the sink.
  void hand_over() {
    if (count_ > 0) sink_.rows(rows_, static_cast<std::size_t>(count_));
    count_ = 0;
  }

 private:
  CoverageSink& sink_;
  CoverageRow* rows_;
  float* coverage_;
  std::size_t slot_;
  int count_ = 0;
};

// A row whose pieces lie within this many cells per active edge is swept whole, as one cluster from its first written
// cell to its last (below), the untouched stretches between pieces included: one sweep and one compositor call
// instead of a sweep, a span and a call per piece. So are crowded rows (a star with hundreds of crossings per
// row) and the rows of self-intersecting polygons and curves (poly10_256 21 %, cubic_256 7 % faster; see
// docs/performance.md); rows whose pieces lie farther apart (the two sides of a circle, the walls of a ring) are
// swept as clusters of nearby pieces (resolve_clusters), their long untouched stretches constant spans. (32 before
// the clusters; 24 since: rings 12 % faster, the shared scenes unchanged.)
constexpr std::size_t kWholeRunCellsPerEdge = 24;

// A band's row buffers (BandScratch's, sized for the row with kRowPadding).
struct RowBuffers {
  const std::vector<std::uint32_t>& active;  // the active list at the band's top (start_active)
  detail::ActiveEdges& columns;
  double* acc;
  std::int32_t* fixed;  // the fixed-point cells of rows of few edges (fixed_cells.hpp); null: doubles for every row
  std::int64_t* wide;   // the wide cells of rows of more edges (fixed_cells.hpp); null where fixed is
  float* cov;
  detail::RowBatchBuffers batch;  // the narrow rows waiting for the sink, kNarrowRowCoverage floats a row
};

// The first and the last cell a piece from x = xa to x = xb adds to (accumulate_piece: the cell of its left end, and
// the one after the cell of its right end).
inline int piece_first_cell(double xa, double xb) { return static_cast<int>(std::min(xa, xb)); }
inline int piece_last_cell(double xa, double xb) { return static_cast<int>(std::max(xa, xb)) + 1; }

// Where active edges [k, size) leave the row [top, bottom), and the signed height of their pieces there (0: none),
// into columns xb and h: Edge::x_at(bottom) for an edge that goes on below the row (its end x1 otherwise), and
// (min(y1, bottom) - max(y0, top)) * winding. Returns whether every one of them goes on below the row.
[[gnu::always_inline]] inline bool leave_row(detail::ActiveEdges& a, std::size_t k, double top, double bottom) {
  bool all_go_on = true;
  for (; k < a.size; ++k) {
    const double ya = std::max(a.y0[k], top);
    double yb, xb;
    if (a.y1[k] > bottom) {
      yb = bottom;
      // Edge::x_at(bottom), step by step.
      const double x0 = a.x0[k], x1 = a.x1[k];
      const double x = x0 + (bottom - a.y0[k]) * a.dxdy[k];
      const double lo = x1 < x0 ? x1 : x0, hi = x0 < x1 ? x1 : x0;
      const double above_lo = lo < x ? x : lo;
      xb = hi < above_lo ? hi : above_lo;
    } else {
      yb = a.y1[k];
      xb = a.x1[k];
      all_go_on = false;
    }
    a.xb[k] = xb;
    a.h[k] = yb > ya ? (yb - ya) * a.winding[k] : 0.0;
  }
  return all_go_on;
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
// leave_row four edges a step, with the same operations (maxpd / minpd give the ternaries' values on these
// non-NaN numbers, and there is no FMA): the same bits. The last step may take up to three lanes past the list (the
// columns' padding, left over from earlier edges): what they compute is stored in the padding and never read, and
// they count as going on.
[[gnu::target("avx2")]] inline bool leave_row_avx2(detail::ActiveEdges& a, double top, double bottom) {
  static_assert(detail::ActiveEdges::kPadding >= 3);
  const __m256d t = _mm256_set1_pd(top), b = _mm256_set1_pd(bottom);
  const __m256i lanes = _mm256_setr_epi64x(0, 1, 2, 3);
  int ends = 0;  // lanes of edges that end in the row
  for (std::size_t k = 0; k < a.size; k += 4) {
    const __m256d y0 = _mm256_loadu_pd(&a.y0[k]), y1 = _mm256_loadu_pd(&a.y1[k]);
    const __m256d x0 = _mm256_loadu_pd(&a.x0[k]), x1 = _mm256_loadu_pd(&a.x1[k]);
    const __m256d on = _mm256_cmp_pd(y1, b, _CMP_GT_OQ);  // goes on below the row
    __m256d x = _mm256_add_pd(x0, _mm256_mul_pd(_mm256_sub_pd(b, y0), _mm256_loadu_pd(&a.dxdy[k])));
    const __m256d lo = _mm256_min_pd(x1, x0), hi = _mm256_max_pd(x1, x0);  // (x1 < x0 ? x1 : x0), (x0 < x1 ? x1 : x0)
    x = _mm256_min_pd(hi, _mm256_max_pd(x, lo));
    _mm256_storeu_pd(&a.xb[k], _mm256_blendv_pd(x1, x, on));
    const __m256d ya = _mm256_max_pd(y0, t);
    const __m256d yb = _mm256_blendv_pd(y1, b, on);
    const __m256d h = _mm256_mul_pd(_mm256_sub_pd(yb, ya), _mm256_loadu_pd(&a.winding[k]));
    _mm256_storeu_pd(&a.h[k], _mm256_and_pd(h, _mm256_cmp_pd(yb, ya, _CMP_GT_OQ)));
    const __m256i in_list = _mm256_cmpgt_epi64(_mm256_set1_epi64x(static_cast<long long>(a.size - k)), lanes);
    ends |= _mm256_movemask_pd(_mm256_andnot_pd(on, _mm256_castsi256_pd(in_list)));
  }
  return ends == 0;
}

// The four doubles at p with the lanes `pack` names first (retire_ended_avx2's kPack).
[[gnu::target("avx2"), gnu::always_inline]] inline __m256d packed_lanes(const double* p, __m256i pack) {
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(_mm256_loadu_pd(p)), pack));
}

// The edges that end in the row [., bottom) dropped from the columns, four edges a step: the kept lanes of each
// step packed to the front by one permutation per column (no branch per edge, which was mispredicted about as
// often as edges end), the others' slots overwritten. The kept edges keep their order and enter the next row
// where they leave this one (x = xb), as in the scalar loop. A step's stores reach at most its own last slot, so
// they never overwrite an edge not yet read.
[[gnu::target("avx2")]] inline void retire_ended_avx2(detail::ActiveEdges& a, double bottom) {
  // For each mask of kept lanes, the 32-bit halves of the kept doubles, in order, first.
  static constexpr auto kPack = [] {
    std::array<std::array<std::int32_t, 8>, 16> table{};
    for (int mask = 0; mask < 16; ++mask) {
      int out = 0;
      for (int lane = 0; lane < 4; ++lane) {
        if (mask >> lane & 1) {
          table[mask][2 * out] = 2 * lane;
          table[mask][2 * out + 1] = 2 * lane + 1;
          ++out;
        }
      }
      for (; out < 4; ++out) table[mask][2 * out] = 0, table[mask][2 * out + 1] = 1;
    }
    return table;
  }();
  const __m256d b = _mm256_set1_pd(bottom);
  const __m256i lanes = _mm256_setr_epi64x(0, 1, 2, 3);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < a.size; k += 4) {
    const __m256i in_list = _mm256_cmpgt_epi64(_mm256_set1_epi64x(static_cast<long long>(a.size - k)), lanes);
    const __m256d on = _mm256_and_pd(_mm256_cmp_pd(_mm256_loadu_pd(&a.y1[k]), b, _CMP_GT_OQ),
                                     _mm256_castsi256_pd(in_list));  // the scalar loop's a.y1[k] > bottom
    const int mask = _mm256_movemask_pd(on);
    const __m256i pack = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kPack[mask].data()));
    for (std::vector<double>* column : {&a.x0, &a.y0, &a.dxdy, &a.y1, &a.x1, &a.winding}) {
      double* c = column->data();
      _mm256_storeu_pd(c + kept, packed_lanes(c + k, pack));
    }
    _mm256_storeu_pd(a.x.data() + kept, packed_lanes(a.xb.data() + k, pack));
    kept += static_cast<std::size_t>(std::popcount(static_cast<unsigned>(mask)));
  }
  a.size = kept;
}

// The row's pieces, four active edges a step: split without branches (detail::SplitLanes), then added in the list's
// order, so each cell gets accumulate_piece's numbers in the scalar loop's order (into fixed-point cells, Cell
// std::int32_t: accumulate_piece_fixed's integers, the shares rounded four pieces at a time). Also the row's first
// and last touched cells (piece_first_cell, piece_last_cell); pieces of height 0 are left out, as there. kRanges:
// also each piece's range of cells for resolve_clusters (first << 32 | last, from the split's numbers:
// piece_first_cell's and piece_last_cell's), a store a piece instead of a second pass over the pieces if the row
// turns out sparse; for rows of few edges, which are the sparse ones (crowded rows are swept whole and would only pay
// the stores). Returns the number of ranges.
template <bool kRanges, class Cell>
[[gnu::target("avx2")]] inline std::size_t add_pieces_avx2(const detail::ActiveEdges& a, Cell* acc, int& x_lo,
                                                          int& x_hi, std::uint64_t* ranges) {
  constexpr bool kFixed = !std::is_same_v<Cell, double>;
  std::size_t count = 0;
  for (std::size_t k = 0; k < a.size; k += 4) {
    const detail::SplitLanes<Cell> split(_mm256_loadu_pd(&a.x[k]), _mm256_loadu_pd(&a.xb[k]),
                                           _mm256_loadu_pd(&a.h[k]));
    const int lanes = static_cast<int>(std::min<std::size_t>(4, a.size - k));  // the last step may pass the list
    for (int i = 0; i < lanes; ++i) {
      if (split.h[i] == 0) continue;
      const int first = split.first[i], last = split.first[i] + split.past[i] + 1;
      if constexpr (kFixed) {
        detail::add_split_lane(split, i, acc);
      } else {
        split.add(i, acc);
      }
      x_lo = std::min(x_lo, first);
      x_hi = std::max(x_hi, last);
      if constexpr (kRanges) {
        ranges[count++] = static_cast<std::uint64_t>(first) << 32 | static_cast<std::uint32_t>(last);
      }
    }
  }
  return count;
}
#endif

// The sink's pixels for resolve_cluster, where it offers them (CoverageSink::solid_over8) and they hold every pixel
// of the fill: columns [0, width) and rows [0, y_end).
inline const SolidOver8* solid_target(const CoverageSink& sink, SolidOver8& pixels, int width, int y_end) {
  if (!sink.solid_over8(pixels)) return nullptr;
  return pixels.x0 == 0 && pixels.y0 == 0 && pixels.width >= width && pixels.height >= y_end ? &pixels : nullptr;
}

// The pixels of the target's row from column x on that a run's partial blend step may read and write back unchanged
// (blend_whole_step8): for an opaque colour those up to the target's width, which the sweeps narrow to the fill's
// columns (so a fill never touches a pixel past the cells its edges write), none for a translucent one. The row is
// this thread's: bands and queued fills own whole rows.
inline int whole_step_room(const SolidOver8& target, int x) {
  return target.color >> 24 == 255 ? target.width - x : 0;
}

// One cluster of a row (a sparse row's, or a narrow, crowded or dense block's row whole): cells lo .. hi (relative to
// x_base; acc is cell x_base) swept from `sum` (carried from the cluster before), one compositor call for its nonzero
// pixels, then the stretch up to gap_end (the next cluster, or the row's end) as one span of the sum left past the
// cluster (none in a hole). With a `target` (the sink's SolidOver8; AVX2 only), the cluster is swept straight into
// its pixels instead (blend_cells_avx2), the cells up to three past hi being untouched as for the narrow sweep.
template <FillRule R, bool kAvx2>
[[gnu::always_inline]] inline void resolve_cluster(int y, int width, int x_base, int lo, int hi, int gap_end,
                                                   double* acc, float* cov, double& sum, const SolidOver8* target,
                                                   CoverageSink& sink) {
  int a = 0, b = 0;  // the cluster's nonzero pixels inside the image, from lo
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if constexpr (kAvx2) {
    if (target) {
      auto* const px = reinterpret_cast<std::uint32_t*>(target->pixels + y * target->stride) + x_base + lo;
      const int visible = std::max(std::min(hi + 1, width - x_base) - lo, 0);
      detail::blend_cells_avx2<R>(acc + lo, hi - lo + 1, visible, sum, px, target->color,
                                  whole_step_room(*target, x_base + lo));
      if (gap_end > hi + 1) {
        const float c = coverage_of<R>(sum);
        if (c > 0) sink.span(y, x_base + hi + 1, x_base + gap_end, c);
      }
      return;
    }
  }
#endif
  if (hi - lo < detail::kNarrowRowCells) {
    // (the cells up to three past hi, which the last block reads, are untouched: zero)
    const std::uint32_t nonzero = detail::sweep_narrow_cells<R, kAvx2>(lo, hi, acc, cov, sum);
    if (!detail::nonzero_bounds(nonzero, width - x_base - lo, a, b)) b = a;
  } else {
    detail::sweep_cells_for<R, kAvx2>(acc + lo, cov, hi - lo + 1, sum);
    b = std::max(std::min(hi + 1, width - x_base) - lo, 0);
    detail::trim_zeros(cov, a, b);
  }
  if (b - a == 1) {
    sink.span(y, x_base + lo + a, x_base + lo + b, cov[a]);
  } else if (b > a) {
    sink.row(y, x_base + lo + a, x_base + lo + b, cov + a);
  }
  if (gap_end > hi + 1) {
    const float c = coverage_of<R>(sum);
    if (c > 0) sink.span(y, x_base + hi + 1, x_base + gap_end, c);
  }
}

// A wide row whose pieces lie far apart (the two sides of a circle, the walls of a ring), as clusters: the pieces'
// cell ranges (first cell << 32 | last cell) sorted, and merged where at most detail::kMergeGap cells lie between
// them; cluster(lo, hi, gap_end) for each, gap_end being where the next one starts (or the row's end). No touched
// bits and no search for runs: about a third of the row's time for discs and rings (docs/performance.md).
template <class Cluster>
[[gnu::always_inline]] inline void for_each_cluster(int width, std::uint64_t* ranges, std::size_t count,
                                                    Cluster&& cluster) {
  for (std::size_t i = 1; i < count; ++i) {  // a few pieces, mostly in order already
    const std::uint64_t v = ranges[i];
    std::size_t j = i;
    for (; j > 0 && ranges[j - 1] > v; --j) ranges[j] = ranges[j - 1];
    ranges[j] = v;
  }
  std::size_t i = 0;
  while (i < count) {
    const int lo = static_cast<int>(ranges[i] >> 32);
    int hi = static_cast<int>(ranges[i] & 0xFFFFFFFFu);
    for (++i; i < count && static_cast<int>(ranges[i] >> 32) <= hi + detail::kMergeGap; ++i) {
      hi = std::max(hi, static_cast<int>(ranges[i] & 0xFFFFFFFFu));
    }
    // Up to the next cluster (past the last one, to the row's end: edges right of the image were dropped).
    cluster(lo, hi, std::min(i < count ? static_cast<int>(ranges[i] >> 32) : width, width));
  }
}

// Each cluster swept from its first cell with the sum carried from the one before, in blocks of four with a mask of
// its nonzero pixels where it is narrow, and one compositor call; the stretch up to the next cluster has that sum
// throughout, one span (none in a hole). Zeroes the clusters' cells.
template <FillRule R, bool kAvx2>
[[gnu::always_inline]] inline void resolve_clusters(int y, int width, std::uint64_t* ranges, std::size_t count,
                                                    double* acc, float* cov, const SolidOver8* target,
                                                    CoverageSink& sink) {
  double sum = 0;
  for_each_cluster(width, ranges, count, [&](int lo, int hi, int gap_end) {
    resolve_cluster<R, kAvx2>(y, width, 0, lo, hi, gap_end, acc, cov, sum, target, sink);
  });
}

// resolve_cluster for fixed-point or wide cells (fixed_cells.hpp): cells lo .. hi (relative to x_base; cells is cell
// x_base) swept from `sum` (blocks of eight or four, which read up to seven or three cells past hi: untouched,
// zero), blended straight into the target's pixels where there is one (fixed-point cells only), else one compositor
// call for the nonzero pixels; then the stretch up to gap_end as one span.
template <FillRule R, bool kAvx2, class Cell>
[[gnu::always_inline]] inline void resolve_fixed_cluster(int y, int width, int x_base, int lo, int hi, int gap_end,
                                                         Cell* cells, float* cov, Cell& sum, const SolidOver8* target,
                                                         CoverageSink& sink) {
  const int visible = std::max(std::min(hi + 1, width - x_base) - lo, 0);
  bool blended = false;
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if constexpr (kAvx2 && std::is_same_v<Cell, std::int32_t>) {
    if (target) {
      auto* const px = reinterpret_cast<std::uint32_t*>(target->pixels + y * target->stride) + x_base + lo;
      detail::blend_fixed_cells_avx2<R>(cells + lo, hi - lo + 1, visible, sum, px, target->color,
                                        whole_step_room(*target, x_base + lo));
      blended = true;
    }
  }
#endif
  if (!blended) {
    detail::sweep_fixed_cells<R, kAvx2>(cells + lo, cov, hi - lo + 1, sum);
    int a = 0, b = visible;
    detail::trim_zeros(cov, a, b);
    if (b - a == 1) {
      sink.span(y, x_base + lo + a, x_base + lo + b, cov[a]);
    } else if (b > a) {
      sink.row(y, x_base + lo + a, x_base + lo + b, cov + a);
    }
  }
  if (gap_end > hi + 1) {
    const float c = detail::integer_cell_coverage<R>(sum);
    if (c > 0) sink.span(y, x_base + hi + 1, x_base + gap_end, c);
  }
}

// A row in fixed-point cells, once its pieces are added: the choices of the double cells' row (below) with the
// integer sweeps. Narrow rows without the sink's pixels go in the batch, as there; crowded ("whole") rows keep their
// coverage row (blending their long runs from the cells was no faster in fixed point either).
template <FillRule R, bool kAvx2>
[[gnu::always_inline]] inline void resolve_fixed_row(int y, int width, int x_lo, int x_hi, bool narrow, bool whole,
                                                     std::uint64_t* ranges, std::size_t clusters,
                                                     std::int32_t* fixed, float* cov, RowBatch& batch,
                                                     const SolidOver8* target, CoverageSink& sink) {
  std::int32_t sum = 0;
  if (narrow && !target) {
    float* const row_coverage = batch.slot();  // kNarrowRowCoverage floats: blocks of eight up to x_hi
    detail::sweep_fixed_cells<R, kAvx2>(fixed + x_lo, row_coverage, x_hi - x_lo + 1, sum);
    int from = 0, to = std::max(std::min(x_hi + 1, width) - x_lo, 0);
    detail::trim_zeros(row_coverage, from, to);
    if (to > from) batch.add(y, x_lo + from, x_lo + to, row_coverage + from);
    const float right = detail::fixed_coverage<R>(sum);
    if (right > 0 && x_hi + 1 < width) {
      batch.hand_over();
      sink.span(y, x_hi + 1, width, right);
    }
    return;
  }
  batch.hand_over();
  if (narrow || whole) {
    resolve_fixed_cluster<R, kAvx2>(y, width, 0, x_lo, x_hi, width, fixed, cov, sum, narrow ? target : nullptr, sink);
    return;
  }
  for_each_cluster(width, ranges, clusters, [&](int lo, int hi, int gap_end) {
    resolve_fixed_cluster<R, kAvx2>(y, width, 0, lo, hi, gap_end, fixed, cov, sum, target, sink);
  });
}

// A row in wide cells (rows of more than kFixedRowEdges edges), once its pieces are added: narrow and crowded rows
// swept from x_lo to x_hi as one cluster, sparse ones cluster by cluster, each into its coverage row and one
// compositor call, with spans between (as the double cells' rows without the sink's pixels).
template <FillRule R, bool kAvx2>
[[gnu::always_inline]] inline void resolve_wide_row(int y, int width, int x_lo, int x_hi, bool narrow, bool whole,
                                                    std::uint64_t* ranges, std::size_t clusters, std::int64_t* wide,
                                                    float* cov, RowBatch& batch, CoverageSink& sink) {
  batch.hand_over();
  std::int64_t sum = 0;
  if (narrow || whole) {
    return resolve_fixed_cluster<R, kAvx2>(y, width, 0, x_lo, x_hi, width, wide, cov, sum, nullptr, sink);
  }
  for_each_cluster(width, ranges, clusters, [&](int lo, int hi, int gap_end) {
    resolve_fixed_cluster<R, kAvx2>(y, width, 0, lo, hi, gap_end, wide, cov, sum, nullptr, sink);
  });
}

// Rows of up to this many active edges note their pieces' ranges as they add them (add_pieces_avx2).
constexpr std::size_t kRangedRowEdges = 8;

template <FillRule R, bool kAvx2>
[[gnu::always_inline]] inline void sweep_analytic_rows(const detail::EdgeTableView& table, const RowBuffers& b,
                                                       int y_from, int y_to, int width, CoverageSink& sink) {
  const std::vector<Edge>& edges = table.edges;
  const std::vector<std::uint32_t>& order = table.order;
  const std::vector<std::uint32_t>& bucket_start = table.bucket_start;
  const int y_min = table.y_min;
  detail::ActiveEdges& a = b.columns;
  double* const acc = b.acc;
  float* const cov = b.cov;
  RowBatch batch(sink, b.batch, detail::kNarrowRowCoverage);  // the narrow rows
  // Narrow rows and sparse rows' clusters blended straight into the sink's pixels where it allows (resolve_cluster).
  // Not the rows swept whole: their long runs were 3-5 % slower so (the coverage row's two tight loops against one
  // longer one).
  SolidOver8 pixels;
  const SolidOver8* const target = kAvx2 ? solid_target(sink, pixels, width, y_to) : nullptr;
  pixels.width = std::min(pixels.width, table.x_end);  // (whole_step_room: no pixel right of the fill's columns)
  // a.x[k]: where active edge k enters the current row (its x at max(y0, row top)). An edge that goes on below the
  // row leaves at x_at(bottom), which is the very number x_at(top) gives in the next row: it is kept instead of
  // computed twice. (Edges active from before y_from enter with x_at(y_from), the same number again.)
  a.clear();
  a.reserve(b.active.size());
  for (const std::uint32_t index : b.active) {
    const Edge& e = edges[index];
    a.push(e, y_from <= e.y0 ? e.x0 : e.x_at(y_from));
  }
  for (int y = y_from; y < y_to; ++y) {
    const int r = y - y_min;
    const std::uint32_t first = bucket_start[r], last = bucket_start[r + 1];
    if (last > first) {
      a.reserve(a.size + (last - first));
      for (std::uint32_t k = first; k < last; ++k) {
        const Edge& e = edges[order[k]];
        a.push(e, e.x0);  // bucketed in its first row: it enters at its top
      }
    }
    const std::size_t n = a.size;
    if (n == 0) continue;
    const double top = y, bottom = y + 1.0;
    int x_lo = width + 1, x_hi = 0;
    bool all_go_on;
#ifdef VRASTER_HAVE_AVX2_KERNELS
    if constexpr (kAvx2) {
      all_go_on = leave_row_avx2(a, top, bottom);
    } else
#endif
    {
      all_go_on = leave_row(a, 0, top, bottom);
    }
    const double* const xs = a.x.data();
    const double* const xbs = a.xb.data();
    const double* const hs = a.h.data();
    std::size_t clusters = 0;  // pieces of a sparse wide row, for resolve_clusters
    bool ranged = false;       // whether the pieces' ranges were noted as they were added
    // Rows of few edges in fixed point, of more in wide cells, of a great many in doubles (fixed_cells.hpp): a
    // choice from the row's own edges, so bands and queued fills make it as a whole sweep does.
    std::int32_t* const fixed = n <= detail::kFixedRowEdges ? b.fixed : nullptr;
    std::int64_t* const wide = !fixed && n <= detail::kWideRowEdges ? b.wide : nullptr;
#ifdef VRASTER_HAVE_AVX2_KERNELS
    if constexpr (kAvx2) {
      // No branch on how many cells a piece touches (mispredicted for short edges and, less often, for long ones;
      // stars 6-8 % faster without it).
      if (wide) {
        add_pieces_avx2<false>(a, wide, x_lo, x_hi, nullptr);  // (rows of many edges: never ranged)
      } else if (fixed) {
        if (n <= kRangedRowEdges) {
          clusters = add_pieces_avx2<true>(a, fixed, x_lo, x_hi, a.ranges.data());
          ranged = true;
        } else {
          add_pieces_avx2<false>(a, fixed, x_lo, x_hi, nullptr);
        }
      } else if (n <= kRangedRowEdges) {
        clusters = add_pieces_avx2<true>(a, acc, x_lo, x_hi, a.ranges.data());
        ranged = true;
      } else {
        add_pieces_avx2<false>(a, acc, x_lo, x_hi, nullptr);
      }
    } else
#endif
    {
      for (std::size_t k = 0; k < n; ++k) {
        if (hs[k] == 0) continue;
        const double xa = xs[k], xb = xbs[k];
        if (wide) {
          detail::accumulate_piece_fixed(wide, xa, xb, hs[k]);
        } else if (fixed) {
          detail::accumulate_piece_fixed(fixed, xa, xb, hs[k]);
        } else {
          accumulate_piece(acc, xa, xb, hs[k]);
        }
        x_lo = std::min(x_lo, piece_first_cell(xa, xb));
        x_hi = std::max(x_hi, piece_last_cell(xa, xb));
      }
    }
    // A sparse wide row's pieces are noted now as ranges of cells, while the columns still hold them (already noted
    // by the split in rows of few edges; otherwise from the pieces again, rather than noted piece by piece in every
    // row: most rows of many edges are narrow or crowded and need none). A row with pieces close together is swept
    // whole from x_lo to x_hi, as one cluster. Both tests depend on the row's own edges only, so a band or a queued
    // fill decides every row as a whole sweep does.
    const bool narrow = x_hi - x_lo < detail::kNarrowRowCells;
    const bool whole = static_cast<std::size_t>(x_hi - x_lo) <= kWholeRunCellsPerEdge * n;
    if (x_lo <= x_hi && !narrow && !whole) {
      if (!ranged) {
        std::uint64_t* const ranges = a.ranges.data();
        for (std::size_t k = 0; k < n; ++k) {
          if (hs[k] == 0) continue;
          ranges[clusters++] = static_cast<std::uint64_t>(piece_first_cell(xs[k], xbs[k])) << 32 |
                               static_cast<std::uint32_t>(piece_last_cell(xs[k], xbs[k]));
        }
      }
    }
    // The edges that go on below enter the next row where they leave this one; the others retire (the list shrinks
    // in place, in order).
    if (all_go_on) {
      a.x.swap(a.xb);
#ifdef VRASTER_HAVE_AVX2_KERNELS
    } else if constexpr (kAvx2) {
      retire_ended_avx2(a, bottom);
#endif
    } else {
      std::size_t kept = 0;
      for (std::size_t k = 0; k < n; ++k) {
        if (a.y1[k] > bottom) {
          if (kept != k) a.move(k, kept);
          a.x[kept++] = a.xb[k];
        }
      }
      a.size = kept;
    }
    if (x_lo > x_hi) continue;
    if (wide) {
      resolve_wide_row<R, kAvx2>(y, width, x_lo, x_hi, narrow, whole, a.ranges.data(), clusters, wide, cov, batch,
                                 sink);
      continue;
    }
    if (fixed) {
      resolve_fixed_row<R, kAvx2>(y, width, x_lo, x_hi, narrow, whole, a.ranges.data(), clusters, fixed, cov, batch,
                                  target, sink);
      continue;
    }
    if (!narrow) {
      batch.hand_over();
      if (whole) {  // one cluster, with its coverage row (blending these long runs from the cells was slower)
        double sum = 0;
        resolve_cluster<R, kAvx2>(y, width, 0, x_lo, x_hi, width, acc, cov, sum, nullptr, sink);
      } else {
        resolve_clusters<R, kAvx2>(y, width, a.ranges.data(), clusters, acc, cov, target, sink);
      }
      continue;
    }
    if (target) {  // one cluster, on the grid sweep_narrow_row takes (blocks of four from x_lo)
      double sum = 0;
      resolve_cluster<R, kAvx2>(y, width, 0, x_lo, x_hi, width, acc, cov, sum, target, sink);
      continue;
    }
    float* const row_coverage = batch.slot();
    std::uint32_t nonzero;
    const float right = detail::sweep_narrow_row<R, kAvx2>(x_lo, x_hi, acc, row_coverage, nonzero);
    int from, to;
    if (detail::nonzero_bounds(nonzero, width - x_lo, from, to)) {
      batch.add(y, x_lo + from, x_lo + to, row_coverage + from);
    }
    if (right > 0 && x_hi + 1 < width) {
      batch.hand_over();
      sink.span(y, x_hi + 1, width, right);
    }
  }
  batch.hand_over();
}

// The row loop compiled for AVX2 (the pieces split four at a time, the AVX2 block for short runs) and for any x86-64;
// the AVX2 build has no FMA, the blocks add in one order, and the split gives accumulate_piece's bits, so both give
// the same bits.
template <FillRule R>
void sweep_analytic_rows_portable(const detail::EdgeTableView& table, const RowBuffers& b, int y_from, int y_to,
                                  int width, CoverageSink& sink) {
  sweep_analytic_rows<R, false>(table, b, y_from, y_to, width, sink);
}
#ifdef VRASTER_HAVE_AVX2_KERNELS
// Flattened (every call inside inlined, the kernels of cells.hpp and blend_cells.hpp too), so that the kernels'
// constants are set up once per band instead of once per row or cluster: 4 % fewer instructions on large polygons
// (docs/performance.md). The kernels cannot be always_inline themselves: the shared row code that calls them is also
// compiled without AVX2 for the portable sweep.
template <FillRule R>
[[gnu::target("avx2"), gnu::flatten]] void sweep_analytic_rows_avx2(const detail::EdgeTableView& table,
                                                                    const RowBuffers& b, int y_from, int y_to,
                                                                    int width, CoverageSink& sink) {
  sweep_analytic_rows<R, true>(table, b, y_from, y_to, width, sink);
}
#endif

// Small paths: every edge walks its own rows into a dense block of cells (the path's rows x columns), then one
// running sum per row. The cell arithmetic is the row sweep's; what it saves is the per-row bookkeeping (edge
// table, active list, touched bits), which dominates glyph-sized paths. Coordinates are shifted by the block's
// integer left column, which is exact for doubles, so the cell fractions are the same numbers.
// Wide blocks (kTrimmedDenseColumns columns or more; DenseRows::Trimmed) note the first and last cell the pieces of
// each row wrote, and the running sum runs only from the block of four that holds the first
// to the block that holds the last (blocks counted from column 0, so the sums are added in the same order as a
// sweep of the whole row); the cells outside are zero, so the sum is 0 left of them and constant right of them.
// Narrow blocks sweep whole rows: there is little outside to skip, and noting it would cost more.
constexpr int kTrimmedDenseColumns = 24;

// A dense block's rows are this many cells apart (columns rounded up to whole blocks of the sweep: four double cells,
// eight fixed-point ones): a row is swept in whole blocks from a block's first cell, each row's own (the cells past
// `columns` stay zero).
template <class Cell>
constexpr int dense_block_cells() {
  return std::is_same_v<Cell, std::int32_t> ? detail::kFixedBlock : 4;
}
template <class Cell = double>
constexpr int dense_stride(int columns) {
  return (columns + dense_block_cells<Cell>() - 1) & ~(dense_block_cells<Cell>() - 1);
}
static_assert(kTrimmedDenseColumns <= 32, "a narrow block's row fits sweep_narrow_row's nonzero mask");

// What a dense block notes of each row while its edges walk: nothing (Whole: narrow blocks sweep every row whole),
// the first and last cell a piece wrote (Trimmed: each row swept between them), or those and each piece's own range
// of cells (Ranged: rows whose pieces lie far apart are swept as clusters, with spans between them, as the row
// sweep's sparse rows are).
enum class DenseRows { Whole, Trimmed, Ranged };

// A Ranged row's notes: [first, last, pieces, first0, last0, first1, last1, ...], the ranges of its first kRowRanges
// pieces (a row of more is swept between first and last). Trimmed rows keep [first, last].
constexpr int kRowRanges = 4;
constexpr int row_notes(DenseRows mode) { return mode == DenseRows::Ranged ? 3 + 2 * kRowRanges : 2; }

// A piece that wrote cells first .. last of the row whose notes are `notes`.
template <DenseRows kMode>
[[gnu::always_inline]] inline void note_piece(int* notes, int first, int last) {
  int* const row_extent = notes;
  row_extent[0] = std::min(row_extent[0], first);
  row_extent[1] = std::max(row_extent[1], last);
  if constexpr (kMode == DenseRows::Ranged) {
    const int k = row_extent[2]++;
    if (k < kRowRanges) {
      row_extent[3 + 2 * k] = first;
      row_extent[4 + 2 * k] = last;
    }
  }
}

// Edges of fewer rows, and vertical edges, keep the scalar walk: four lanes for them cost more than their branches'
// mispredictions (text 5-8 % slower with them, docs/performance.md).
constexpr int kWalkMinRows = 3;
#ifdef VRASTER_HAVE_AVX2_KERNELS
// The scalar walk below (sweep_dense_block) four rows a step: the x where edge e leaves each of rows y .. y + 3
// computed as Edge::x_at computes it (no FMA; minpd / maxpd in the operand order of leave_row_avx2), the four pieces
// split at once (split4) and added row by row, so every cell gets the numbers and the order of the scalar walk.
// Rows from r1 on are left alone.
// Into fixed-point cells (Cell std::int32_t): the split's rounded shares, as add_pieces_avx2 adds them.
template <DenseRows kMode, class Cell>
[[gnu::target("avx2")]] inline void walk_edge_avx2(const Edge& e, int r0, int r1, int y_min, double shift,
                                                   Cell* block, int stride, int* notes) {
  constexpr bool kFixed = !std::is_same_v<Cell, double>;
  double ya = std::max(e.y0, static_cast<double>(r0));
  double xa = (ya == e.y0 ? e.x0 : e.x_at(ya)) - shift;
  const __m256d y0 = _mm256_set1_pd(e.y0), y1 = _mm256_set1_pd(e.y1), x0 = _mm256_set1_pd(e.x0);
  const __m256d x1 = _mm256_set1_pd(e.x1), dxdy = _mm256_set1_pd(e.dxdy), winding = _mm256_set1_pd(e.winding);
  const __m256d lo = _mm256_min_pd(x1, x0), hi = _mm256_max_pd(x1, x0), to_cells = _mm256_set1_pd(shift);
  const __m256d bottoms = _mm256_setr_pd(1, 2, 3, 4);
  const __m128i lanes = _mm_setr_epi32(0, 1, 2, 3);
  for (int y = r0; y < r1; y += 4) {
    // Row y + i ends at min(y1, y + i + 1) (std::min's operand order); it is left at x1 at the edge's end.
    const __m256d yb = _mm256_min_pd(_mm256_add_pd(_mm256_set1_pd(y), bottoms), y1);
    __m256d x = _mm256_add_pd(x0, _mm256_mul_pd(_mm256_sub_pd(yb, y0), dxdy));
    x = _mm256_min_pd(hi, _mm256_max_pd(x, lo));
    const __m256d xb = _mm256_sub_pd(_mm256_blendv_pd(x, x1, _mm256_cmp_pd(yb, y1, _CMP_EQ_OQ)), to_cells);
    // Each row starts where the one above ends.
    const __m256d ya4 = _mm256_blend_pd(_mm256_permute4x64_pd(yb, 0x90), _mm256_set1_pd(ya), 0x1);
    const __m256d xa4 = _mm256_blend_pd(_mm256_permute4x64_pd(xb, 0x90), _mm256_set1_pd(xa), 0x1);
    const __m256d h = _mm256_mul_pd(_mm256_sub_pd(yb, ya4), winding);
    const detail::SplitLanes<Cell> split(xa4, xb, h);
    const __m256i in_rows = _mm256_cvtepi32_epi64(_mm_cmpgt_epi32(_mm_set1_epi32(r1 - y), lanes));
    const int pieces =
        _mm256_movemask_pd(_mm256_and_pd(_mm256_cmp_pd(yb, ya4, _CMP_GT_OQ), _mm256_castsi256_pd(in_rows)));
    for (int i = 0; i < 4; ++i) {
      if (!(pieces >> i & 1)) continue;
      Cell* const row = block + static_cast<std::size_t>(y + i - y_min) * stride;
      if constexpr (kFixed) {
        detail::add_split_lane(split, i, row);
      } else {
        split.add(i, row);
      }
      if constexpr (kMode != DenseRows::Whole) {
        note_piece<kMode>(notes + row_notes(kMode) * (y + i - y_min), split.first[i],
                          split.first[i] + split.past[i] + 1);
      }
    }
    ya = yb[3];
    xa = split.xb[3];
  }
}
#endif

// The clusters of a Ranged row (notes `row_notes`) whose pieces lie at least detail::kMergeGap cells apart: their
// first and last cells in lo and hi (relative to x_base), each cluster starting on a block of the sweep (kBlock cells)
// so that its blocks stay inside the row (the cells before a piece in its block are untouched: zero). Returns how
// many; 0 for a row to sweep between its first and last cell (one cluster, a narrow row, or more pieces than noted).
template <int kBlock>
[[gnu::always_inline]] inline int ranged_clusters(const int* row_notes, int (&lo)[kRowRanges], int (&hi)[kRowRanges]) {
  static_assert(detail::kMergeGap >= kBlock - 1, "a cluster's last block must not reach the next cluster's cells");
  const int count = row_notes[2];
  if (count < 2 || count > kRowRanges || row_notes[1] - row_notes[0] < detail::kNarrowRowCells) return 0;
  for (int k = 0; k < count; ++k) {  // sorted by first cell, then last
    const int l = row_notes[3 + 2 * k] & ~(kBlock - 1), h = row_notes[4 + 2 * k];
    int j = k;
    for (; j > 0 && (lo[j - 1] > l || (lo[j - 1] == l && hi[j - 1] > h)); --j) {
      lo[j] = lo[j - 1];
      hi[j] = hi[j - 1];
    }
    lo[j] = l;
    hi[j] = h;
  }
  int clusters = 1;
  for (int k = 1; k < count; ++k) {
    if (lo[k] <= hi[clusters - 1] + detail::kMergeGap) {
      hi[clusters - 1] = std::max(hi[clusters - 1], hi[k]);
    } else {
      lo[clusters] = lo[k];
      hi[clusters] = hi[k];
      ++clusters;
    }
  }
  return clusters > 1 ? clusters : 0;
}

// The rows of a dense block in double cells, once its edges have walked.
template <FillRule R, DenseRows kMode, bool kAvx2>
[[gnu::always_inline]] inline void resolve_dense_rows(int y_min, int y_max, int x_base, int columns, int width,
                                                      double* block, const int* notes, RowBatch& batch,
                                                      const SolidOver8* target, CoverageSink& sink) {
  constexpr int kNotes = row_notes(kMode);
  const int stride = dense_stride(columns);
  const int visible = std::min(columns, width - x_base);  // the last cells may lie at or right of the image edge
  for (int y = y_min; y < y_max; ++y) {
    double* row = block + static_cast<std::size_t>(y - y_min) * stride;
    float* const cov = batch.slot();
    int a = 0, b = visible;
    float c;  // the coverage right of the swept cells
    if constexpr (kMode != DenseRows::Whole) {
      const int* row_extent = notes + kNotes * (y - y_min);
      if (row_extent[1] < 0) continue;  // no piece in this row: coverage 0 all along
      if constexpr (kMode == DenseRows::Ranged) {
        int lo[kRowRanges], hi[kRowRanges];
        if (const int clusters = ranged_clusters<4>(row_extent, lo, hi)) {
          // Cluster by cluster with spans between them, as the row sweep's sparse rows (resolve_clusters).
          batch.hand_over();  // the rows before go first
          double sum = 0;
          const int row_end = width - x_base;  // the image's right edge, in cells from x_base
          for (int k = 0; k < clusters; ++k) {
            const int gap_end = std::min(k + 1 < clusters ? lo[k + 1] : row_end, row_end);
            resolve_cluster<R, kAvx2>(y, width, x_base, lo[k], std::min(hi[k], columns - 1), gap_end, row,
                                      batch.slot(), sum, target, sink);
          }
          continue;
        }
      }
      const int from = row_extent[0] & ~3, to = std::min(columns, (row_extent[1] + 4) & ~3);
      double sum = 0;
      if (target) {
        resolve_cluster<R, kAvx2>(y, width, x_base, from, std::min(row_extent[1], columns - 1), width - x_base, row,
                                  cov, sum, target, sink);
        continue;
      }
      if (to - from <= detail::kNarrowRowCells) {
        // A short stretch (most rows of small and medium shapes): the narrow row's blocks (on the same grid, so the
        // same sums) and its mask of nonzero pixels instead of trimming loops.
        const std::uint32_t nonzero =
            detail::sweep_narrow_cells<R, kAvx2>(0, to - from - 1, row + from, cov + from, sum);
        c = coverage_of<R>(sum);
        int lo = 0, hi = 0;
        const bool any = detail::nonzero_bounds(nonzero, visible - from, lo, hi);
        if (c > 0 && to < visible) {  // the coverage goes on to the block's right end
          std::fill(cov + to, cov + visible, c);
          a = any ? from + lo : to;
        } else if (any) {
          a = from + lo;
          b = from + hi;
        } else {
          b = a;
        }
      } else {
        detail::sweep_cells_for<R, kAvx2>(row + from, cov + from, to - from, sum);
        c = coverage_of<R>(sum);
        a = from;
        if (c > 0) {
          std::fill(cov + std::min(to, visible), cov + visible, c);
        } else {
          b = std::min(b, to);
        }
        detail::trim_zeros(cov, a, b);
      }
    } else {
      if (target) {
        double sum = 0;
        resolve_cluster<R, kAvx2>(y, width, x_base, 0, columns - 1, width - x_base, row, cov, sum, target, sink);
        continue;
      }
      // The whole row (whole blocks from column 0, as sweep_cells adds them) and which pixels have coverage.
      std::uint32_t nonzero;
      c = detail::sweep_narrow_row<R, kAvx2>(0, columns - 1, row, cov, nonzero);
      if (!detail::nonzero_bounds(nonzero, visible, a, b)) b = a;
    }
    if (b > a) batch.add(y, x_base + a, x_base + b, cov + a);
    // Edges right of the image were dropped, so the sum need not return to 0: it holds to the row's end.
    if (x_base + columns < width && c > 0) {
      batch.hand_over();
      sink.span(y, x_base + columns, width, c);
    }
  }
  batch.hand_over();
}

// The rows of a dense block in fixed-point or wide cells (Trimmed or Ranged), once its edges have walked: as the
// double cells' rows below, with the integer sweeps (resolve_fixed_cluster), from blocks of eight (four).
template <FillRule R, DenseRows kMode, bool kAvx2, class Cell>
[[gnu::always_inline]] inline void resolve_dense_rows_fixed(int y_min, int y_max, int x_base, int columns, int width,
                                                            Cell* block, const int* notes, RowBatch& batch,
                                                            const SolidOver8* target, CoverageSink& sink) {
  constexpr int kBlock = dense_block_cells<Cell>();
  static_assert(kMode != DenseRows::Whole, "narrow blocks keep double cells");
  constexpr int kNotes = row_notes(kMode);
  const int stride = dense_stride<Cell>(columns);
  const int row_end = width - x_base;  // the image's right edge, in cells from x_base
  for (int y = y_min; y < y_max; ++y) {
    Cell* const row = block + static_cast<std::size_t>(y - y_min) * stride;
    const int* const row_extent = notes + kNotes * (y - y_min);
    if (row_extent[1] < 0) continue;  // no piece in this row: coverage 0 all along
    Cell sum = 0;
    if constexpr (kMode == DenseRows::Ranged) {
      int lo[kRowRanges], hi[kRowRanges];
      if (const int clusters = ranged_clusters<kBlock>(row_extent, lo, hi)) {
        batch.hand_over();  // the rows before go first
        for (int k = 0; k < clusters; ++k) {
          const int gap_end = std::min(k + 1 < clusters ? lo[k + 1] : row_end, row_end);
          resolve_fixed_cluster<R, kAvx2>(y, width, x_base, lo[k], std::min(hi[k], columns - 1), gap_end, row,
                                          batch.slot(), sum, target, sink);
        }
        continue;
      }
    }
    const int from = row_extent[0] & ~(kBlock - 1), last = std::min(row_extent[1], columns - 1);
    if (target) {
      resolve_fixed_cluster<R, kAvx2>(y, width, x_base, from, last, row_end, row, batch.slot(), sum, target, sink);
      continue;
    }
    // Without the sink's pixels: the row's coverage in the batch, and a span right of its last cell.
    float* const cov = batch.slot();
    detail::sweep_fixed_cells<R, kAvx2>(row + from, cov + from, last - from + 1, sum);
    int a = from, b = std::max(std::min(last + 1, row_end), from);
    detail::trim_zeros(cov, a, b);
    if (b > a) batch.add(y, x_base + a, x_base + b, cov + a);
    const float c = detail::integer_cell_coverage<R>(sum);
    if (c > 0 && last + 1 < row_end) {
      batch.hand_over();
      sink.span(y, x_base + last + 1, width, c);
    }
  }
  batch.hand_over();
}

// kAvx2: compiled into an AVX2 function (sweep_dense_rows_avx2), whose narrow blocks' rows take sweep_narrow_row's
// AVX2 blocks and its mask of nonzero coverage (no trimming loops). Cell: double, or std::int32_t for fixed-point
// cells (Trimmed and Ranged blocks of fills of few edges, fixed_cells.hpp), or std::int64_t for wide cells (those of
// fills of more).
template <FillRule R, DenseRows kMode, bool kAvx2, class Cell>
[[gnu::always_inline]] inline void sweep_dense_block(const std::vector<Edge>& edges, int y_min, int y_max, int x_base,
                                                     int columns, int width, Cell* block, int* notes,
                                                     const detail::RowBatchBuffers& out, CoverageSink& sink) {
  constexpr bool kFixed = !std::is_same_v<Cell, double>;
  const int stride = dense_stride<Cell>(columns);
  RowBatch batch(sink, out, static_cast<std::size_t>(stride));
  const double shift = x_base;
  constexpr int kNotes = row_notes(kMode);
  // Every row blended straight into the sink's pixels where it allows (resolve_cluster): small shapes 5-10 % faster,
  // and no loss on wide rows here (docs/performance.md).
  SolidOver8 pixels;
  const SolidOver8* const target = kAvx2 ? solid_target(sink, pixels, width, y_max) : nullptr;
  pixels.width = std::min(pixels.width, x_base + columns);  // (whole_step_room: no pixel right of the fill's columns)
  for (int r = 0; kMode != DenseRows::Whole && r < y_max - y_min; ++r) {
    notes[kNotes * r] = columns;
    notes[kNotes * r + 1] = -1;
    if constexpr (kMode == DenseRows::Ranged) notes[kNotes * r + 2] = 0;
  }
  for (const Edge& e : edges) {
    const int r0 = std::max(static_cast<int>(std::floor(e.y0)), y_min);
    const int r1 = std::min(static_cast<int>(std::ceil(e.y1)), y_max);
    if (r0 >= r1) continue;  // outside this strip or band
#ifdef VRASTER_HAVE_AVX2_KERNELS
    if constexpr (kAvx2) {
      if (r1 - r0 >= kWalkMinRows && e.x0 != e.x1) {
        walk_edge_avx2<kMode, Cell>(e, r0, r1, y_min, shift, block, stride, notes);
        continue;
      }
    }
#endif
    // The edge's piece in row y runs from (ya, xa) to (yb, xb): ya = max(y0, y), yb = min(y1, y + 1), x at each
    // (x0, x1 at the ends). Below the first row ya is y, the previous row's yb: its x is carried, not computed again.
    double ya = std::max(e.y0, static_cast<double>(r0));
    double xa = (ya == e.y0 ? e.x0 : e.x_at(ya)) - shift;
    for (int y = r0; y < r1; ++y) {
      const double yb = std::min(e.y1, y + 1.0);
      const double xb = (yb == e.y1 ? e.x1 : e.x_at(yb)) - shift;
      if (yb > ya) {
        Cell* const row = block + static_cast<std::size_t>(y - y_min) * stride;
        if constexpr (kFixed) {
          detail::accumulate_piece_fixed(row, xa, xb, (yb - ya) * e.winding);
        } else {
          accumulate_piece(row, xa, xb, (yb - ya) * e.winding);
        }
        if constexpr (kMode != DenseRows::Whole) {
          note_piece<kMode>(notes + kNotes * (y - y_min), static_cast<int>(std::min(xa, xb)),
                              static_cast<int>(std::max(xa, xb)) + 1);
        }
      }
      ya = yb;
      xa = xb;
    }
  }
  if constexpr (kFixed) {
    resolve_dense_rows_fixed<R, kMode, kAvx2>(y_min, y_max, x_base, columns, width, block, notes, batch, target, sink);
  } else {
    resolve_dense_rows<R, kMode, kAvx2>(y_min, y_max, x_base, columns, width, block, notes, batch, target, sink);
  }
}

template <FillRule R, DenseRows kMode, class Cell>
void sweep_dense_rows_portable(const std::vector<Edge>& edges, int y_min, int y_max, int x_base, int columns,
                               int width, Cell* block, int* notes, const detail::RowBatchBuffers& out,
                               CoverageSink& sink) {
  sweep_dense_block<R, kMode, false>(edges, y_min, y_max, x_base, columns, width, block, notes, out, sink);
}
#ifdef VRASTER_HAVE_AVX2_KERNELS
// Flattened as sweep_analytic_rows_avx2 (thin shapes: 5 % fewer instructions).
template <FillRule R, DenseRows kMode, class Cell>
[[gnu::target("avx2"), gnu::flatten]] void sweep_dense_rows_avx2(const std::vector<Edge>& edges, int y_min,
                                                                 int y_max, int x_base, int columns, int width,
                                                                 Cell* block, int* notes,
                                                                 const detail::RowBatchBuffers& out,
                                                                 CoverageSink& sink) {
  sweep_dense_block<R, kMode, true>(edges, y_min, y_max, x_base, columns, width, block, notes, out, sink);
}
#endif

template <FillRule R, DenseRows kMode, class Cell>
void sweep_dense_rows(const std::vector<Edge>& edges, int y_min, int y_max, int x_base, int columns, int width,
                      Cell* block, int* notes, const detail::RowBatchBuffers& out, CoverageSink& sink) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (detail::cpu_has_avx2()) {
    return sweep_dense_rows_avx2<R, kMode>(edges, y_min, y_max, x_base, columns, width, block, notes, out, sink);
  }
#endif
  sweep_dense_rows_portable<R, kMode>(edges, y_min, y_max, x_base, columns, width, block, notes, out, sink);
}

// A block of the given mode; in fixed-point or wide cells where `fixed` or `wide` is given (Trimmed and Ranged
// blocks only).
template <FillRule R>
void sweep_dense_rows(DenseRows mode, const std::vector<Edge>& edges, int y_min, int y_max, int x_base, int columns,
                      int width, double* block, std::int32_t* fixed, std::int64_t* wide, int* notes,
                      const detail::RowBatchBuffers& out, CoverageSink& sink) {
  auto in_cells = [&](auto mode_constant, auto* cells) {
    sweep_dense_rows<R, decltype(mode_constant)::value>(edges, y_min, y_max, x_base, columns, width, cells, notes, out,
                                                        sink);
  };
  auto with_cells = [&](auto mode_constant) {
    if (fixed) return in_cells(mode_constant, fixed);
    if (wide) return in_cells(mode_constant, wide);
    in_cells(mode_constant, block);
  };
  switch (mode) {
    case DenseRows::Ranged:
      return with_cells(std::integral_constant<DenseRows, DenseRows::Ranged>{});
    case DenseRows::Trimmed:
      return with_cells(std::integral_constant<DenseRows, DenseRows::Trimmed>{});
    case DenseRows::Whole:
      return in_cells(std::integral_constant<DenseRows, DenseRows::Whole>{}, block);
  }
}

}  // namespace

// Blocks up to this many cells always take the dense sweep (glyph-sized paths); larger ones up to the dense limit
// when they hold at most kDenseCellsPerOutline cells per unit of outline.
constexpr std::int64_t kAlwaysDenseCells = 8192;
constexpr double kDenseCellsPerOutline = 16;

// Thin shapes (slivers, the outlines of thin strokes) take the dense sweep whatever their box, in strips
// (sweep_dense_range): each of their rows is swept only between its first and last written cell, so an empty box
// costs nothing, and the edges walk their rows without the active list. A shape is thin when its area is at most
// kThinAreaPerOutline per unit of outline and, on kThinSampleRows rows spread over its height, the edges' x span at
// most kThinRowCells cells on average (a ring with thin walls passes the first test, not the second: its rows span
// the hole). Only fills of up to kThinMaxEdges edges are tested: the test is a pass over the edges, and on a fill of
// many (a large curved shape) it cost more than thin shapes save (cubic_256 2 % slower). thin_slivers 12 % faster
// (docs/performance.md).
constexpr std::size_t kThinMaxEdges = 64;
constexpr double kThinAreaPerOutline = 2;
constexpr int kThinSampleRows = 16;
constexpr double kThinRowCells = 24;

namespace {
bool thin_shape(const std::vector<Edge>& edges, int y_min, int y_max) {
  if (edges.size() > kThinMaxEdges) return false;
  double signed_area = 0, outline = 0;
  for (const Edge& e : edges) {
    signed_area += 0.5 * (e.x0 + e.x1) * (e.y1 - e.y0) * e.winding;
    outline += (e.y1 - e.y0) + std::abs(e.x1 - e.x0);
  }
  if (std::abs(signed_area) > kThinAreaPerOutline * outline) return false;
  // Sample row k is the line y = y_min + (k + 0.5) * step; each edge visits the samples between its ends.
  double lo[kThinSampleRows], hi[kThinSampleRows];
  std::fill(lo, lo + kThinSampleRows, std::numeric_limits<double>::infinity());
  std::fill(hi, hi + kThinSampleRows, -std::numeric_limits<double>::infinity());
  const double step = static_cast<double>(y_max - y_min) / kThinSampleRows;
  for (const Edge& e : edges) {
    const int k0 = std::max(static_cast<int>(std::ceil((e.y0 - y_min) / step - 0.5)), 0);
    const int k1 = std::min(static_cast<int>(std::ceil((e.y1 - y_min) / step - 0.5)), kThinSampleRows);
    for (int k = k0; k < k1; ++k) {
      const double x = e.x_at(y_min + (k + 0.5) * step);
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  }
  double span = 0;
  for (int k = 0; k < kThinSampleRows; ++k) span += hi[k] > lo[k] ? hi[k] - lo[k] : 0.0;
  return span <= kThinRowCells * kThinSampleRows;
}
}  // namespace

// Larger fills take the dense sweep with their rows' pieces noted (DenseRows::Ranged) where their rows hold few
// pieces: at most kRangedPiecesPerRow per row on average (a convex shape has 2, plus one where an edge ends and the
// next begins), and kRangedMinColumns columns or more. Their edges then walk their rows without the active list, and
// each row's far-apart pieces are swept as clusters with spans between them. Opaque triangles 9 %, ellipses and
// turned rectangles 4-5 % faster; rings (4 pieces a row) and self-intersecting polygons slower, so they keep the row
// sweep (docs/performance.md).
constexpr double kRangedPiecesPerRow = 2.75;
constexpr int kRangedMinColumns = 64;
namespace {
bool few_pieces_per_row(const std::vector<Edge>& edges, int y_min, int y_max) {
  double pieces = 0;
  for (const Edge& e : edges) pieces += std::ceil(e.y1) - std::floor(e.y0);
  return pieces <= kRangedPiecesPerRow * (y_max - y_min);
}
}  // namespace

namespace {
// What a dense block of this kind and width notes of its rows.
DenseRows dense_rows_mode(detail::DenseKind kind, int columns) {
  if (kind == detail::DenseKind::Ranged) return DenseRows::Ranged;
  return columns >= kTrimmedDenseColumns ? DenseRows::Trimmed : DenseRows::Whole;
}

// Whether no row of the fill holds more than kFixedRowEdges pieces (an edge is a piece in every row it crosses), so
// that its rows can take fixed-point cells within their bound: trivially so for a fill of that many edges; else from
// a count of the edges starting and ending in each row (`counts`: scratch), over the fill's whole height.
bool few_pieces_in_every_row(const std::vector<Edge>& edges, std::vector<int>& counts) {
  if (edges.size() <= detail::kFixedRowEdges) return true;
  int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
  for (const Edge& e : edges) {
    lo = std::min(lo, static_cast<int>(std::floor(e.y0)));
    hi = std::max(hi, static_cast<int>(std::ceil(e.y1)));
  }
  counts.assign(static_cast<std::size_t>(hi - lo) + 1, 0);
  for (const Edge& e : edges) {
    ++counts[static_cast<std::size_t>(static_cast<int>(std::floor(e.y0)) - lo)];
    --counts[static_cast<std::size_t>(static_cast<int>(std::ceil(e.y1)) - lo)];
  }
  int crossing = 0;
  for (const int c : counts) {
    crossing += c;
    if (crossing > static_cast<int>(detail::kFixedRowEdges)) return false;
  }
  return true;
}
}  // namespace

// Once per fill, before its bands and strips (so that all of them decide alike): wide blocks (Trimmed, Ranged) whose
// rows hold at most kFixedRowEdges pieces each take fixed-point cells, where the rasterizer allows them.
detail::DenseCells detail::dense_cell_type(bool fixed_cells, DenseKind kind, int columns,
                                           const std::vector<Edge>& edges, std::vector<int>& scratch) {
  if (!fixed_cells || dense_rows_mode(kind, columns) == DenseRows::Whole) return DenseCells::Double;
  if (few_pieces_in_every_row(edges, scratch)) return DenseCells::Fixed;
  // (a row's pieces are at most the fill's edges)
  return edges.size() <= kWideRowEdges ? DenseCells::Wide : DenseCells::Double;
}

// The one choice of the dense sweep, for fills drawn at once and queued ones alike (both must take the same path).
detail::DenseKind detail::dense_kind(const std::vector<Edge>& edges, int y_min, int y_max, int columns,
                                     std::int64_t dense_limit) {
  if (edges.empty() || dense_limit <= 0) return DenseKind::None;
  const std::int64_t cells = static_cast<std::int64_t>(columns) * (y_max - y_min);
  if (cells <= kAlwaysDenseCells) return DenseKind::Dense;
  // A larger block pays where edges pass through a good share of it, or where every row's pieces lie close
  // together; otherwise the row sweep's runs and spans skip more.
  if (cells <= dense_limit && static_cast<double>(cells) <= kDenseCellsPerOutline * outline_cells(edges)) {
    return DenseKind::Dense;
  }
  if (thin_shape(edges, y_min, y_max)) return DenseKind::Dense;
  if (columns >= kRangedMinColumns && few_pieces_per_row(edges, y_min, y_max)) return DenseKind::Ranged;
  return DenseKind::None;
}

detail::RowBatchBuffers detail::row_batch_buffers(std::vector<CoverageRow>& batch, std::vector<float>& coverage,
                                                   int rows, int slot) {
  const auto slots = static_cast<std::size_t>(std::min(rows, kBatchRows));
  if (batch.size() < slots) batch.resize(slots);
  if (coverage.size() < slots * static_cast<std::size_t>(slot)) coverage.resize(slots * static_cast<std::size_t>(slot));
  return {batch.data(), coverage.data()};
}

// Rows [y_from, y_to) of a dense fill, in strips of at most Rasterizer::kDefaultDenseLimit cells (a thin shape's
// box may be the image's, and the block must stay in the cache). Each row takes the pieces of the edges inside it (in
// edge order) and a running sum of its own, so strips, like bands, give the bits one block would.
// Fixed-point or wide cells where dense_cell_type said so for the fill (its wide blocks: with at most kFixedRowEdges
// pieces in every row fixed-point cells, else wide ones; the row sweep's bound holds for both). Narrow blocks (glyphs,
// micro shapes) keep double cells: their sums are short, and their areas stay exact to the double's round-off.
void detail::sweep_dense_range(FillRule rule, DenseKind kind, const std::vector<Edge>& edges, int y_from, int y_to,
                               int x_base, int columns, int width, DenseCells cell_type, DenseScratch s,
                               CoverageSink& sink) {
  const DenseRows mode = dense_rows_mode(kind, columns);
  const bool fixed = cell_type == DenseCells::Fixed && mode != DenseRows::Whole;
  const bool wide = cell_type == DenseCells::Wide && mode != DenseRows::Whole;
  const int stride = fixed ? dense_stride<std::int32_t>(columns)
                           : wide ? dense_stride<std::int64_t>(columns) : dense_stride(columns);
  const int strip_rows =
      static_cast<int>(std::clamp<std::int64_t>(Rasterizer::kDefaultDenseLimit / stride, 1, y_to - y_from));
  // (plus kPieceSlack: a piece split without branches adds + 0 to up to 3 cells past the cell after its last, past
  // the block's last row too)
  const std::size_t cells =
      static_cast<std::size_t>(stride) * static_cast<std::size_t>(strip_rows) + detail::kPieceSlack;
  if (fixed && s.fixed_block.size() < cells) s.fixed_block.assign(cells, 0);  // zero; every sweep leaves it zero
  if (wide && s.wide_block.size() < cells) s.wide_block.assign(cells, 0);
  if (!fixed && !wide && s.block.size() < cells) s.block.assign(cells, 0.0);
  const auto notes = static_cast<std::size_t>(row_notes(DenseRows::Ranged)) * static_cast<std::size_t>(strip_rows);
  if (s.notes.size() < notes) s.notes.resize(notes);
  const RowBatchBuffers out = row_batch_buffers(s.batch, s.coverage, strip_rows, stride);
  // A small fill's pixels may be fetched while its cells are accumulated; most of a thin shape's box is not drawn.
  if (strip_rows == y_to - y_from) sink.expect(y_from, y_to, x_base, x_base + columns);
  with_rule(rule, [&](auto r) {
    for (int y = y_from; y < y_to; y += strip_rows) {
      sweep_dense_rows<decltype(r)::value>(mode, edges, y, std::min(y + strip_rows, y_to), x_base, columns, width,
                                           s.block.data(), fixed ? s.fixed_block.data() : nullptr,
                                           wide ? s.wide_block.data() : nullptr, s.notes.data(), out, sink);
    }
  });
}

bool detail::RasterizerImpl::sweep_dense(FillRule rule, int width, int x_base, int columns, bool fixed_cells,
                                         CoverageSink& sink) {
  const DenseKind kind = dense_kind(edges_, y_min_, y_max_, columns, dense_limit_);
  if (kind == DenseKind::None) return false;
  const DenseCells cell_type = dense_cell_type(fixed_cells, kind, columns, edges_, dense_notes_);
  if (kind == DenseKind::Ranged) {
    sweep_ranged(rule, width, x_base, columns, cell_type, sink);
  } else {
    sweep_dense_range(rule, kind, edges_, y_min_, y_max_, x_base, columns, width, cell_type,
                      {dense_block_, dense_fixed_block_, dense_wide_block_, dense_notes_, dense_batch_, row_coverage_},
                      sink);
  }
  return true;
}

// A large fill with its rows' pieces noted: in bands with threads, as the row sweep (rows are swept one by one from
// the cells of their own pieces, so bands give the bits of one sweep). Out of line: small fills come by sweep_dense
// by the thousand.
void detail::RasterizerImpl::sweep_ranged(FillRule rule, int width, int x_base, int columns, DenseCells cell_type,
                                          CoverageSink& sink) {
  in_bands(band_count(sink), [&](int y0, int y1, BandScratch& s) {
    sweep_dense_range(rule, DenseKind::Ranged, edges_, y0, y1, x_base, columns, width, cell_type,
                      {s.dense_block, s.dense_fixed_block, s.dense_wide_block, s.dense_notes, s.batch, s.coverage},
                      sink);
  });
}

// Rows [y_from, y_to) of a queued dense fill.
void detail::RasterizerImpl::sweep_dense_band(const QueuedFill& fill, int y_from, int y_to, BandScratch& s) {
  const DenseKind kind = fill.kind == QueuedFill::Kind::Ranged ? DenseKind::Ranged : DenseKind::Dense;
  sweep_dense_range(fill.rule, kind, fill.edges, y_from, y_to, fill.x_base, fill.columns, fill.width, fill.dense_cells,
                    {s.dense_block, s.dense_fixed_block, s.dense_wide_block, s.dense_notes, s.batch, s.coverage},
                    *fill.sink);
}

// The columns the edges reach: cells [x_base, x_base + columns) hold every cell an edge can write (the last edge's
// cell and the one after it), so a running sum over them returns to 0 wherever the path closes inside the image.
void detail::edge_columns(const std::vector<Edge>& edges, int& x_base, int& columns) {
  double x_lo = edges[0].x0, x_hi = x_lo;
  for (const Edge& e : edges) {
    x_lo = std::min({x_lo, e.x0, e.x1});
    x_hi = std::max({x_hi, e.x0, e.x1});
  }
  x_base = static_cast<int>(x_lo);  // x >= 0 after clipping: truncation is floor
  columns = static_cast<int>(x_hi) - x_base + 2;
}

// Bands pay where a fill's work outweighs handing them out: a band costs a few cache-line transfers between cores
// (claiming it, counting it done) and a pass over the edges above it, about half a microsecond. The work of a fill
// is estimated from its edges: each edge writes cells along its height and across its width (the sweep's cost),
// and the area inside is composited (spans, far cheaper per pixel). Units: about 10 ns each on the machine of
// docs/performance.md ("Threads"), so a band of kWorkPerBand units is some 3 us.
constexpr int kMinBandRows = 8;
constexpr double kWorkPerBand = 300;    // small bands balance well: whoever finishes first takes the next
constexpr double kMinBandedWork = 800;   // below this, the fork and join cost more than the second thread saves
constexpr double kAreaPerUnit = 16;  // composited pixels per unit of work
constexpr int kBandsPerThread = 8;   // several bands per thread: a thread that finishes early takes another

double detail::outline_cells(const std::vector<Edge>& edges) {
  double outline = 0;
  for (const Edge& e : edges) outline += (e.y1 - e.y0) + std::abs(e.x1 - e.x0);
  return outline;
}

double detail::work_of(double outline, double signed_area) {
  return outline + std::abs(signed_area) / kAreaPerUnit;
}

double detail::band_work(const std::vector<Edge>& edges) {
  double signed_area = 0;
  for (const Edge& e : edges) signed_area += 0.5 * (e.x0 + e.x1) * (e.y1 - e.y0) * e.winding;
  return work_of(outline_cells(edges), signed_area);
}

int detail::RasterizerImpl::band_count(const CoverageSink& sink) const {
  const int rows = y_max_ - y_min_;
  if (!pool_ || rows < 2 * kMinBandRows || !sink.takes_concurrent_rows()) return 1;
  const double work = band_work(edges_);
  if (work < kMinBandedWork) return 1;
  const int by_work = static_cast<int>(std::min(work / kWorkPerBand, double{BandPool::kMaxBands}));
  const int threads = pool_->threads();
  const int bands = std::min({by_work, rows / kMinBandRows, threads * kBandsPerThread});
  // A whole number of bands per thread, so that no thread is left with one band more than the others at the end.
  return bands > threads ? bands - bands % threads : bands;
}

template <class Sweep>
void detail::RasterizerImpl::in_bands(int bands, Sweep&& sweep) {
  last_fill_bands_ = std::max(bands, 1);
  if (bands <= 1) {
    sweep(y_min_, y_max_, bands_[0]);
    return;
  }
  const int rows = y_max_ - y_min_;
  auto job = [&](int band, int worker) {
    const int y0 = y_min_ + static_cast<int>(std::int64_t{rows} * band / bands);
    const int y1 = y_min_ + static_cast<int>(std::int64_t{rows} * (band + 1) / bands);
    sweep(y0, y1, bands_[static_cast<std::size_t>(worker)]);
  };
  pool_->run(bands, job);
}

void detail::RasterizerImpl::start_active(const EdgeTableView& table, int y_from, double retire_at,
                                          std::vector<std::uint32_t>& active) {
  active.clear();
  const std::uint32_t before = table.bucket_start[static_cast<std::size_t>(y_from - table.y_min)];
  for (std::uint32_t k = 0; k < before; ++k) {
    if (table.edges[table.order[k]].y1 > retire_at) active.push_back(table.order[k]);
  }
}

void detail::RasterizerImpl::set_threads(int threads) {
  threads = std::clamp(threads, 1, 64);
  if (threads == this->threads()) return;
  flush();
  pool_.reset();
  if (threads > 1) pool_ = std::make_unique<BandPool>(threads);
  bands_.resize(static_cast<std::size_t>(threads));
}

void detail::RasterizerImpl::sweep_analytic(FillRule rule, int width, bool fixed_cells, CoverageSink& sink) {
  int x_base = 0, columns = 0;
  edge_columns(edges_, x_base, columns);
  if (sweep_dense(rule, width, x_base, columns, fixed_cells, sink)) return;
  bucket_edges(false);
  EdgeTableView edge_table = table();
  edge_table.x_end = x_base + columns;
  in_bands(band_count(sink), [&](int y0, int y1, BandScratch& s) {
    sweep_analytic_band(edge_table, rule, width, y0, y1, fixed_cells, s, sink);
  });
}

void detail::RasterizerImpl::sweep_analytic_band(const EdgeTableView& table, FillRule rule, int width, int y_from,
                                                 int y_to, bool fixed_cells, BandScratch& s, CoverageSink& sink) {
  const std::size_t cells = static_cast<std::size_t>(width) + 2;  // a piece writes up to cell width + 1
  const std::size_t padded = cells + detail::kRowPadding;  // a narrow cluster's last block reads past, pieces write
  static_assert(detail::kRowPadding >= detail::kPieceSlack - 1);
  if (s.accumulation.size() < padded) s.accumulation.assign(padded, 0.0);
  // The fixed-point sweeps read and write blocks of eight from a run's first cell.
  const std::size_t padded_fixed = cells + detail::kFixedBlock;
  if (fixed_cells && s.fixed_cells.size() < padded_fixed) s.fixed_cells.assign(padded_fixed, 0);
  // The wide sweep reads and writes blocks of four from a run's first cell.
  const std::size_t padded_wide = cells + 4;
  if (fixed_cells && s.wide_cells.size() < padded_wide) s.wide_cells.assign(padded_wide, 0);
  if (s.coverage.size() < padded_fixed) s.coverage.resize(padded_fixed);
  // An edge whose bottom is at or above the band's top was retired before it (e.y1 > bottom keeps an edge).
  start_active(table, y_from, y_from, s.active);
  const RowBuffers buffers{s.active, s.columns, s.accumulation.data(),
                           fixed_cells ? s.fixed_cells.data() : nullptr,
                           fixed_cells ? s.wide_cells.data() : nullptr, s.coverage.data(),
                           row_batch_buffers(s.batch, s.batch_coverage, kBatchRows, detail::kNarrowRowCoverage)};
  with_rule(rule, [&](auto r) {
    constexpr FillRule R = decltype(r)::value;
#ifdef VRASTER_HAVE_AVX2_KERNELS
    if (detail::cpu_has_avx2()) return sweep_analytic_rows_avx2<R>(table, buffers, y_from, y_to, width, sink);
#endif
    sweep_analytic_rows_portable<R>(table, buffers, y_from, y_to, width, sink);
  });
}

// Point-sampled modes: every row's sample counts are integers from the edges alone, so bands (each re-bucketing
// the edges for its rows) give the same coverage as one sweep.
void detail::RasterizerImpl::sweep_sampled(FillRule rule, AntiAlias aa, int width, CoverageSink& sink) {
  const detail::SamplePattern pattern = detail::sample_pattern(aa);
  in_bands(band_count(sink), [&](int y0, int y1, BandScratch&) {
    detail::sweep_sampled(edges_, y0, y1, rule, pattern, width, sink);  // supersample.cpp
  });
}

// Aliased: one sample per pixel at its centre (x + 0.5, y + 0.5). An edge takes part in the sample rows with
// y0 <= y + 0.5 < y1 (so a vertex on a sample line counts once and horizontal edges never do); a pixel is inside
// when its centre lies in [left crossing, right crossing) (top-left rule: of two shapes sharing an edge exactly
// one owns each pixel centre on it).
void detail::RasterizerImpl::sweep_aliased(FillRule rule, int width, CoverageSink& sink) {
  bucket_edges(true);
  in_bands(band_count(sink), [&](int y0, int y1, BandScratch& s) {
    // Edges that end at or above the band's first sample line would be retired there anyway. A band's active list
    // starts in a different order than a whole sweep's (which keeps it sorted by x); crossings are sorted per row,
    // and edges crossing at the same x start and end spans at the same pixel, so the pixels are the same.
    sweep_aliased_rows(table(), rule, width, y0, y1, s, sink);
  });
}

void detail::RasterizerImpl::sweep_aliased_rows(const EdgeTableView& table, FillRule rule, int width, int y_from,
                                                int y_to, BandScratch& s, CoverageSink& sink) {
  const std::vector<Edge>& edges = table.edges;
  start_active(table, y_from, y_from + 0.5, s.active);
  std::vector<std::uint32_t>& active = s.active;
  std::vector<Crossing>& crossings = s.crossings;
  for (int y = y_from; y < y_to; ++y) {
    const int r = y - table.y_min;
    for (std::uint32_t k = table.bucket_start[r]; k < table.bucket_start[r + 1]; ++k) active.push_back(table.order[k]);
    const double sample = y + 0.5;
    // Retire edges that end at or above this sample line, and find where the others cross it.
    crossings.clear();
    std::size_t kept = 0;
    for (std::size_t k = 0; k < active.size(); ++k) {
      const Edge& e = edges[active[k]];
      if (e.y1 <= sample) continue;
      active[kept++] = active[k];
      if (e.y0 <= sample) crossings.push_back({e.x_at(sample), active[k]});
    }
    active.resize(kept);
    if (crossings.empty()) continue;
    // The crossings of the previous row are nearly sorted: insertion sort is linear in practice.
    for (std::size_t i = 1; i < crossings.size(); ++i) {
      const Crossing c = crossings[i];
      std::size_t j = i;
      while (j > 0 && crossings[j - 1].x > c.x) {
        crossings[j] = crossings[j - 1];
        --j;
      }
      crossings[j] = c;
    }
    // Keep the active list in crossing order so next row's sort has little to do.
    for (std::size_t i = 0; i < crossings.size(); ++i) active[i] = crossings[i].edge;
    active.resize(crossings.size());
    int w = 0;
    int span_start = 0;
    bool in = false;
    for (const Crossing& c : crossings) {
      w += edges[c.edge].winding;
      const bool now = winding_fills(rule, w);
      if (now == in) continue;
      const int px = static_cast<int>(std::ceil(c.x - 0.5));
      if (now) {
        span_start = px;
      } else {
        const int x0 = std::max(span_start, 0), x1 = std::min(px, width);
        if (x1 > x0) sink.span(y, x0, x1, 1.0f);
      }
      in = now;
    }
    // Still inside after the last crossing: the closing edges lie right of the image and were dropped.
    if (in && span_start < width) sink.span(y, std::max(span_start, 0), width, 1.0f);
  }
}

Rasterizer::Rasterizer() : impl_(std::make_unique<detail::RasterizerImpl>()) {}
Rasterizer::~Rasterizer() = default;
Rasterizer::Rasterizer(Rasterizer&&) noexcept = default;
Rasterizer& Rasterizer::operator=(Rasterizer&&) noexcept = default;

void Rasterizer::fill(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                      CoverageSink& sink) {
  impl_->fill(lines, rule, aa, width, height, sink);
}
void Rasterizer::fill_mask(const Polylines& lines, FillRule rule, int width, int height, std::uint8_t* mask,
                           std::ptrdiff_t stride) {
  impl_->fill_mask(lines, rule, width, height, mask, stride);
}
const std::vector<Edge>& Rasterizer::edges() const { return impl_->edges_; }
void Rasterizer::set_dense_limit(std::int64_t cells) { impl_->dense_limit_ = cells; }
void Rasterizer::set_exact_shortcut(bool on) { impl_->exact_shortcut_ = on; }
void Rasterizer::set_rect_shortcut(bool on) { impl_->rect_shortcut_ = on; }
void Rasterizer::set_fixed_cells(bool on) { impl_->fixed_cells_ = on; }
void Rasterizer::set_threads(int threads) { impl_->set_threads(threads); }
int Rasterizer::threads() const { return impl_->threads(); }
int Rasterizer::last_fill_bands() const { return impl_->last_fill_bands_; }
void Rasterizer::fill_queued(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                             std::unique_ptr<CoverageSink> sink) {
  if (!sink) return;
  CoverageSink& now = *sink;  // before the pointer moves (argument order is unspecified)
  impl_->fill_queued(lines, rule, aa, width, height, now, std::move(sink));
}
void Rasterizer::fill_queued(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                             CoverageSink& sink) {
  impl_->fill_queued(lines, rule, aa, width, height, sink, nullptr);
}
void Rasterizer::flush() { impl_->flush(); }
std::size_t Rasterizer::queued_fills() const { return impl_->queued_fills(); }
int Rasterizer::last_flush_bands() const { return impl_->last_flush_bands_; }
std::uint64_t Rasterizer::exact_fallbacks() const { return impl_->exact_fallbacks_; }

void detail::RasterizerImpl::fill(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                                  CoverageSink& sink) {
  flush();  // queued fills come first: painter's order
  last_fill_bands_ = 1;
  if (width <= 0 || height <= 0) return;
  if (fill_rect(lines, rule, aa, width, height, sink)) return;
  if (rule == FillRule::NonExterior) {
    // Over the work budget (counted on the visible edges): non-zero, the nearest rule that needs no arrangement.
    build_edges(lines, width, height);
    if (lines.points.size() > Rasterizer::kMaxNonExteriorPoints || !exact_within_budget(height)) {
      ++exact_fallbacks_;
      rule = FillRule::NonZero;
      if (aa == AntiAlias::Exact) aa = AntiAlias::Analytic;
    }
  }
  if (rule == FillRule::NonExterior) {
    // The boundary of the non-exterior region, then a non-zero fill of it in the requested mode.
    build_unclipped_edges(lines);
    pieces_.clear();
    boundary_.extract(edges_, horizontals_, rule, pieces_);
    clip_pieces(width, height);
    rule = FillRule::NonZero;
  } else {
    build_edges(lines, width, height);
    if (aa == AntiAlias::Exact && !(exact_shortcut_ && unit_winding_(edges_))) {
      // Only the boundary of the filled region, accumulated row by row as the sweep finds it: its pieces never
      // cross, so the accumulation is exact. (Where the winding is only ever 0 or one other value, analytic is
      // already exact: the shapes most scenes are made of take that path.) Over the crossing budget: analytic.
      if (exact_within_budget(height)) {
        if (!edges_.empty()) boundary_.fill(edges_, rule, width, sink);
        return;
      }
      ++exact_fallbacks_;
      aa = AntiAlias::Analytic;
    }
  }
  sweep_edges(rule, aa, width, sink);
}

void detail::RasterizerImpl::sweep_edges(FillRule rule, AntiAlias aa, int width, CoverageSink& sink) {
  if (edges_.empty()) return;
  if (detail::sample_pattern(aa).grid > 0) {
    sweep_sampled(rule, aa, width, sink);  // ssaa-N, msaa-N
  } else if (aa == AntiAlias::None) {
    sweep_aliased(rule, width, sink);
  } else {
    // Exact mode comes here for paths the analytic sweep is exact for: double cells only (1e-9, not 5.4e-7).
    sweep_analytic(rule, width, fixed_cells_ && aa == AntiAlias::Analytic, sink);
  }
}

}  // namespace vraster
