// The work budget of exact fills: counts the edge crossings inside pixel rows before the boundary sweep runs.
//
// The boundary sweep's cost grows with the crossings it must resolve (a 100,000-point star in 200 px has
// billions). Per row, two segments cross inside the row exactly when their x order at the row's top and bottom
// differs, so the crossings are the inversions between those two orders. A quick bound first: at most
// a(a-1)/2 crossings in a row with a active edges, summed over rows from a difference array; only when that bound
// passes the budget are the inversions counted (row_crossings, stopping as soon as the budget is passed).
#include <algorithm>
#include <cmath>

#include "raster/rasterizer_p.hpp"

namespace vraster::detail {
namespace {

struct RowX {
  double top, bottom;  // the edge's x at the row's top and bottom (clamped to the edge's own rows)
  std::uint32_t edge;
};

bool before(const RowX& a, const RowX& b) { return a.top < b.top || (a.top == b.top && a.bottom < b.bottom); }

}  // namespace

// The order at one row's bottom is the order at the next row's top (an edge that goes on is at x_at(bottom) in both,
// the same number), so each row starts from the last row's order: a pass that moves each edge's bottom x to its top,
// an insertion sort that only has ties to fix, the row's new edges merged in; then an insertion sort by the bottom
// x counts the inversions as it moves past them, and leaves the order the next row starts from. Linear per row
// plus the crossings themselves, against a sort of every row from scratch (a third of a star's exact frame).
std::uint64_t row_crossings(const std::vector<Edge>& edges, int height, std::uint64_t limit) {
  std::vector<std::uint32_t> by_y0(edges.size());
  for (std::uint32_t i = 0; i < by_y0.size(); ++i) by_y0[i] = i;
  std::sort(by_y0.begin(), by_y0.end(), [&](std::uint32_t a, std::uint32_t b) { return edges[a].y0 < edges[b].y0; });
  std::vector<RowX> row, fresh, merged;
  std::size_t next = 0;
  std::uint64_t crossings = 0;
  for (int r = 0; r < height; ++r) {
    const double top = r, bottom = r + 1.0;
    if (row.empty() && next < by_y0.size() && edges[by_y0[next]].y0 >= bottom) continue;  // nothing in this row
    std::erase_if(row, [&](const RowX& x) { return edges[x.edge].y1 <= top; });  // stable: the order holds
    for (RowX& x : row) {
      const Edge& e = edges[x.edge];
      x.top = x.bottom;
      x.bottom = e.x_at(std::min(bottom, e.y1));
    }
    for (std::size_t i = 1; i < row.size(); ++i) {  // ties at the top, ordered by the bottom
      const RowX x = row[i];
      std::size_t j = i;
      for (; j > 0 && before(x, row[j - 1]); --j) row[j] = row[j - 1];
      row[j] = x;
    }
    fresh.clear();
    for (; next < by_y0.size() && edges[by_y0[next]].y0 < bottom; ++next) {
      const Edge& e = edges[by_y0[next]];
      if (e.y1 <= top) continue;
      fresh.push_back({e.x_at(std::max(top, e.y0)), e.x_at(std::min(bottom, e.y1)), by_y0[next]});
    }
    if (!fresh.empty()) {
      std::sort(fresh.begin(), fresh.end(), before);
      merged.resize(row.size() + fresh.size());
      std::merge(row.begin(), row.end(), fresh.begin(), fresh.end(), merged.begin(), before);
      row.swap(merged);
    }
    // Inversions of the bottom order: each step left past a larger bottom x is one crossing.
    for (std::size_t i = 1; i < row.size(); ++i) {
      const RowX x = row[i];
      std::size_t j = i;
      for (; j > 0 && row[j - 1].bottom > x.bottom; --j) row[j] = row[j - 1];
      row[j] = x;
      crossings += i - j;
      if (crossings > limit) return crossings;
    }
  }
  return crossings;
}

bool RasterizerImpl::exact_within_budget(int height) {
  if (edges_.empty()) return true;
  const std::uint64_t budget = Rasterizer::kMaxExactCrossings;
  // Active edges per row, from where each edge starts and ends.
  std::vector<std::int64_t>& count = budget_rows_;
  count.assign(static_cast<std::size_t>(height) + 1, 0);
  for (const Edge& e : edges_) {
    const auto r0 = static_cast<std::size_t>(std::clamp(std::floor(e.y0), 0.0, static_cast<double>(height)));
    const auto r1 = static_cast<std::size_t>(std::clamp(std::ceil(e.y1), 0.0, static_cast<double>(height)));
    if (r1 <= r0) continue;
    ++count[r0];
    --count[r1];
  }
  std::uint64_t bound = 0;
  std::int64_t active = 0;
  for (int r = 0; r < height; ++r) {
    active += count[static_cast<std::size_t>(r)];
    bound += static_cast<std::uint64_t>(active) * static_cast<std::uint64_t>(std::max<std::int64_t>(active - 1, 0)) / 2;
    if (bound > budget) break;
  }
  if (bound <= budget) return true;
  return row_crossings(edges_, height, budget) <= budget;
}

}  // namespace vraster::detail
