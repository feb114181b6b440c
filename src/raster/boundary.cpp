// Boundary extraction by a sweep over the edges' arrangement.
//
//   1. Edges enter the sweep at their top, sorted by x at the sweep line (ties: by slope below it).
//   2. Neighbours in that order are tested for a crossing before either ends; crossings are events, and at each
//      the two neighbours swap: only the face between them changes, so a crossing costs O(1) (plus a heap push).
//   3. Each edge knows the winding number (and, for NonExterior, the face) on its left; its weight is
//      filled(right) - filled(left), in {-1, 0, +1}. Whenever a weight changes, the piece of the edge since the last
//      change is written out with the old weight.
//   4. NonExterior is not a function of the winding number: faces get ids, faces that meet along a free stretch
//      of the sweep line (not blocked by an edge point or a horizontal edge) are united, and the faces joined to
//      the outside (id 0) are exterior. That is only known at the end, so the sweep runs twice with the same ids.
#include "raster/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "raster/cells.hpp"

namespace vraster::detail {
namespace {

constexpr std::uint32_t kRemoved = 0xFFFFFFFFu;

class UnionFind {
 public:
  void reset() { parent_.assign(1, 0); }
  std::int32_t make() {
    parent_.push_back(static_cast<std::int32_t>(parent_.size()));
    return parent_.back();
  }
  std::int32_t find(std::int32_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a > b) std::swap(a, b);
    parent_[b] = a;  // the smaller id wins, so the outside (0) stays its own root
  }
  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::int32_t> parent_;
};

}  // namespace

struct BoundarySweep::State {
  UnionFind faces;
  std::vector<std::uint8_t> exterior;  // NonExterior second pass: per face id, whether it is outside
};

// Where the boundary pieces go: a list of edges (NonExterior, whose boundary is clipped and filled afterwards),
// nowhere (NonExterior's first pass), or straight into pixel rows (fill()).
struct BoundarySweep::PieceList {
  static constexpr bool kRows = false;
  std::vector<Edge>* out;
  void piece(const Edge& s, double y0, double x0, double y1, double x1, int weight) {
    if (out) out->push_back(Edge{x0, y0, x1, y1, s.dxdy, weight});
  }
  void resolve(std::int64_t) {}
};

// The sweep hands over every piece of the current pixel row before it moves past the row (it cuts the boundary
// edges at row bottoms), so one row of cells is enough.
struct BoundarySweep::RowCells {
  static constexpr bool kRows = true;
  int width;
  double* acc;
  std::uint64_t* bits;
  float* cov;
  CoverageSink& sink;
  int x_lo, x_hi;
  bool crowded = false;  // a row where pieces touch nearly every cell: mark them all at once when resolving

  void piece(const Edge&, double y0, double xa, double y1, double xb, int weight) {
    accumulate_piece(acc, xa, xb, (y1 - y0) * weight);
    const int c0 = static_cast<int>(std::min(xa, xb)), c1 = static_cast<int>(std::max(xa, xb)) + 1;
    if (!crowded) mark_cells(bits, c0, c1);
    x_lo = std::min(x_lo, c0);
    x_hi = std::max(x_hi, c1);
  }
  // The pieces bound a region of winding 0 or 1, so the running sum is that region's area in each pixel.
  void resolve(std::int64_t row) {
    if (x_lo > x_hi) return;
    if (crowded) mark_cells(bits, x_lo, x_hi);
    resolve_row<FillRule::NonZero>(static_cast<int>(row), width, x_lo, x_hi, acc, bits, cov, sink);
    x_lo = width + 1;
    x_hi = 0;
  }
};

// Events are kept per pixel row: only the current row's events are in the heap, later ones wait unsorted in their
// row's bucket. The heap stays small (one row's crossings), so a crossing costs a short heap operation.
void BoundarySweep::push_event(const Event& e) {
  if (bucketed_) {
    const auto row = static_cast<std::int64_t>(std::floor(e.y)) - row_base_;
    if (row > current_row_) {
      buckets_[static_cast<std::size_t>(row)].push_back(e);
      lowest_pending_ = std::min(lowest_pending_, row);
      return;
    }
  }
  heap_.push_back(e);
  std::push_heap(heap_.begin(), heap_.end(), Later{});
}

