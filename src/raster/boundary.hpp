// Boundary extraction: edges -> the pieces of them that bound the filled region under a fill rule.
//
// The pieces never cross each other and bound a region of winding 0 or 1, so the analytic accumulation over them
// gives the true area of (filled region x pixel) for any rule, also where the original edges cross inside a pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "vraster/raster.hpp"

namespace vraster::detail {

/// x of an edge at height y, exact at its end points (so edges that share a vertex agree there).
[[gnu::always_inline]] inline double x_of(const Edge& e, double y) {
  if (y == e.y0) return e.x0;
  if (y == e.y1) return e.x1;
  return e.x_at(y);
}

/// Classifies the faces of the edges' arrangement as filled or not.
///  - For a winding rule, a face is filled when the rule holds for its winding number.
///  - For NonExterior, a face is filled unless it is connected to the region outside all edges.
class BoundarySweep {
 public:
  /// Appends the boundary pieces of the filled region to `out`, each with winding +1 (filled region to its
  /// right, as a downward edge) or -1. `edges` must not contain horizontal edges; for NonExterior, `horizontals`
  /// holds the horizontal segments (they block the way out and so matter for connectivity).
  void extract(const std::vector<Edge>& edges, const std::vector<Edge>& horizontals, FillRule rule,
               std::vector<Edge>& out);

  /// Exact coverage of `edges` (clipped to the image, as Rasterizer::build_edges leaves them) under a winding
  /// rule, straight to `sink`: the boundary pieces are accumulated into one pixel row at a time as the sweep
  /// passes it (no list of pieces, no second sweep). Rows come out in increasing y.
  void fill(const std::vector<Edge>& edges, FillRule rule, int width, CoverageSink& sink);

 private:
  struct Event {
    double y;
    std::uint32_t kind;  // kCrossing or kEnd; at equal y crossings come first
    std::uint32_t a, b;
  };
  static constexpr std::uint32_t kCrossing = 0, kEnd = 1;
  // Paths with fewer edges keep all their events in one heap: setting up and walking row buckets costs more.
  static constexpr std::size_t kMinBucketedEdges = 256;
  struct Later {
    bool operator()(const Event& p, const Event& q) const { return p.y > q.y || (p.y == q.y && p.kind > q.kind); }
  };

  struct State;
  struct PieceList;
  struct RowCells;
  template <class Filled, class Out>
  void run(const std::vector<Edge>& edges, const std::vector<Edge>& horizontals, bool track_faces, State& state,
           Filled&& filled, Out& out);

  template <class UpdateWeight>
  bool insert_turning_pair(std::uint32_t a, std::uint32_t b, double y, bool track_faces, State& state,
                           UpdateWeight& update_weight);
  template <class Emit>
  bool remove_turning_pair(std::uint32_t a, std::uint32_t b, double y, bool track_faces, State& state, Emit& emit);
  void check_pair(std::size_t left_pos, double y);
  void push_event(const Event& e);
  bool refill(double max_y);
  Event pop_event();

  const std::vector<Edge>* edges_ = nullptr;
  std::vector<std::uint32_t> starts_;  // edge indices sorted by (y0, x0)
  std::vector<Event> heap_;                   // events of the current row
  std::vector<std::vector<Event>> buckets_;   // events of later rows, by row
  bool bucketed_ = false;
  std::int64_t row_base_ = 0, current_row_ = -1;
  std::int64_t lowest_pending_ = 0;           // no bucket below this row holds events
  std::vector<std::uint32_t> order_;   // active edges sorted by x at the sweep line
  std::vector<std::int32_t> pos_;      // position of each edge in order_, -1 when inactive
  std::vector<std::int32_t> left_face_;     // NonExterior: face id just left of each active edge
  struct EdgeState {  // of each active edge, together: a crossing touches all of it
    Point since;               // the point of the edge from which `weight` holds
    std::int32_t left_winding = 0;  // winding number just left of the edge
    std::int8_t weight = 0;    // filled(right) - filled(left)
  };
  std::vector<EdgeState> state_;
  std::vector<std::uint8_t> dirty_;    // edges whose neighbours changed in the current batch
  std::vector<std::uint32_t> scratch_;
  std::vector<std::uint8_t> consumed_;
  std::vector<std::uint32_t> replaced_;  // edges that continued an ending one in the current batch
  // Scratch of one run, kept for its capacity.
  std::vector<std::uint32_t> ends_, new_edges_, h_order_;
  std::vector<std::pair<double, double>> blocked_;
  std::vector<double> above_x_, cuts_;
  std::vector<std::int32_t> above_face_;
  // Band mode (see run()): rows with at least this many crossings, a quarter of the active edges, go band by band,
  // unless a row has more than kMaxBandBatches heights where edges start or end.
  static constexpr std::size_t kMinBandCrossings = 32;
  static constexpr std::size_t kMaxBandBatches = 8;
  struct BandEvent {
    double y, x;        // the crossing point
    std::uint32_t pos;  // the edge's position in the order at the band's top
    std::int32_t delta; // change of the winding number left of it
  };
  bool band_mode_ = false;
  double band_top_y_ = 0;              // band_xa_ holds the order's x at this height (-inf: nothing cached)
  struct BandKey {
    double x;           // x at the band's bottom
    std::uint32_t pos;  // position in the order at its top
  };
  std::vector<double> band_xa_, band_xb_;   // x of the order's edges at the band's top and bottom
  std::vector<BandKey> band_keys_;
  std::vector<std::int8_t> band_w_;         // their windings
  std::vector<std::uint32_t> band_start_, band_cursor_;
  std::vector<BandEvent> band_events_, band_sorted_;
  // fill(): one row of accumulation cells, their touched bits, the row's coverage.
  std::vector<double> cells_;
  std::vector<std::uint64_t> touched_;
  std::vector<float> coverage_;
};

}  // namespace vraster::detail
