// detail::row_crossings, the count behind exact mode's work budget, against a count of every pair of edges in every
// row: a pair crosses inside a row when its x order at the row's top (ties by x at the bottom) and at the bottom
// differ. The count carries each row's order into the next, so the edges here start and end inside rows and on row
// lines, share end points (as the sides of a star do), stand vertical and meet at the same x.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "raster/rasterizer_p.hpp"

namespace vraster::test {
namespace {

Edge edge(double x0, double y0, double x1, double y1) {
  if (y0 > y1) {
    std::swap(x0, x1);
    std::swap(y0, y1);
  }
  return Edge{x0, y0, x1, y1, (x1 - x0) / (y1 - y0), 1};
}

std::uint64_t every_pair(const std::vector<Edge>& edges, int height) {
  std::uint64_t crossings = 0;
  for (int r = 0; r < height; ++r) {
    const double top = r, bottom = r + 1.0;
    std::vector<std::pair<double, double>> xs;
    for (const Edge& e : edges) {
      if (e.y0 < bottom && e.y1 > top) xs.emplace_back(e.x_at(std::max(top, e.y0)), e.x_at(std::min(bottom, e.y1)));
    }
    for (std::size_t i = 0; i < xs.size(); ++i) {
      for (std::size_t j = 0; j < xs.size(); ++j) {
        if (xs[i] < xs[j] && xs[i].second > xs[j].second) ++crossings;
      }
    }
  }
  return crossings;
}

TEST(ExactBudget, RowCrossingsCountEveryCrossingPairInEveryRow) {
  std::mt19937 rng(404);
  std::uniform_real_distribution<double> unit(0, 1);
  const int height = 24;
  int with_crossings = 0;
  for (int it = 0; it < 300; ++it) {
    std::vector<Point> corners;  // shared end points
    for (int k = 0; k < 6; ++k) {
      const double y = rng() % 3 == 0 ? static_cast<double>(rng() % (height + 1)) : unit(rng) * height;
      corners.push_back({rng() % 4 == 0 ? 10.0 : unit(rng) * 20, y});
    }
    std::vector<Edge> edges;
    const int n = 2 + static_cast<int>(rng() % 40);
    for (int k = 0; k < n; ++k) {
      Point a = corners[rng() % corners.size()], b = corners[rng() % corners.size()];
      if (rng() % 3 == 0) a = {unit(rng) * 20, unit(rng) * height};
      if (rng() % 3 == 0) b = {rng() % 5 == 0 ? a.x : unit(rng) * 20, unit(rng) * height};  // vertical at times
      if (a.y == b.y) continue;
      edges.push_back(edge(a.x, a.y, b.x, b.y));
    }
    const std::uint64_t expected = every_pair(edges, height);
    with_crossings += expected > 0;
    ASSERT_EQ(detail::row_crossings(edges, height, ~std::uint64_t{0}), expected) << "iteration " << it;
    // With a limit the count stops past it: above the limit exactly when the true count is.
    const std::uint64_t limit = expected / 2;
    EXPECT_EQ(detail::row_crossings(edges, height, limit) > limit, expected > limit) << "iteration " << it;
  }
  EXPECT_GT(with_crossings, 200);
}

TEST(ExactBudget, ACrossingOnARowLineIsInsideNeitherRow) {
  // The diagonals of a square cross at (5, 5), on the line between rows 4 and 5: at row 5's top the two are tied,
  // and the one that goes left is first. An X crossing inside row 6 (at y = 6.5) counts once.
  const std::vector<Edge> on_line = {edge(0, 0, 10, 10), edge(10, 0, 0, 10)};
  EXPECT_EQ(every_pair(on_line, 10), 0u);
  EXPECT_EQ(detail::row_crossings(on_line, 10, ~std::uint64_t{0}), 0u);
  const std::vector<Edge> inside = {edge(0, 0, 13, 13), edge(13, 0, 0, 13)};
  EXPECT_EQ(every_pair(inside, 13), 1u);
  EXPECT_EQ(detail::row_crossings(inside, 13, ~std::uint64_t{0}), 1u);
}

TEST(ExactBudget, AStarCrossesAsOftenAsEveryPairSays) {
  // A 37-point star through a 64-row box: long sides through many rows, all meeting at the points.
  std::vector<Point> pts;
  for (int i = 0; i < 37; ++i) {
    const double a = 2 * 3.14159265358979 * (i * 16 % 37) / 37.0;
    pts.push_back({32 + 30 * std::cos(a), 32 + 30 * std::sin(a)});
  }
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point a = pts[i], b = pts[(i + 1) % pts.size()];
    if (a.y != b.y) edges.push_back(edge(a.x, a.y, b.x, b.y));
  }
  const std::uint64_t expected = every_pair(edges, 64);
  EXPECT_GT(expected, 300u);
  EXPECT_EQ(detail::row_crossings(edges, 64, ~std::uint64_t{0}), expected);
}

}  // namespace
}  // namespace vraster::test
