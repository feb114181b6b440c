// The fill queue (Rasterizer::fill_queued / flush): many fills, one fork and join.
//
//   1. fill_queued, on the caller's thread: flatten (the caller), then the polylines are copied into a QueuedFill
//      (a rectangle's few distinct rows are computed at once into a CoverageRecording instead). Small fills with
//      nothing queued before them are drawn at once, until enough of them in a row show a frame of many.
//   2. flush, first fork and join: the queued fills' edges and edge tables are built, fills shared out among the
//      caller and the workers (building them on the caller alone held the other threads idle for a tenth of a
//      frame of curves)
//   3. flush, second fork and join: rows [lowest fill top, highest fill bottom) cut into bands, each with the list of
//      fills crossing it; the caller and the workers claim bands
//   4. per band: every fill of its list, in queue order, over the band's rows only (the edge table is read-only and
//      shared)
//
// A row's pixels see the fills in the order they were queued (one thread owns the row for the whole queue), and
// each fill's rows come out of the same arithmetic as an unbanded sweep (docs/design.md, "Threads"), so the image
// is the same, bit for bit, as drawing the fills one by one on one thread.
#include <algorithm>
#include <climits>
#include <cmath>

#include "raster/rasterizer_p.hpp"
#include "raster/supersample.hpp"

