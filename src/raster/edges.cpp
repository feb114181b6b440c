// Edge building: polylines -> clipped, top-to-bottom edges -> edge table bucketed by first row.
#include <algorithm>
#include <cmath>

#include "raster/rasterizer_p.hpp"
#include "vraster/raster.hpp"

namespace vraster {

namespace {

void add_edge(std::vector<Edge>& edges, Point top, Point bottom, int winding) {
  if (!(bottom.y > top.y)) return;  // horizontal (or degenerate after clipping): contributes nothing
  const double dxdy = (bottom.x - top.x) / (bottom.y - top.y);
  edges.push_back({top.x, top.y, bottom.x, bottom.y, std::isfinite(dxdy) ? dxdy : 0.0, winding});
}

// Calls f(p, q) for every segment of the contours whose points are all finite: a contour with a NaN or infinite
// point has no shape, and is skipped whole (dropping only its bad segments would leave it open).
template <class F>
void for_each_finite_segment(const Polylines& lines, F&& f) {
  for (std::size_t k = 0; k < lines.contour_count(); ++k) {
    const auto pts = lines.contour(k);
    const std::size_t n = pts.size();
    if (n < 2) continue;
    bool finite = true;
    for (const Point& p : pts) finite = finite && std::isfinite(p.x) && std::isfinite(p.y);
    if (!finite) continue;
    for (std::size_t i = 0; i < n; ++i) f(pts[i], pts[i + 1 == n ? 0 : i + 1]);
  }
}

}  // namespace

// Clips segment p -> q to the device rectangle [0, width] x [0, height] and records what is left:
//  - parts above or below the rectangle, or right of it, change no pixel inside: dropped;
//  - parts left of it still change the winding of every pixel to their right: kept as vertical edges at x = 0.
void detail::add_clipped_segment(std::vector<Edge>& edges, Point p, Point q, int width, int height) {
  if (p.y == q.y) return;
  const int winding = q.y > p.y ? 1 : -1;
  Point a = winding > 0 ? p : q;  // top
  Point b = winding > 0 ? q : p;  // bottom
  const double h = height;
  if (b.y <= 0 || a.y >= h) return;
  if (a.x >= width && b.x >= width) return;
  // Interpolate from the endpoint nearer the cut, which keeps far-away endpoints from costing precision.
  auto x_at_y = [&](double y) {
    const double t = (y - a.y) / (b.y - a.y);
    return t < 0.5 ? a.x + (b.x - a.x) * t : b.x - (b.x - a.x) * (1 - t);
  };
  if (a.y < 0) a = {x_at_y(0), 0};
  if (b.y > h) b = {x_at_y(h), h};
  const double w = width;
  if (a.x <= 0 && b.x <= 0) return add_edge(edges, {0, a.y}, {0, b.y}, winding);
  if (a.x >= 0 && a.x <= w && b.x >= 0 && b.x <= w) return add_edge(edges, a, b, winding);

  // The segment crosses x = 0 and/or x = width: split it there.
  auto y_at_x = [&](double x) {
    const double t = (x - a.x) / (b.x - a.x);
    const double y = t < 0.5 ? a.y + (b.y - a.y) * t : b.y - (b.y - a.y) * (1 - t);
    return std::clamp(y, a.y, b.y);
  };
  Point cuts[4];
  int n = 0;
  cuts[n++] = a;
  const bool rightward = b.x > a.x;
  const double first = rightward ? 0.0 : w, second = rightward ? w : 0.0;
  for (double x : {first, second}) {
    if ((a.x < x && x < b.x) || (b.x < x && x < a.x)) cuts[n++] = {x, y_at_x(x)};
  }
  cuts[n++] = b;
  for (int i = 0; i + 1 < n; ++i) {
    const Point s = cuts[i], e = cuts[i + 1];
    const double mid = 0.5 * (s.x + e.x);
    if (mid < 0) {
      add_edge(edges, {0, s.y}, {0, e.y}, winding);
    } else if (mid <= w) {
      add_edge(edges, {std::clamp(s.x, 0.0, w), s.y}, {std::clamp(e.x, 0.0, w), e.y}, winding);
    }
  }
}

void detail::build_edges(const Polylines& lines, int width, int height, std::vector<Edge>& edges, int& y_min,
                         int& y_max, double* work) {
  edges.clear();
  if (work) *work = 0;
  if (lines.points.empty()) {
    y_min = y_max = 0;
    return;
  }
  // Only clip when something lies outside the image: most paths don't, and then every segment is an edge as is.
  double x_lo = lines.points[0].x, x_hi = x_lo, y_lo = lines.points[0].y, y_hi = y_lo;
  bool finite = true;
  for (const Point& p : lines.points) {
    x_lo = std::min(x_lo, p.x);
    x_hi = std::max(x_hi, p.x);
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
    finite = finite && std::isfinite(p.x) && std::isfinite(p.y);
  }
  if (!finite) {  // the contours without a NaN or infinite point, clipped (the bounds above are not theirs)
    for_each_finite_segment(lines, [&](Point p, Point q) { add_clipped_segment(edges, p, q, width, height); });
    row_range(edges, height, y_min, y_max);
    if (work) *work = band_work(edges);
    return;
  }
  const bool inside = x_lo >= 0 && y_lo >= 0 && x_hi <= width && y_hi <= height;
  auto add = [&](Point p, Point q) {
    if (!inside) {
      add_clipped_segment(edges, p, q, width, height);
    } else if (q.y > p.y) {
      edges.push_back({p.x, p.y, q.x, q.y, (q.x - p.x) / (q.y - p.y), 1});
    } else if (q.y < p.y) {
      edges.push_back({q.x, q.y, p.x, p.y, (p.x - q.x) / (p.y - q.y), -1});
    }
  };
  if (work && inside) {
    // band_work's sums over the segments as they go by (the same edges, nothing clipped): no second pass.
    WorkSums sums;
    lines.for_each_segment([&](Point p, Point q) {
      sums.add(p, q);
      add(p, q);
    });
    *work = sums.work();
  } else {
    lines.for_each_segment(add);
    if (work) *work = band_work(edges);
  }
  if (inside) {
    y_min = std::max(static_cast<int>(std::floor(y_lo)), 0);
    y_max = std::min(static_cast<int>(std::ceil(y_hi)), height);
  } else {
    row_range(edges, height, y_min, y_max);
  }
}

void detail::row_range(const std::vector<Edge>& edges, int height, int& y_min, int& y_max) {
  y_min = height;
  y_max = 0;
  for (const Edge& e : edges) {
    y_min = std::min(y_min, static_cast<int>(std::floor(e.y0)));
    y_max = std::max(y_max, static_cast<int>(std::ceil(e.y1)));
  }
  y_min = std::max(y_min, 0);
  y_max = std::min(y_max, height);
}

// All segments as edges, unclipped; horizontal ones kept apart (NonExterior needs both).
void detail::RasterizerImpl::build_unclipped_edges(const Polylines& lines) {
  edges_.clear();
  horizontals_.clear();
  for_each_finite_segment(lines, [&](Point p, Point q) {
    if (p.y == q.y) {
      if (p.x != q.x) horizontals_.push_back({p.x, p.y, q.x, q.y, 0.0, 0});
    } else if (q.y > p.y) {
      add_edge(edges_, p, q, 1);
    } else {
      add_edge(edges_, q, p, -1);
    }
  });
}

// Replaces the edges by the boundary pieces, clipped to the image.
void detail::RasterizerImpl::clip_pieces(int width, int height) {
  edges_.clear();
  for (const Edge& e : pieces_) {
    const Point top{e.x0, e.y0}, bottom{e.x1, e.y1};
    if (e.winding > 0) {
      add_clipped_segment(edges_, top, bottom, width, height);
    } else {
      add_clipped_segment(edges_, bottom, top, width, height);
    }
  }
  row_range(edges_, height, y_min_, y_max_);
}

// Edge table: a counting sort of the edges by the first row they take part in.
//  analytic: the row containing the edge's top, floor(y0);
//  aliased:  the first row whose sample line y = r + 0.5 the edge crosses, ceil(y0 - 0.5) (half-open [y0, y1)).
void detail::bucket_edges(const std::vector<Edge>& edges, int y_min, int y_max, bool by_sample_row,
                          std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& bucket_start,
                          BucketScratch& scratch) {
  const int rows = std::max(y_max - y_min, 0);
  bucket_start.assign(static_cast<std::size_t>(rows) + 2, 0);
  scratch.edge_row.resize(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const double y0 = edges[i].y0;
    const double r = by_sample_row ? std::ceil(y0 - 0.5) : std::floor(y0);
    const int row = std::clamp(static_cast<int>(r), y_min, y_max) - y_min;
    scratch.edge_row[i] = static_cast<std::uint32_t>(row);
    ++bucket_start[static_cast<std::size_t>(row) + 1];
  }
  // Prefix sums: bucket r holds order[bucket_start[r] .. bucket_start[r + 1]).
  for (std::size_t r = 1; r < bucket_start.size(); ++r) bucket_start[r] += bucket_start[r - 1];
  order.resize(edges.size());
  scratch.cursor.assign(bucket_start.begin(), bucket_start.end() - 1);
  for (std::uint32_t i = 0; i < edges.size(); ++i) order[scratch.cursor[scratch.edge_row[i]]++] = i;
}

}  // namespace vraster
