// The work budget of exact fills: counts the edge crossings inside pixel rows before the boundary sweep runs.
//
// The boundary sweep's cost grows with the crossings it must resolve (a 100,000-point star in 200 px has
// billions). Per row, two segments cross inside the row exactly when their x order at the row's top and bottom
// differs, so the crossings are the inversions between those two orders. A quick bound first: at most
// a(a-1)/2 crossings in a row with a active edges, summed over rows from a difference array; only when that bound
// passes the budget are the inversions counted (merge sort per row, stopping as soon as the budget is passed).
#include <algorithm>
#include <cmath>

#include "raster/rasterizer_p.hpp"

namespace vraster::detail {

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

  // The real count: per row, order the active edges by x at the top, count inversions of x at the bottom.
  std::vector<std::uint32_t>& by_top = budget_order_;
  by_top.resize(edges_.size());
  for (std::uint32_t i = 0; i < by_top.size(); ++i) by_top[i] = i;
  std::sort(by_top.begin(), by_top.end(), [&](std::uint32_t a, std::uint32_t b) { return edges_[a].y0 < edges_[b].y0; });
  std::vector<std::uint32_t> active_edges;
  std::vector<std::pair<double, double>> xs;
  std::vector<double> bottoms, merged;
  std::size_t next = 0;
  std::uint64_t crossings = 0;
  for (int r = 0; r < height; ++r) {
    const double top = r, bottom = r + 1.0;
    while (next < by_top.size() && edges_[by_top[next]].y0 < bottom) active_edges.push_back(by_top[next++]);
    std::erase_if(active_edges, [&](std::uint32_t i) { return edges_[i].y1 <= top; });
    xs.clear();
    for (const std::uint32_t i : active_edges) {
      const Edge& e = edges_[i];
      xs.emplace_back(e.x_at(std::max(top, e.y0)), e.x_at(std::min(bottom, e.y1)));
    }
    std::sort(xs.begin(), xs.end());
    bottoms.resize(xs.size());
    for (std::size_t k = 0; k < xs.size(); ++k) bottoms[k] = xs[k].second;
    // Bottom-up merge sort counting inversions (pairs i < j with bottoms[i] > bottoms[j]).
    merged.resize(bottoms.size());
    for (std::size_t width = 1; width < bottoms.size(); width *= 2) {
      for (std::size_t lo = 0; lo < bottoms.size(); lo += 2 * width) {
        const std::size_t mid = std::min(lo + width, bottoms.size()), hi = std::min(lo + 2 * width, bottoms.size());
        std::size_t a = lo, b = mid, o = lo;
        while (a < mid && b < hi) {
          if (bottoms[b] < bottoms[a]) {
            crossings += mid - a;
            merged[o++] = bottoms[b++];
          } else {
            merged[o++] = bottoms[a++];
          }
        }
        while (a < mid) merged[o++] = bottoms[a++];
        while (b < hi) merged[o++] = bottoms[b++];
      }
      bottoms.swap(merged);
      if (crossings > budget) return false;
    }
  }
  return true;
}

}  // namespace vraster::detail
