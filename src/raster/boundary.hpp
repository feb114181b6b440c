// Boundary extraction: edges -> the pieces of them that bound the filled region under a fill rule.
//
// The pieces never cross each other and bound a region of winding 0 or 1, so the analytic accumulation over them
// gives the true area of (filled region x pixel) for any rule, also where the original edges cross inside a pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "vraster/raster.hpp"

namespace vraster::detail {

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

 private:
  struct Event {
    double y;
    std::uint32_t kind;  // kCrossing or kEnd; at equal y crossings come first
    std::uint32_t a, b;
  };
  static constexpr std::uint32_t kCrossing = 0, kEnd = 1;
  struct Later {
    bool operator()(const Event& p, const Event& q) const { return p.y > q.y || (p.y == q.y && p.kind > q.kind); }
  };

  struct State;
  template <class Filled>
  void run(const std::vector<Edge>& edges, const std::vector<Edge>& horizontals, bool track_faces, State& state,
           Filled&& filled, std::vector<Edge>* out);

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
  std::vector<std::int32_t> left_winding_;  // winding number just left of each active edge
  std::vector<std::int32_t> left_face_;     // NonExterior: face id just left of each active edge
  std::vector<std::int8_t> weight_;    // filled(right) - filled(left) of each active edge
  std::vector<double> since_;          // y from which weight_ holds
  std::vector<std::uint8_t> dirty_;    // edges whose neighbours changed in the current batch
  std::vector<std::uint32_t> scratch_;
  std::vector<std::uint8_t> consumed_;
  std::vector<std::uint32_t> replaced_;  // edges that continued an ending one in the current batch  // ends of the current batch already continued by a starting edge
};

}  // namespace vraster::detail
