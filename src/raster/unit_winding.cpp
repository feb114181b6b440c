// A sweep down the edges that only looks for trouble. Between two heights where the set of active edges changes,
// the active edges are straight and keep their order unless two of them cross; a crossing first happens between
// neighbours, so each edge is tested against its neighbours whenever it or they change (Shamos and Hoey's test for
// "any crossing at all"). Without crossings the winding of the faces between neighbours only changes where edges
// start or end without continuing a chain, and there every face is checked for {0, s}.
#include "raster/unit_winding.hpp"

#include <algorithm>
#include <limits>

#include "raster/boundary.hpp"

namespace vraster::detail {
namespace {

// The test gives up past this much work (active edges summed over the heights it visits) per edge: a glyph or a
// circle needs 2 to 10; a path with hundreds of edges side by side (a whole line of text in one path) is the
// boundary sweep's job.
constexpr std::size_t kWorkPerEdge = 24;

// x_of for an edge active at y (y0 <= y <= y1); x_at is exact at y0 already.
inline double x_inside(const Edge& e, double y) { return y == e.y1 ? e.x1 : e.x_at(y); }

// Whether `left` is still at or left of `right` where the first of them ends. Enough for the whole of their common
// stretch below the current height: there they were in order already (when they became neighbours, or at the end of
// the edges they continue), and straight pieces in order at both ends are in order in between.
inline bool in_order_at_first_end(const Edge& left, const Edge& right) {
  return left.y1 <= right.y1 ? left.x1 <= x_inside(right, left.y1) : x_inside(left, right.y1) <= right.x1;
}

}  // namespace

bool UnitWindingTest::operator()(const std::vector<Edge>& edges) {
  const auto n = static_cast<std::uint32_t>(edges.size());
  // Chains, in the order the edges come.
  chains_.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    const Edge& e = edges[i];
    if (i > 0 && chains_.back().winding == e.winding) {
      const Edge& p = edges[i - 1];
      const bool joins = e.winding > 0 ? p.x1 == e.x0 && p.y1 == e.y0 : e.x1 == p.x0 && e.y1 == p.y0;
      if (joins) {
        Chain& c = chains_.back();
        c.last = i;
        if (e.winding < 0) {  // an upward chain is listed bottom to top: its newest edge is its top
          c.top_y = e.y0;
          c.top_x = e.x0;
          c.top_dxdy = e.dxdy;
        }
        continue;
      }
    }
    chains_.push_back({e.y0, e.x0, e.dxdy, i, i, e.winding});
  }
  const auto by_top = [](const Chain& a, const Chain& b) {
    return a.top_y < b.top_y || (a.top_y == b.top_y && (a.top_x < b.top_x || (a.top_x == b.top_x && a.top_dxdy < b.top_dxdy)));
  };
  if (chains_.size() > 16) {
    std::sort(chains_.begin(), chains_.end(), by_top);
  } else {  // most paths are small: a plain insertion sort costs less than setting up std::sort
    for (std::size_t i = 1; i < chains_.size(); ++i) {
      const Chain c = chains_[i];
      std::size_t j = i;
      for (; j > 0 && by_top(c, chains_[j - 1]); --j) chains_[j] = chains_[j - 1];
      chains_[j] = c;
    }
  }

  active_.clear();
  const std::size_t budget = kWorkPerEdge * n + 64;
  const double inf = std::numeric_limits<double>::infinity();
  std::size_t work = 0, next_chain = 0;
  int s = 0;  // the one non-zero winding, once seen
  for (;;) {
    // The next height: the earliest end among the active edges, or the next chain's top.
    double y = inf;
    std::size_t earliest = 0;
    const std::size_t count = active_.size();
    const Active* active = active_.data();
    for (std::size_t i = 0; i < count; ++i) {
      const double y1 = active[i].edge.y1;
      earliest = y1 < y ? i : earliest;
      y = std::min(y, y1);
    }
    const double next_top = next_chain < chains_.size() ? chains_[next_chain].top_y : inf;
    work += count;
    if (work > budget) return false;
    if (y < next_top && active_[earliest].next != active_[earliest].end) {
      // The common case: one chain passes a vertex. Its new edge takes its place; only its neighbours can cross it.
      Active& a = active_[earliest];
      a.edge = edges[a.next];
      a.next += a.step;
      if (earliest > 0 && !in_order_at_first_end(active_[earliest - 1].edge, a.edge)) return false;
      if (earliest + 1 < count && !in_order_at_first_end(a.edge, active_[earliest + 1].edge)) return false;
      continue;
    }
    y = std::min(y, next_top);
    if (y == inf) return true;

    // Edges ending at y: the chain goes on with its next edge (same vertex, same direction: no face changes), or
    // ends and leaves its neighbours side by side.
    bool faces_changed = false;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < active_.size(); ++i) {
      Active& a = active_[i];
      if (a.edge.y1 == y) {
        if (a.next == a.end) {
          faces_changed = true;
          if (kept > 0) active_[kept - 1].changed = true;
          continue;
        }
        a.edge = edges[a.next];
        a.next += a.step;
        a.changed = true;
      }
      if (kept != i) active_[kept] = a;
      ++kept;
    }
    active_.resize(kept);
    // Chains starting at y, in order of x and then slope, each where it falls in the order.
    for (; next_chain < chains_.size() && chains_[next_chain].top_y == y; ++next_chain) {
      const Chain& c = chains_[next_chain];
      const bool down = c.winding > 0;
      const std::uint32_t first = down ? c.first : c.last;
      const Edge& e = edges[first];
      std::size_t p = 0;
      while (p < active_.size()) {
        const double x = x_of(active_[p].edge, y);
        if (x > e.x0 || (x == e.x0 && active_[p].edge.dxdy > e.dxdy)) break;
        ++p;
      }
      const std::int32_t step = down ? 1 : -1;
      active_.insert(active_.begin() + static_cast<std::ptrdiff_t>(p),
                     Active{e, first + static_cast<std::uint32_t>(step), (down ? c.last : c.first) + static_cast<std::uint32_t>(step), step, true});
      faces_changed = true;
    }
    if (faces_changed) {
      int w = 0;
      for (const Active& a : active_) {
        w += a.edge.winding;
        if (w == 0) continue;
        if (s == 0) s = w;
        if (w != s) return false;
      }
    }
    for (std::size_t i = 0; i < active_.size(); ++i) {
      if (!active_[i].changed) continue;
      active_[i].changed = false;
      if (i > 0 && !in_order_at_first_end(active_[i - 1].edge, active_[i].edge)) return false;
      if (i + 1 < active_.size() && !in_order_at_first_end(active_[i].edge, active_[i + 1].edge)) return false;
    }
  }
}

}  // namespace vraster::detail