// Makes the heap hold the earliest pending events if they lie in a row up to `max_y`'s (the next start: rows
// after it must not be loaded yet, or every event pushed before the sweep gets there would go to the heap);
// false when the heap stays empty.
bool BoundarySweep::refill(double max_y) {
  if (!heap_.empty()) return true;
  if (!bucketed_) return false;
  const std::int64_t last = std::isfinite(max_y)
                                ? std::min(static_cast<std::int64_t>(std::floor(max_y)) - row_base_,
                                           static_cast<std::int64_t>(buckets_.size()) - 1)
                                : static_cast<std::int64_t>(buckets_.size()) - 1;
  for (auto r = std::max(current_row_ + 1, lowest_pending_); r <= last; ++r) {
    auto& bucket = buckets_[static_cast<std::size_t>(r)];
    if (bucket.empty()) continue;
    current_row_ = r;
    lowest_pending_ = r + 1;
    heap_.swap(bucket);
    std::make_heap(heap_.begin(), heap_.end(), Later{});
    return true;
  }
  lowest_pending_ = std::max(lowest_pending_, last + 1);
  return false;
}

BoundarySweep::Event BoundarySweep::pop_event() {
  std::pop_heap(heap_.begin(), heap_.end(), Later{});
  const Event e = heap_.back();
  heap_.pop_back();
  return e;
}

// Tests the neighbours at positions p and p + 1 for a crossing below y, and schedules it (not in band mode,
// where bands find crossings themselves).
void BoundarySweep::check_pair(std::size_t p, double y) {
  if (band_mode_) return;
  const std::uint32_t a = order_[p], b = order_[p + 1];
  const Edge& ea = (*edges_)[a];
  const Edge& eb = (*edges_)[b];
  const double y_end = std::min(ea.y1, eb.y1);
  const double d0 = x_of(eb, y) - x_of(ea, y);
  if (d0 < 0) {
    // Out of order already (an edge that continued another at a vertex took a slot that round-off at that
    // height left stale): swap now, whatever happens further down.
    push_event({y, kCrossing, a, b});
    return;
  }
  if (!(y_end > y)) return;
  const double d1 = x_of(eb, y_end) - x_of(ea, y_end);
  if (!(d1 < 0)) return;  // still in order where the first of them ends: no crossing
  double yc = y;
  if (d0 > 0) yc = std::clamp(y + (y_end - y) * (d0 / (d0 - d1)), y, y_end);
  push_event({yc, kCrossing, a, b});
}

// Local minimum: edges a and b start at the same point with opposite windings. Inserts them next to each other
// where that point falls in the order. Returns false (nothing changed) when the general path is needed.
template <class UpdateWeight>
bool BoundarySweep::insert_turning_pair(std::uint32_t a, std::uint32_t b, double y, bool track_faces, State& state,
                                        UpdateWeight& update_weight) {
  const std::vector<Edge>& edges = *edges_;
  const Edge &ea = edges[a], &eb = edges[b];
  if (ea.x0 != eb.x0 || ea.winding + eb.winding != 0) return false;
  if (eb.dxdy < ea.dxdy) std::swap(a, b);  // the one heading left goes left
  const double x = edges[a].x0;
  // First position whose edge lies right of x at y (ties: an edge through the very point makes the general path
  // decide, since its slope order against the pair matters).
  std::size_t lo = 0, hi = order_.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (x_of(edges[order_[mid]], y) < x) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  if (lo < order_.size() && x_of(edges[order_[lo]], y) == x) return false;
  const std::size_t p = lo;
  const int wl = p == 0 ? 0 : state_[order_[p - 1]].left_winding + edges[order_[p - 1]].winding;
  const std::int32_t gap = p < order_.size() ? left_face_[order_[p]] : 0;
  order_.insert(order_.begin() + static_cast<std::ptrdiff_t>(p), {a, b});
  if (band_top_y_ == y && band_xa_.size() + 2 == order_.size()) {  // keep the next band's x at its top
    band_xa_.insert(band_xa_.begin() + static_cast<std::ptrdiff_t>(p), {x, x});
  }
  for (std::size_t q = p; q < order_.size(); ++q) pos_[order_[q]] = static_cast<std::int32_t>(q);
  state_[a].left_winding = wl;
  state_[b].left_winding = wl + edges[a].winding;
  left_face_[a] = gap;  // the gap the pair opens in keeps its face on both sides
  left_face_[b] = track_faces ? state.faces.make() : 0;
  for (std::uint32_t e : {a, b}) {
    state_[e].since = {edges[e].x0, y};
    state_[e].weight = 0;
    push_event({edges[e].y1, kEnd, e, 0});
  }
  update_weight(p, y);
  update_weight(p + 1, y);
  if (p > 0) check_pair(p - 1, y);
  if (p + 2 < order_.size()) check_pair(p + 1, y);
  return true;
}