namespace vraster::detail {
namespace {

// Bands of the whole queue (flush): rounds of one band per thread, each round's bands half the estimated work of the
// previous round's, so the last bands are small and a thread that finishes early (the estimate is only an estimate,
// and the host may preempt a thread) waits for little: with equal shares a thread was idle for 13-26 % of the
// queue's time at the end. Every band costs each fill crossing it a start from cold edges and tables, so the bands
// are few: four rounds, eight bands on two threads (docs/performance.md, "Threads").
constexpr int kQueueRounds = 4;
constexpr int kQueueMinBandRows = 8;
// A fill of less work than this (band_work's units, about 10 ns each; the threshold of banding a fill alone) is
// drawn at once on the caller's thread when nothing is queued: queued, a small fill costs 5-15 % more on one
// thread (its edges are stored and read back cold, its sink copied), which a frame of small fills only would not
// win back. Once a large fill has started a queue, small ones join it (the order must hold).
constexpr double kMinQueuedFillWork = 800;
// Small fills start a queue too once fills drawn at once since the last flush add up to this much work: the frame
// is evidently made of many of them (1,000 polygons of 32 px, or 20,000 triangles of 2 px), and a queue shares
// them out among the threads, drawn in the background while the caller queues more (run_queue).
constexpr double kWorkDrawnBeforeQueue = 3200;
// Recorded fills: composited pixels per unit of work, as band_work counts the area inside.
constexpr double kRecordedPixelsPerUnit = 16;
// Memory the queue may hold (outlines, edge tables and recordings) before fill_queued runs it. What a fill queues
// is written when the queue is built and read back when its bands run: past the cache, that is a trip to memory
// each way. At 16 MiB, cubic_256 (11 MiB of outlines and edges a frame) took 11-18 % longer queued than drawn fill
// by fill on one thread; 2 MiB was best on the Zen 3 host (twenty-third session). Since queues are drawn in the
// background (so a small budget no longer means waiting for the threads to wake), 1 MiB, about one core's L2 on the
// Zen 5 host: in alternating runs cubic_256's two threads took 1.05-1.3x one thread's CPU time against 1.2-1.35x
// at 2 MiB, and two-thread text_outlines 1.02-1.21x one thread against 0.71-0.86x (docs/performance.md, thirtieth
// session).
constexpr std::size_t kQueueBudgetBytes = std::size_t{1} << 20;
// Building the queue's fills: chunks of consecutive fills per thread, several so that the threads finish together.
constexpr int kBuildChunksPerThread = 8;

// band_work's estimate (sweep.cpp) from an outline before it is built: the same sums over the segments as they come,
// unclipped. It only decides whether a fill waits in the queue, and whether the queue is worth threads.
double outline_work(const Polylines& lines) {
  WorkSums sums;
  lines.for_each_segment([&](Point p, Point q) { sums.add(p, q); });
  const double work = sums.work();
  return std::isfinite(work) ? work : 0.0;  // points no edge can come from (NaN) must not poison the queue's sums
}

}  // namespace

void CoverageRecording::span(int y, int x0, int x1, float coverage) {
  calls_.push_back({y, y + 1, x0, x1, coverage, kSpan});
  pixels_ += static_cast<std::size_t>(x1 - x0);
  ++replayed_calls_;
}

void CoverageRecording::row(int y, int x0, int x1, const float* coverage) {
  calls_.push_back({y, y + 1, x0, x1, 0.0f, static_cast<std::uint32_t>(values_.size())});
  values_.insert(values_.end(), coverage, coverage + (x1 - x0));
  pixels_ += static_cast<std::size_t>(x1 - x0);
  ++replayed_calls_;
}

void CoverageRecording::repeat_row(int y, int y_end) {
  for (auto call = calls_.rbegin(); call != calls_.rend() && call->y == y; ++call) {
    const auto more = static_cast<std::size_t>(y_end - call->y_end);
    call->y_end = y_end;
    pixels_ += more * static_cast<std::size_t>(call->x1 - call->x0);
    replayed_calls_ += more;
  }
}

void CoverageRecording::replay(int y_from, int y_to, CoverageSink& sink) const {
  // The calls are in row order and their row ranges follow each other, so the first call that reaches y_from is
  // found by its range's end.
  auto call = std::upper_bound(calls_.begin(), calls_.end(), y_from, [](int y, const Call& c) { return y < c.y_end; });
  while (call != calls_.end() && call->y < y_to) {
    auto row_end = call;  // the calls of one row (or of one run of rows alike)
    while (row_end != calls_.end() && row_end->y == call->y) ++row_end;
    const int to = std::min(call->y_end, y_to);
    for (int y = std::max(call->y, y_from); y < to; ++y) {
      for (auto c = call; c != row_end; ++c) {
        if (c->first == kSpan) {
          sink.span(y, c->x0, c->x1, c->coverage);
        } else {
          sink.row(y, c->x0, c->x1, values_.data() + c->first);
        }
      }
    }
    call = row_end;
  }
}

void CoverageRecording::clear() {
  calls_.clear();
  values_.clear();
  pixels_ = 0;
  replayed_calls_ = 0;
}

std::size_t CoverageRecording::bytes() const { return calls_.size() * sizeof(Call) + values_.size() * sizeof(float); }

bool QueuedFill::keep_sink(const CoverageSink& s, std::unique_ptr<CoverageSink> owned) {
  drop_sink();
  if (owned) {
    owned_sink_ = std::move(owned);
    sink = owned_sink_.get();
    return true;
  }
  sink = s.clone_into(sink_storage_, kSinkStorageBytes);
  sink_in_storage_ = sink != nullptr;
  if (!sink) {
    owned_sink_ = s.clone();
    sink = owned_sink_.get();
  }
  return sink != nullptr;
}

void QueuedFill::drop_sink() {
  if (sink_in_storage_) sink->~CoverageSink();
  sink_in_storage_ = false;
  owned_sink_.reset();
  sink = nullptr;
}

std::size_t QueuedFill::bytes() const {
  // An unbuilt fill counts the edges it will have (about one per point) with its outline, and every fill its entry
  // (some 400 bytes, most of a tiny fill's share of the budget).
  const std::size_t edge_bytes =
      kind == Kind::Unbuilt && !prebuilt ? lines.points.size() * sizeof(Edge) : edges.size() * sizeof(Edge);
  return sizeof(QueuedFill) + lines.points.size() * sizeof(Point) + lines.ends.size() * sizeof(std::uint32_t) +
         lines.closed.size() + edge_bytes + (order.size() + bucket_start.size()) * sizeof(std::uint32_t) +
         recording.bytes();
}

void RasterizerImpl::fill_queued(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                                 CoverageSink& sink, std::unique_ptr<CoverageSink> owned) {
  // What the queue does not hold is drawn now (after what is queued, so the order stays): without threads, for a
  // sink that wants its calls in order, and for the two modes that resolve the whole arrangement before a row.
  if (!pool_ || !sink.takes_concurrent_rows() || rule == FillRule::NonExterior || aa == AntiAlias::Exact) {
    fill(lines, rule, aa, width, height, sink);
    return;
  }
  if (width <= 0 || height <= 0) return;
  std::deque<QueuedFill>& queue = queues_[filling_];
  if (queued_ == queue.size()) queue.emplace_back();
  QueuedFill& q = queue[queued_];
  q.rule = rule;
  q.aa = aa;
  q.width = width;
  q.recording.clear();
  // The choices of fill(), made now. A small fill with nothing queued before it (nor drawing in the background) is
  // drawn at once, unless it starts a queue for a frame of many small fills.
  // Whether a fill of this much work is drawn at once; if so, it counts towards the frame's drawn_at_once_.
  auto at_once = [&](double work) {
    if (queued_ > 0 || running_ || work >= kMinQueuedFillWork) return false;
    if (drawn_at_once_ >= kWorkDrawnBeforeQueue && !workers_starved_) return false;
    drawn_at_once_ += work;
    return true;
  };
  bool recorded = fill_rect(lines, rule, aa, width, height, q.recording, &q.recording);
  if (recorded && at_once(static_cast<double>(q.recording.pixels()) / kRecordedPixelsPerUnit)) {
    q.recording.replay(q.recording.y_min(), q.recording.y_max(), sink);
    return;
  }
  bool prebuilt = false;
  if (!recorded && queued_ == 0) {
    // Nothing queued: the edges are built now, with the estimate taken on the way (no pass over the outline of
    // its own, which cost a small fill 5 % more than drawing it without threads). A small fill is drawn at once
    // (at_once); a fill that starts the queue keeps these edges.
    detail::build_edges(lines, width, height, edges_, y_min_, y_max_, &q.work);
    if (at_once(q.work)) {
      if (!edges_.empty()) sweep_edges(rule, aa, width, sink);
      return;
    }
    prebuilt = true;
  } else if (!recorded) {
    q.work = outline_work(lines);
  }
  if (recorded && q.recording.empty()) return;  // nothing visible
  // The sink to keep: the one handed over, or a copy (made only now that the fill really waits).
  if (!q.keep_sink(sink, std::move(owned))) {  // a sink that cannot be kept: drawn now, after the queue
    flush();
    if (recorded) {
      q.recording.replay(q.recording.y_min(), q.recording.y_max(), sink);
    } else {
      if (!prebuilt) build_edges(lines, width, height);
      if (!edges_.empty()) sweep_edges(rule, aa, width, sink);
    }
    return;
  }
  q.edges.clear();
  q.order.clear();
  q.bucket_start.clear();
  q.prebuilt = prebuilt;
  if (recorded) {
    q.kind = QueuedFill::Kind::Recorded;
    q.y_min = q.recording.y_min();
    q.y_max = q.recording.y_max();
    q.work = static_cast<double>(q.recording.calls()) +
             static_cast<double>(q.recording.pixels()) / kRecordedPixelsPerUnit;
    q.lines.clear();
  } else {
    q.kind = QueuedFill::Kind::Unbuilt;  // built by flush(), on the pool's threads
    q.height = height;
    if (prebuilt) {
      q.edges.swap(edges_);  // the rasterizer's buffer takes the entry's old one in exchange
      q.y_min = y_min_;
      q.y_max = y_max_;
      q.lines.clear();
    } else {
      q.y_min = q.y_max = 0;
      q.lines = lines;  // a copy into the entry's own vectors (they keep their capacity from flush to flush)
    }
  }
  ++queued_;
  queued_bytes_ += q.bytes();
  queued_work_ += q.work;
  // Not the frame's end (drawn_at_once_ goes on): drawn in the background while the next fills are queued.
  if (queued_bytes_ > kQueueBudgetBytes) run_queue(true);
}

void RasterizerImpl::build_queued(QueuedFill& q, BandScratch& s) const {
  // The choices fill() makes for a fill drawn at once, on the same edges, so the two draw the same bits.
  if (!q.prebuilt) detail::build_edges(q.lines, q.width, q.height, q.edges, q.y_min, q.y_max);
  if (q.edges.empty() || q.y_max <= q.y_min) {
    q.kind = QueuedFill::Kind::Empty;
  } else if (sample_pattern(q.aa).grid > 0) {
    q.kind = QueuedFill::Kind::Sampled;
  } else if (q.aa == AntiAlias::None) {
    detail::bucket_edges(q.edges, q.y_min, q.y_max, true, q.order, q.bucket_start, s.bucket);
    q.kind = QueuedFill::Kind::Aliased;
  } else {
    edge_columns(q.edges, q.x_base, q.columns);
    const DenseKind dense = dense_kind(q.edges, q.y_min, q.y_max, q.columns, dense_limit_);
    if (dense != DenseKind::None) {
      q.kind = dense == DenseKind::Ranged ? QueuedFill::Kind::Ranged : QueuedFill::Kind::Dense;
      q.dense_cells = dense_cell_type(fixed_cells_, dense, q.columns, q.edges, s.dense_notes);
    } else {
      detail::bucket_edges(q.edges, q.y_min, q.y_max, false, q.order, q.bucket_start, s.bucket);
      q.kind = QueuedFill::Kind::Analytic;
      q.fixed_cells = fixed_cells_;  // (kept: the rasterizer's setting may change while the fill draws)
    }
  }
}

void RasterizerImpl::run_queued_band(const std::deque<QueuedFill>& queue, int band, BandScratch& s) {
  const auto b = static_cast<std::size_t>(band);
  const int y_from = band_top_[b], y_to = band_top_[b + 1];
  for (std::uint32_t k = band_first_[b]; k < band_first_[b + 1]; ++k) {
    const QueuedFill& q = queue[band_entries_[k]];
    if (k + 1 < band_first_[b + 1]) {
      // The next fill's entry, edges and tables are cold (other fills ran since they were built): ask for them now,
      // while this fill runs.
      const QueuedFill& next = queue[band_entries_[k + 1]];
      __builtin_prefetch(&next);
      __builtin_prefetch(next.edges.data());
      __builtin_prefetch(next.bucket_start.data());
      __builtin_prefetch(next.order.data());
      __builtin_prefetch(next.sink);
    }
    const int y0 = std::max(y_from, q.y_min), y1 = std::min(y_to, q.y_max);
    switch (q.kind) {
      case QueuedFill::Kind::Analytic:
        sweep_analytic_band(q.table(), q.rule, q.width, y0, y1, q.fixed_cells, s, *q.sink);
        break;
      case QueuedFill::Kind::Aliased:
        sweep_aliased_rows(q.table(), q.rule, q.width, y0, y1, s, *q.sink);
        break;
      case QueuedFill::Kind::Sampled:
        detail::sweep_sampled(q.edges, y0, y1, q.rule, sample_pattern(q.aa), q.width, *q.sink);  // supersample.cpp
        break;
      case QueuedFill::Kind::Dense:
      case QueuedFill::Kind::Ranged:
        sweep_dense_band(q, y0, y1, s);
        break;
      case QueuedFill::Kind::Recorded:
        q.recording.replay(y0, y1, *q.sink);
        break;
      case QueuedFill::Kind::Unbuilt:  // built before any band runs
      case QueuedFill::Kind::Empty:    // in no band's list
        break;
    }
  }
}

void RasterizerImpl::flush() {
  run_queue();
  drawn_at_once_ = 0;  // a flush ends a frame, or a stretch of drawing the queue cannot hold
  workers_starved_ = false;  // (each frame tries the workers again)
}

void RasterizerImpl::finish_running() {
  if (!running_) return;
  // No worker got to a queue drawn in the background before the caller came back for it: the other cores are busy
  // (or this process has no other). Until the frame ends, queues then run in the open and small fills are drawn at
  // once, as without threads: queued, they would cost without paying.
  if (pool_->finish() == running_bands_) workers_starved_ = true;
  drop_sinks(queues_[filling_ ^ 1], running_count_);
  running_ = false;
  running_count_ = 0;
}

void RasterizerImpl::run_queue(bool in_background) {
  finish_running();  // the fills queued before these come first in every row
  if (queued_ == 0) return;
  std::deque<QueuedFill>& queue = queues_[filling_];
  // First the edges of the fills that wait unbuilt: chunks of consecutive fills on the pool's threads.
  auto build = [&](std::size_t from, std::size_t to, BandScratch& s) {
    for (std::size_t i = from; i < to; ++i) {
      if (queue[i].kind == QueuedFill::Kind::Unbuilt) build_queued(queue[i], s);
    }
  };
  const std::size_t chunks = pool_ && queued_work_ >= kMinQueuedFillWork
                                 ? std::min(queued_, static_cast<std::size_t>(pool_->threads() * kBuildChunksPerThread))
                                 : 1;
  if (chunks <= 1) {
    build(0, queued_, bands_[0]);
  } else {
    auto job = [&](int chunk, int worker) {
      const auto c = static_cast<std::size_t>(chunk);
      build(queued_ * c / chunks, queued_ * (c + 1) / chunks, bands_[static_cast<std::size_t>(worker)]);
    };
    pool_->run(static_cast<int>(chunks), job);
  }
  // The entries' rows and work, gathered once: the passes below then read a compact array, not an entry (several
  // cache lines, cold in a queue of thousands of small fills) per pass.
  fill_rows_.clear();
  int top = INT_MAX, bottom = INT_MIN;
  for (std::size_t i = 0; i < queued_; ++i) {
    const QueuedFill& q = queue[i];
    if (q.y_max <= q.y_min) continue;  // Empty fills (and none else) have no rows
    fill_rows_.push_back({static_cast<std::uint32_t>(i), q.y_min, q.y_max, q.work});
    top = std::min(top, q.y_min);
    bottom = std::max(bottom, q.y_max);
  }
  if (top >= bottom) {  // nothing inside the image
    last_flush_bands_ = 1;
    empty_queue();
    return;
  }
  const int rows = bottom - top;
  // Rounds of bands (kQueueRounds; fewer where the rows are too few), cut at shares of the queue's work, each fill's
  // estimate spread evenly over its rows: where fills crowd, bands are thinner.
  band_top_.assign(1, top);
  const int threads = pool_ ? pool_->threads() : 1;
  const int rounds = std::min({kQueueRounds, rows / (kQueueMinBandRows * threads), BandPool::kMaxBands / threads});
  if (threads > 1 && queued_work_ >= kMinQueuedFillWork && rounds >= 1) {  // (a fill of this much is banded alone)
    row_work_.assign(static_cast<std::size_t>(rows) + 1, 0.0);
    for (const FillRows& f : fill_rows_) {
      const double per_row = f.work / (f.y_max - f.y_min);
      row_work_[static_cast<std::size_t>(f.y_min - top)] += per_row;
      row_work_[static_cast<std::size_t>(f.y_max - top)] -= per_row;
    }
    double density = 0, total = 0;
    for (int r = 0; r < rows; ++r) {  // row_work_[r]: the work of rows [top, top + r] once summed
      density += row_work_[static_cast<std::size_t>(r)];
      total += std::max(density, 0.0);
      row_work_[static_cast<std::size_t>(r)] = total;
    }
    // Band b ends where the work above reaches band_cuts_[b]: the bands of round k hold 2^-k of a first-round band's.
    band_cuts_.clear();
    const double first_round = total / (threads * (2.0 - std::ldexp(1.0, 1 - rounds)));  // sum of 2^-k, k < rounds
    double at = 0;
    for (int k = 0; k < rounds; ++k) {
      for (int t = 0; t < threads; ++t) band_cuts_.push_back(at += std::ldexp(first_round, -k));
    }
    band_cuts_.back() = total;  // (round-off)
    std::size_t b = 0;
    for (int r = 0; r + 1 < rows && b + 1 < band_cuts_.size(); ++r) {
      if (row_work_[static_cast<std::size_t>(r)] >= band_cuts_[b]) {
        band_top_.push_back(top + r + 1);
        while (b + 1 < band_cuts_.size() && row_work_[static_cast<std::size_t>(r)] >= band_cuts_[b]) ++b;
      }
    }
  }
  band_top_.push_back(bottom);
  const int bands = static_cast<int>(band_top_.size()) - 1;
  last_flush_bands_ = bands;
  // Each band's list of the fills crossing it, in queue order (a band never looks at the others). A fill's bands
  // [first, last) are found once, by a table of each row's band.
  row_band_.resize(static_cast<std::size_t>(rows));
  for (int k = 0; k < bands; ++k) {
    std::fill(row_band_.begin() + (band_top_[static_cast<std::size_t>(k)] - top),
              row_band_.begin() + (band_top_[static_cast<std::size_t>(k) + 1] - top), static_cast<std::uint16_t>(k));
  }
  band_first_.assign(static_cast<std::size_t>(bands) + 1, 0);
  for (FillRows& f : fill_rows_) {
    f.first_band = row_band_[static_cast<std::size_t>(f.y_min - top)];
    f.last_band = row_band_[static_cast<std::size_t>(f.y_max - 1 - top)] + 1;
    for (int k = f.first_band; k < f.last_band; ++k) ++band_first_[static_cast<std::size_t>(k) + 1];
  }
  for (std::size_t k = 1; k < band_first_.size(); ++k) band_first_[k] += band_first_[k - 1];
  band_entries_.resize(band_first_.back());
  cursor_.assign(band_first_.begin(), band_first_.end() - 1);
  for (const FillRows& f : fill_rows_) {
    for (int k = f.first_band; k < f.last_band; ++k) band_entries_[cursor_[static_cast<std::size_t>(k)]++] = f.entry;
  }
  band_job_ = {this, &queue};
  if (in_background && !workers_starved_) {
    // The workers draw this queue; the caller fills the other one meanwhile (a frame of small fills is mostly the
    // caller's flattening and queueing: drawn in the background, their bands no longer wait for it).
    pool_->start(bands, band_job_);
    running_ = true;
    running_bands_ = bands;
    running_count_ = queued_;
    filling_ ^= 1;
    queued_ = 0;
    queued_bytes_ = 0;
    queued_work_ = 0;
    return;
  }
  if (bands == 1) {
    run_queued_band(queue, 0, bands_[0]);
  } else {
    pool_->run(bands, band_job_);
  }
  empty_queue();
}

void RasterizerImpl::drop_sinks(std::deque<QueuedFill>& queue, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) queue[i].drop_sink();
}

void RasterizerImpl::empty_queue() {
  drop_sinks(queues_[filling_], queued_);
  queued_ = 0;
  queued_bytes_ = 0;
  queued_work_ = 0;
}

}  // namespace vraster::detail
