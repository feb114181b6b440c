// Paths whose analytic coverage is already exact.
#pragma once

#include <cstdint>
#include <vector>

#include "vraster/raster.hpp"

namespace vraster::detail {

/// Decides whether the winding number of `edges` is 0 or s almost everywhere, for one s in {+1, -1}. Then every
/// pixel sees at most two consecutive winding numbers, the analytic accumulation is the exact area under every
/// winding rule, and exact mode needs no boundary sweep. Simple polygons, glyph outlines with their holes drawn the
/// other way round, rectangles, circles and strokes of disjoint pieces pass; crossings, overlaps and nesting in the
/// same direction do not.
///
/// Conservative: false is also the answer where the test would cost more than the sweep (long active lists), where
/// coincident edges leave the order ambiguous, and for parts of opposite orientation (even when they are apart).
class UnitWindingTest {
 public:
  bool operator()(const std::vector<Edge>& edges);

 private:
  // A run of edges that join end to start in the order build_edges left them, all in one direction: a piece of a
  // contour that is monotone in y. Edges of a chain enter the sweep one after the other, with no sorting.
  struct Chain {
    double top_y, top_x, top_dxdy;
    std::uint32_t first, last;  // edge indices; walked first -> last going down, last -> first going up
    std::int32_t winding;
  };
  struct Active {
    Edge edge;            // the chain's current edge
    std::uint32_t next;   // the chain's next edge, or `end` when this is its last
    std::uint32_t end;
    std::int32_t step;    // +1 or -1 through the edge indices
    bool changed;         // new neighbours or a new edge at this height: test against both neighbours
  };
  std::vector<Chain> chains_;
  std::vector<Active> active_;  // sorted by x at the sweep line
};

}  // namespace vraster::detail