// Local maximum: neighbours a and b of opposite winding end at the same point. Removes them; the faces on either
// side join. Returns false (nothing changed) when the general path is needed.
template <class Emit>
bool BoundarySweep::remove_turning_pair(std::uint32_t a, std::uint32_t b, double y, bool track_faces, State& state,
                                        Emit& emit) {
  const std::vector<Edge>& edges = *edges_;
  if (pos_[b] < pos_[a]) std::swap(a, b);
  if (pos_[a] < 0 || pos_[b] != pos_[a] + 1) return false;
  if (edges[a].x1 != edges[b].x1 || edges[a].winding + edges[b].winding != 0) return false;
  const auto p = static_cast<std::size_t>(pos_[a]);
  // A neighbour through the very point closes the face beside the pair there: the general path decides.
  const double x = edges[a].x1;
  if (p > 0 && !(x_of(edges[order_[p - 1]], y) < x)) return false;
  if (p + 2 < order_.size() && !(x_of(edges[order_[p + 2]], y) > x)) return false;
  emit(a, y);
  emit(b, y);
  if (track_faces) {
    const std::int32_t right = p + 2 < order_.size() ? left_face_[order_[p + 2]] : 0;
    state.faces.unite(left_face_[a], right);
  }
  order_.erase(order_.begin() + static_cast<std::ptrdiff_t>(p), order_.begin() + static_cast<std::ptrdiff_t>(p) + 2);
  if (band_top_y_ == y && band_xa_.size() == order_.size() + 2) {
    band_xa_.erase(band_xa_.begin() + static_cast<std::ptrdiff_t>(p), band_xa_.begin() + static_cast<std::ptrdiff_t>(p) + 2);
  }
  pos_[a] = pos_[b] = -1;
  for (std::size_t q = p; q < order_.size(); ++q) pos_[order_[q]] = static_cast<std::int32_t>(q);
  if (p > 0 && p < order_.size()) check_pair(p - 1, y);
  return true;
}

template <class Filled, class Out>
void BoundarySweep::run(const std::vector<Edge>& edges, const std::vector<Edge>& horizontals, bool track_faces,
                        State& state, Filled&& filled, Out& out) {
  edges_ = &edges;
  const std::size_t n = edges.size();
  starts_.resize(n);
  std::iota(starts_.begin(), starts_.end(), 0u);
  std::sort(starts_.begin(), starts_.end(), [&](std::uint32_t i, std::uint32_t j) {
    const Edge &a = edges[i], &b = edges[j];
    return a.y0 < b.y0 || (a.y0 == b.y0 && (a.x0 < b.x0 || (a.x0 == b.x0 && a.dxdy < b.dxdy)));
  });
  pos_.assign(n, -1);
  state_.assign(n, EdgeState{});
  left_face_.assign(n, 0);
  dirty_.assign(n, 0);
  order_.clear();
  heap_.clear();
  // Row buckets when the edges span a sane number of rows (always after clipping to an image).
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = -y_lo;
  for (const Edge& e : edges) {
    y_lo = std::min(y_lo, e.y0);
    y_hi = std::max(y_hi, e.y1);
  }
  // (and lie where row numbers fit 64 bits: unclipped NonExterior edges may reach 1e300)
  bucketed_ = n >= kMinBucketedEdges && y_hi - y_lo < (1 << 20) && y_lo > -0x1p52 && y_hi < 0x1p52;
  if (bucketed_) {
    row_base_ = static_cast<std::int64_t>(std::floor(y_lo));
    const auto rows = static_cast<std::size_t>(static_cast<std::int64_t>(std::floor(y_hi)) - row_base_ + 2);
    // A finished sweep leaves every bucket empty (each is swapped into the heap before use); clear just the rows
    // this one needs, in case.
    if (buckets_.size() < rows) buckets_.resize(rows);
    for (std::size_t r = 0; r < rows; ++r) buckets_[r].clear();
    current_row_ = -1;
    lowest_pending_ = 0;
  }
  state.faces.reset();

  auto emit_at = [&](std::uint32_t e, double y, double x) {  // x: the edge's x at y
    EdgeState& st = state_[e];
    if (st.weight != 0 && y > st.since.y) out.piece(edges[e], st.since.y, st.since.x, y, x, st.weight);
    st.since = {x, y};
  };
  auto emit = [&](std::uint32_t e, double y) { emit_at(e, y, x_of(edges[e], y)); };
  auto right_face = [&](std::size_t p) { return p + 1 < order_.size() ? left_face_[order_[p + 1]] : 0; };
  auto update_weight = [&](std::size_t p, double y) {
    const std::uint32_t e = order_[p];
    const int wl = state_[e].left_winding;
    const int wr = wl + edges[e].winding;
    const int w = static_cast<int>(filled(wr, right_face(p))) - static_cast<int>(filled(wl, left_face_[e]));
    if (w != state_[e].weight) {
      emit(e, y);
      state_[e].weight = static_cast<std::int8_t>(w);
    }
  };

  // Crossing-heavy rows go band by band instead of crossing by crossing (winding rules, row output only): between
  // two heights where no edge starts or ends, the crossings are the inversions between the order at the top and
  // the order at the bottom, found by an insertion sort. Each crossing then changes the winding left of its two
  // edges only; every edge walks its own crossings in y order. No event queue, no neighbour tests: O(1) per
  // crossing plus O(edges) per band. Rows go back to events when crossings get rare.
  constexpr bool kBands = Out::kRows;
  band_mode_ = false;
  band_top_y_ = -std::numeric_limits<double>::infinity();
  double band_from = 0;
  std::size_t row_crossings = 0, row_batches = 0;
  auto sweep_band = [&](double y0, double y1) -> std::size_t {
    const std::size_t m = order_.size();
    if (m < 2) return 0;
    band_xb_.resize(m);
    band_keys_.resize(m);
    band_w_.resize(m);
    // x at the top: the previous band's x at its bottom when nothing started or ended in between.
    if (band_top_y_ != y0 || band_xa_.size() != m) {
      band_xa_.resize(m);
      for (std::size_t i = 0; i < m; ++i) band_xa_[i] = x_of(edges[order_[i]], y0);
    }
    for (std::size_t i = 0; i < m; ++i) {
      const Edge& e = edges[order_[i]];
      band_xb_[i] = x_of(e, y1);
      band_keys_[i] = {band_xb_[i], static_cast<std::uint32_t>(i)};
      band_w_[i] = static_cast<std::int8_t>(e.winding);
    }
    band_events_.clear();
    const double h = y1 - y0;
    for (std::size_t i = 1; i < m; ++i) {
      const BandKey key = band_keys_[i];
      const std::uint32_t c = key.pos;
      std::size_t j = i;
      while (j > 0 && band_keys_[j - 1].x > key.x) {
        // d was left of c at y0 and is right of it at y1: they cross in between, where their gap closes.
        const std::uint32_t d = band_keys_[j - 1].pos;
        const double top = band_xa_[c] - band_xa_[d], bottom = key.x - band_xb_[d];
        const double t = top > 0 ? top / (top - bottom) : 0.0;  // in [0, 1): bottom < 0
        const double yc = std::min(y0 + h * t, y1);
        const double xc = band_xa_[c] + (key.x - band_xa_[c]) * t;  // the crossing point, on both edges
        band_events_.push_back({yc, xc, c, -band_w_[d]});
        band_events_.push_back({yc, xc, d, band_w_[c]});
        band_keys_[j] = band_keys_[j - 1];
        --j;
      }
      band_keys_[j] = key;
    }
    const std::size_t crossings = band_events_.size() / 2;
    band_top_y_ = y1;
    if (crossings == 0) {
      band_xa_.swap(band_xb_);
      return 0;
    }
    // Group the events by edge (counting sort), then each edge's few events by y.
    band_start_.assign(m + 1, 0);
    for (const BandEvent& ev : band_events_) ++band_start_[ev.pos + 1];
    for (std::size_t i = 0; i < m; ++i) band_start_[i + 1] += band_start_[i];
    band_sorted_.resize(band_events_.size());
    band_cursor_.assign(band_start_.begin(), band_start_.end() - 1);
    for (const BandEvent& ev : band_events_) band_sorted_[band_cursor_[ev.pos]++] = ev;
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t b = band_start_[i], end = band_start_[i + 1];
      if (b == end) continue;
      for (std::uint32_t k = b + 1; k < end; ++k) {  // insertion sort: an edge has one or two crossings per band
        const BandEvent ev = band_sorted_[k];
        std::uint32_t j = k;
        for (; j > b && band_sorted_[j - 1].y > ev.y; --j) band_sorted_[j] = band_sorted_[j - 1];
        band_sorted_[j] = ev;
      }
      const std::uint32_t e = order_[i];
      const int winding = band_w_[i];
      int wl = state_[e].left_winding;
      for (std::uint32_t k = b; k < end; ++k) {
        wl += band_sorted_[k].delta;
        const int w = static_cast<int>(filled(wl + winding, 0)) - static_cast<int>(filled(wl, 0));
        if (w != state_[e].weight) {
          emit_at(e, band_sorted_[k].y, band_sorted_[k].x);
          state_[e].weight = static_cast<std::int8_t>(w);
        }
      }
      // The inversions are exactly the pairs whose order changed, so this is the prefix sum of the windings left
      // of e in the order at y1 (integers: no round-off).
      state_[e].left_winding = wl;
    }
    // The order at y1.
    scratch_.resize(m);
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t e = order_[band_keys_[i].pos];
      scratch_[i] = e;
      pos_[e] = static_cast<std::int32_t>(i);
      band_xa_[i] = band_keys_[i].x;
    }
    order_.swap(scratch_);
    return crossings;
  };
  // Brings the order up to height y (band mode); afterwards the order is sorted at y as the batch code expects.
  auto catch_up = [&](double y) {
    if (band_mode_ && y > band_from) row_crossings += sweep_band(band_from, y);
    band_from = y;
  };
  auto check_all = [&](double y) {
    for (std::size_t p = 0; p + 1 < order_.size(); ++p) check_pair(p, y);
  };

  // Row output: before the sweep passes the bottom of the current pixel row, the boundary edges hand over their
  // pieces down to it and the row is resolved.
  // (Only row output counts rows; its edges are clipped to the image. Unclipped edges may lie beyond 64 bits.)
  std::int64_t row = Out::kRows && n > 0 ? static_cast<std::int64_t>(std::floor(edges[starts_[0]].y0)) : 0;
  // Returns true when it scheduled crossings (back to events), which the caller must look at before anything at y.
  auto finish_rows_above = [&](double y) {
    bool scheduled = false;
    while (static_cast<double>(row + 1) <= y) {
      const double bottom = static_cast<double>(row + 1);
      if constexpr (kBands) catch_up(bottom);
      if (band_mode_ && band_top_y_ == bottom && band_xa_.size() == order_.size()) {
        // The band that just ended here has every edge's x at the bottom, in order.
        for (std::size_t i = 0; i < order_.size(); ++i) emit_at(order_[i], bottom, band_xa_[i]);
      } else {
        for (std::uint32_t e : order_) emit(e, bottom);
      }
      out.resolve(row);
      if constexpr (kBands) {
        // The next row's mode, from this row's count of crossings.
        const bool crowded = row_crossings >= kMinBandCrossings && row_crossings * 4 >= order_.size();
        if (band_mode_ && !crowded) {
          band_mode_ = false;
          band_top_y_ = -std::numeric_limits<double>::infinity();
          check_all(bottom);  // events again: every pair of neighbours needs its crossing scheduled
          scheduled = true;
        } else if (!band_mode_ && crowded && !track_faces) {
          band_mode_ = true;
        }
        band_from = bottom;
        row_crossings = row_batches = 0;
        out.crowded = band_mode_;
      }
      ++row;
      // Nothing active: jump to the row of the next event.
      if (order_.empty()) row = std::max(row, static_cast<std::int64_t>(std::floor(y)));
    }
    return scheduled;
  };

  std::vector<std::uint32_t>& h_order = h_order_;
  h_order.resize(horizontals.size());
  std::iota(h_order.begin(), h_order.end(), 0u);
  std::sort(h_order.begin(), h_order.end(),
            [&](std::uint32_t i, std::uint32_t j) { return horizontals[i].y0 < horizontals[j].y0; });

  std::size_t next_start = 0, next_h = 0;
  std::vector<std::uint32_t>&ends = ends_, &new_edges = new_edges_;
  std::vector<std::pair<double, double>>& blocked = blocked_;
  std::vector<double>& above_x = above_x_;
  std::vector<std::int32_t>& above_face = above_face_;
  const double inf = std::numeric_limits<double>::infinity();

  for (;;) {
    const double ys = next_start < n ? edges[starts_[next_start]].y0 : inf;
    const double yh = next_h < h_order.size() ? horizontals[h_order[next_h]].y0 : inf;
    const double ye = refill(std::min(ys, yh)) ? heap_.front().y : inf;
    const double y = std::min({ys, yh, ye});
    if (y == inf) break;
    if constexpr (Out::kRows) {
      if (finish_rows_above(y)) continue;  // new crossing events may come before y's
    }
    // Crossings at y go before the vertices at y, so an edge continuing another takes an up-to-date slot.
    const bool batch = !(ye == y && heap_.front().kind == kCrossing);
    if constexpr (kBands) {
      if (band_mode_) {
        if (!batch) {  // bands find the crossings themselves
          pop_event();
          continue;
        }
        catch_up(y);
        if (++row_batches > kMaxBandBatches) {  // vertex-heavy row: each band costs O(edges), go back to events
          band_mode_ = false;
          band_top_y_ = -std::numeric_limits<double>::infinity();
          check_all(y);
          continue;  // the crossings just scheduled at y go first
        }
      }
    }
    if (!batch) {
      // A crossing of two neighbours: swap them.
      const Event ev = pop_event();
      const std::int32_t p = pos_[ev.a];
      if (p < 0 || pos_[ev.b] != p + 1) continue;  // stale: they are no longer neighbours
      ++row_crossings;
      const std::uint32_t a = ev.a, b = ev.b;
      const auto pa = static_cast<std::size_t>(p);
      order_[pa] = b;
      order_[pa + 1] = a;
      pos_[b] = p;
      pos_[a] = p + 1;
      state_[b].left_winding = state_[a].left_winding;
      state_[a].left_winding = state_[b].left_winding + edges[b].winding;
      if (track_faces) {
        left_face_[b] = left_face_[a];
        left_face_[a] = state.faces.make();  // the face opening below the crossing point
      }
      update_weight(pa, y);
      update_weight(pa + 1, y);
      if (pa > 0) check_pair(pa - 1, y);
      if (pa + 2 < order_.size()) check_pair(pa + 1, y);
      continue;
    }

    // A batch at height y: edges ending, edges starting, horizontal edges.
    ends.clear();
    while (refill(y) && heap_.front().y == y && heap_.front().kind == kEnd) ends.push_back(pop_event().a);
    const std::size_t start_begin = next_start;
    while (next_start < n && edges[starts_[next_start]].y0 == y) ++next_start;
    blocked.clear();
    while (next_h < h_order.size() && horizontals[h_order[next_h]].y0 == y) {
      const Edge& h = horizontals[h_order[next_h++]];
      blocked.emplace_back(std::min(h.x0, h.x1), std::max(h.x0, h.x1));
    }

    // An edge that ends where one of the same direction starts continues through the vertex: the new edge takes
    // the old one's place, winding and faces (the common case along a contour, O(1)).
    new_edges.clear();
    std::sort(ends.begin(), ends.end(), [&](std::uint32_t i, std::uint32_t j) { return edges[i].x1 < edges[j].x1; });
    consumed_.assign(ends.size(), 0);
    replaced_.clear();
    std::size_t ei = 0;
    for (std::size_t k = start_begin; k < next_start; ++k) {
      const std::uint32_t s = starts_[k];
      const Edge& es = edges[s];
      while (ei < ends.size() && edges[ends[ei]].x1 < es.x0) ++ei;
      std::size_t m = ei;
      while (m < ends.size() && edges[ends[m]].x1 == es.x0 &&
             (consumed_[m] || edges[ends[m]].winding != es.winding)) {
        ++m;
      }
      if (blocked.empty() && m < ends.size() && edges[ends[m]].x1 == es.x0) {
        const std::uint32_t e = ends[m];
        emit(e, y);
        const std::int32_t p = pos_[e];
        order_[p] = s;
        pos_[s] = p;
        pos_[e] = -1;
        state_[s].left_winding = state_[e].left_winding;
        left_face_[s] = left_face_[e];
        state_[s].weight = state_[e].weight;
        state_[s].since = {es.x0, y};
        dirty_[s] = 1;
        replaced_.push_back(s);
        push_event({es.y1, kEnd, s, 0});
        consumed_[m] = 1;
      } else {
        new_edges.push_back(s);
      }
    }
    std::size_t unmatched_ends = 0;
    for (std::size_t m = 0; m < ends.size(); ++m) unmatched_ends += !consumed_[m];

    if (unmatched_ends == 0 && new_edges.empty() && blocked.empty()) {
      // Only pass-through vertices: check the new neighbours of the continuing edges, O(1) each.
      for (std::uint32_t s : replaced_) {
        const auto p = static_cast<std::size_t>(pos_[s]);
        if (p > 0) check_pair(p - 1, y);
        if (p + 1 < order_.size()) check_pair(p, y);
        dirty_[s] = 0;
      }
      continue;  // (in band mode the x cached for the next band stays right: a continuing edge starts where its
                 // predecessor ended, in the same slot)
    }

    // Turning vertices: local minima (two edges of opposite winding start at one point) and local maxima (two
    // neighbours of opposite winding end at one point). The windings of all other edges stay as they are, so only
    // positions shift: no rebuild. Several may share a height (a circle's mirror images); whatever does not fit
    // these patterns is left to the general path below.
    if (blocked.empty() && replaced_.empty()) {
      for (std::size_t m = 0; m + 1 < ends.size(); ++m) {  // ends are sorted by x1
        if (consumed_[m] || consumed_[m + 1] || edges[ends[m]].x1 != edges[ends[m + 1]].x1) continue;
        if (remove_turning_pair(ends[m], ends[m + 1], y, track_faces, state, emit)) {
          consumed_[m] = consumed_[m + 1] = 1;
          unmatched_ends -= 2;
          ++m;
        }
      }
      std::sort(new_edges.begin(), new_edges.end(), [&](std::uint32_t i, std::uint32_t j) {
        return edges[i].x0 < edges[j].x0 || (edges[i].x0 == edges[j].x0 && edges[i].dxdy < edges[j].dxdy);
      });
      std::size_t kept = 0;
      for (std::size_t k = 0; k < new_edges.size(); ++k) {
        if (k + 1 < new_edges.size() && edges[new_edges[k]].x0 == edges[new_edges[k + 1]].x0 &&
            insert_turning_pair(new_edges[k], new_edges[k + 1], y, track_faces, state, update_weight)) {
          ++k;
          continue;
        }
        new_edges[kept++] = new_edges[k];
      }
      new_edges.resize(kept);
      if (unmatched_ends == 0 && new_edges.empty()) continue;
    }

    // General case: rebuild the order at y, O(active edges).
    band_top_y_ = -std::numeric_limits<double>::infinity();  // no cached x for the next band
    if (track_faces) {
      above_x.clear();
      above_face.clear();
      for (std::uint32_t e : order_) {
        above_x.push_back(x_of(edges[e], y));
        above_face.push_back(left_face_[e]);
      }
      above_face.push_back(0);
    }
    for (std::size_t m = 0; m < ends.size(); ++m) {
      if (consumed_[m]) continue;
      const std::uint32_t e = ends[m];
      emit(e, y);
      const std::int32_t p = pos_[e];
      order_[p] = kRemoved;
      pos_[e] = -1;
    }
    // The neighbours of removed edges get new neighbours.
    for (std::size_t p = 0; p < order_.size(); ++p) {
      if (order_[p] != kRemoved) continue;
      if (p > 0 && order_[p - 1] != kRemoved) dirty_[order_[p - 1]] = 1;
      if (p + 1 < order_.size() && order_[p + 1] != kRemoved) dirty_[order_[p + 1]] = 1;
    }
    std::erase(order_, kRemoved);
    std::sort(new_edges.begin(), new_edges.end(), [&](std::uint32_t i, std::uint32_t j) {
      return edges[i].x0 < edges[j].x0 || (edges[i].x0 == edges[j].x0 && edges[i].dxdy < edges[j].dxdy);
    });
    scratch_.clear();
    std::size_t oi = 0;
    for (std::uint32_t s : new_edges) {
      const Edge& es = edges[s];
      while (oi < order_.size()) {
        const Edge& eo = edges[order_[oi]];
        const double xo = x_of(eo, y);
        if (xo < es.x0 || (xo == es.x0 && eo.dxdy <= es.dxdy)) {
          scratch_.push_back(order_[oi++]);
        } else {
          break;
        }
      }
      scratch_.push_back(s);
      dirty_[s] = 1;
      state_[s].since = {es.x0, y};
      state_[s].weight = 0;
      push_event({es.y1, kEnd, s, 0});
    }
    while (oi < order_.size()) scratch_.push_back(order_[oi++]);
    order_.swap(scratch_);

    int w = 0;
    for (std::size_t p = 0; p < order_.size(); ++p) {
      const std::uint32_t e = order_[p];
      pos_[e] = static_cast<std::int32_t>(p);
      state_[e].left_winding = w;
      w += edges[e].winding;
    }
    if (track_faces) {
      // Faces below the line: fresh ids (outermost ones are the outside), united with the faces above wherever
      // the line between them is free.
      for (std::size_t p = 0; p < order_.size(); ++p) left_face_[order_[p]] = p == 0 ? 0 : state.faces.make();
      std::sort(blocked.begin(), blocked.end());
      std::vector<double>& cuts = cuts_;
      cuts.clear();
      cuts.insert(cuts.end(), above_x.begin(), above_x.end());
      for (std::uint32_t e : order_) cuts.push_back(x_of(edges[e], y));
      for (const auto& [lo, hi] : blocked) {
        cuts.push_back(lo);
        cuts.push_back(hi);
      }
      std::sort(cuts.begin(), cuts.end());
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
      std::size_t ia = 0, ib = 0, ih = 0;
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double lo = cuts[c], hi = cuts[c + 1];
        while (ia < above_x.size() && above_x[ia] <= lo) ++ia;
        while (ib < order_.size() && x_of(edges[order_[ib]], y) <= lo) ++ib;
        while (ih < blocked.size() && blocked[ih].second <= lo) ++ih;
        bool is_blocked = false;
        for (std::size_t k = ih; k < blocked.size() && blocked[k].first <= lo; ++k) {
          if (blocked[k].second >= hi) {
            is_blocked = true;
            break;
          }
        }
        if (is_blocked) continue;
        const std::int32_t below = ib < order_.size() ? left_face_[order_[ib]] : 0;
        state.faces.unite(above_face[ia], below);
      }
    }
    for (std::size_t p = 0; p < order_.size(); ++p) update_weight(p, y);
    for (std::size_t p = 0; p + 1 < order_.size(); ++p) {
      if (dirty_[order_[p]] | dirty_[order_[p + 1]]) check_pair(p, y);
    }
    for (std::uint32_t e : order_) dirty_[e] = 0;
  }
  if constexpr (Out::kRows) {
    if (n > 0) out.resolve(row);  // every edge has ended: the last row holds all its pieces
  }
}

void BoundarySweep::extract(const std::vector<Edge>& edges, const std::vector<Edge>& horizontals, FillRule rule,
                            std::vector<Edge>& out) {
  State state;
  PieceList pieces{&out};
  if (rule != FillRule::NonExterior) {
    static const std::vector<Edge> kNone;
    run(edges, kNone, false, state, [rule](int w, std::int32_t) { return winding_fills(rule, w); }, pieces);
    return;
  }
  // First pass: which faces reach the outside. Second pass: the same sweep (same face ids), writing the pieces
  // between exterior and non-exterior faces.
  PieceList nowhere{nullptr};
  run(edges, horizontals, true, state, [](int, std::int32_t) { return false; }, nowhere);
  state.exterior.resize(state.faces.size());
  for (std::size_t i = 0; i < state.exterior.size(); ++i) {
    state.exterior[i] = state.faces.find(static_cast<std::int32_t>(i)) == 0;
  }
  std::vector<std::uint8_t> exterior = std::move(state.exterior);
  run(edges, horizontals, true, state, [&](int, std::int32_t face) { return !exterior[face]; }, pieces);
}

void BoundarySweep::fill(const std::vector<Edge>& edges, FillRule rule, int width, CoverageSink& sink) {
  const std::size_t cells = static_cast<std::size_t>(width) + 2;
  if (cells_.size() < cells) cells_.assign(cells, 0.0);
  if (touched_.size() < cells / 64 + 1) touched_.assign(cells / 64 + 1, 0);
  if (coverage_.size() < cells) coverage_.resize(cells);
  RowCells rows{width, cells_.data(), touched_.data(), coverage_.data(), sink, width + 1, 0};
  State state;
  static const std::vector<Edge> kNone;
  // The rule as a compile-time constant: the sweep asks it twice per crossing.
  with_rule(rule, [&](auto r) {
    run(edges, kNone, false, state, [](int w, std::int32_t) { return winding_fills(decltype(r)::value, w); }, rows);
  });
}

}  // namespace vraster::detail
