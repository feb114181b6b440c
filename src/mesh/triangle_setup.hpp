// Triangle setup shared by the mesh renderer and rasterize_triangle(): snapping, edge functions with the top-left
// rule, guard-band clipping, and the per-row spans of covered pixel centres.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "vraster/geometry.hpp"
#include "vraster/mesh.hpp"

namespace vraster::mesh_detail {

/// Coordinates in 1/256 px (kMeshSubpixelBits), exact in 64-bit products within the guard band.
using Fixed = std::int64_t;
inline constexpr Fixed kOne = Fixed{1} << kMeshSubpixelBits;
inline constexpr Fixed kHalf = kOne / 2;
/// Triangles with a coordinate beyond this are not drawn (their barycentric weights would lose all precision).
inline constexpr double kMeshCoordLimit = 1e12;

inline Fixed snap(double v) { return static_cast<Fixed>(std::llround(v * static_cast<double>(kOne))); }

inline Fixed floor_div(Fixed a, Fixed b) {  // b > 0
  const Fixed q = a / b;
  return (a % b != 0 && (a < 0)) ? q - 1 : q;
}
inline Fixed ceil_div(Fixed a, Fixed b) {  // b > 0
  const Fixed q = a / b;
  return (a % b != 0 && (a > 0)) ? q + 1 : q;
}

/// A snapped triangle: E_i(x, y) = a[i] x + b[i] y + c[i] (x, y in Fixed) is the edge function of the edge opposite
/// vertex i, oriented positive inside; a centre is covered when E_i >= bias[i] for all i (bias 0 on owned edges).
struct SnappedTriangle {
  Fixed a[3], b[3], c[3], bias[3];
  int x0, y0, x1, y1;  // pixels whose centres may be covered, clipped to the target: [x0, x1) x [y0, y1)

  /// False for a degenerate triangle or one with no pixel centre in [0, width) x [0, height).
  bool setup(const Fixed x[3], const Fixed y[3], int width, int height) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      a[i] = y[j] - y[k];
      b[i] = x[k] - x[j];
      c[i] = x[j] * y[k] - x[k] * y[j];
    }
    const Fixed area2 = a[0] * x[0] + b[0] * y[0] + c[0];
    if (area2 == 0) return false;
    for (int i = 0; i < 3; ++i) {
      if (area2 < 0) a[i] = -a[i], b[i] = -b[i], c[i] = -c[i];
      // Top-left rule: the gradient (a, b) points inside; a left edge has the inside on its right (a > 0), a top
      // edge is horizontal with the inside below (a == 0, b > 0). Those own the centres on them.
      bias[i] = (a[i] > 0 || (a[i] == 0 && b[i] > 0)) ? 0 : 1;
    }
    const Fixed min_x = std::min({x[0], x[1], x[2]}), max_x = std::max({x[0], x[1], x[2]});
    const Fixed min_y = std::min({y[0], y[1], y[2]}), max_y = std::max({y[0], y[1], y[2]});
    // Pixel p has its centre at p * kOne + kHalf.
    x0 = static_cast<int>(std::max<Fixed>(0, ceil_div(min_x - kHalf, kOne)));
    x1 = static_cast<int>(std::min<Fixed>(width, floor_div(max_x - kHalf, kOne) + 1));
    y0 = static_cast<int>(std::max<Fixed>(0, ceil_div(min_y - kHalf, kOne)));
    y1 = static_cast<int>(std::min<Fixed>(height, floor_div(max_y - kHalf, kOne) + 1));
    return x0 < x1 && y0 < y1;
  }

  /// Edge function i at the centre of pixel (0, py), and its step per pixel to the right.
  Fixed row_start(int i, int py) const { return a[i] * kHalf + b[i] * (Fixed{py} * kOne + kHalf) + c[i]; }
  Fixed step(int i) const { return a[i] * kOne; }

  /// Incremental form: each row's covered pixels solved from the three edge functions (no per-pixel tests).
  template <class F>
  void for_each_span(F&& span) const {
    for (int py = y0; py < y1; ++py) {
      Fixed lo = x0, hi = x1 - 1;
      for (int i = 0; i < 3 && lo <= hi; ++i) {
        const Fixed e0 = row_start(i, py), s = step(i);  // E(px) = e0 + s * px >= bias
        if (s > 0) {
          lo = std::max(lo, ceil_div(bias[i] - e0, s));
        } else if (s < 0) {
          hi = std::min(hi, floor_div(e0 - bias[i], -s));
        } else if (e0 < bias[i]) {
          hi = lo - 1;
        }
      }
      if (lo <= hi) span(py, static_cast<int>(lo), static_cast<int>(hi + 1));
    }
  }

  /// Bounding-box form: every centre of the box tested, the edge functions stepped by one addition per pixel.
  template <class F>
  void for_each_span_bbox(F&& span) const {
    for (int py = y0; py < y1; ++py) {
      Fixed e[3];
      for (int i = 0; i < 3; ++i) e[i] = row_start(i, py) + step(i) * x0;
      int run = -1;
      for (int px = x0; px < x1; ++px) {
        const bool in = e[0] >= bias[0] && e[1] >= bias[1] && e[2] >= bias[2];
        if (in && run < 0) run = px;
        if (!in && run >= 0) span(py, run, px), run = -1;
        for (int i = 0; i < 3; ++i) e[i] += step(i);
      }
      if (run >= 0) span(py, run, x1);
    }
  }
};

/// The part of a triangle inside the guard band [-kMeshGuard, kMeshGuard]^2 (Sutherland-Hodgman), at most 7 points.
/// Each cut point is computed from the segment's endpoints in a fixed order, so two triangles sharing an edge cut it
/// at the same point.
inline int clip_to_guard(const Point in[3], Point out[9]) {
  Point buf_a[9], buf_b[9];
  int n = 3;
  std::copy(in, in + 3, buf_a);
  Point* src = buf_a;
  Point* dst = buf_b;
  for (int side = 0; side < 4; ++side) {
    auto value = [side](Point p) {  // >= 0 inside this side of the band
      switch (side) {
        case 0: return p.x + kMeshGuard;
        case 1: return kMeshGuard - p.x;
        case 2: return p.y + kMeshGuard;
        default: return kMeshGuard - p.y;
      }
    };
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const Point p = src[i], q = src[(i + 1) % n];
      const double vp = value(p), vq = value(q);
      if (vp >= 0) dst[m++] = p;
      if ((vp >= 0) != (vq >= 0)) {
        const bool p_first = p.x < q.x || (p.x == q.x && p.y < q.y);
        const Point s = p_first ? p : q, e = p_first ? q : p;
        const double vs = p_first ? vp : vq, ve = p_first ? vq : vp;
        const double t = vs / (vs - ve);
        dst[m++] = Point{s.x + (e.x - s.x) * t, s.y + (e.y - s.y) * t};
      }
    }
    n = m;
    std::swap(src, dst);
    if (n == 0) return 0;
  }
  std::copy(src, src + n, out);
  return n;
}

/// Calls span(y, x0, x1) for the centres the triangle (a, b, c) covers inside [0, width) x [0, height): snapped,
/// clipped to the guard band when needed (the clipped polygon is fanned; its inner edges are shared, so the top-left
/// rule keeps every centre once). `bbox_form` forces the bounding-box scan.
template <class F>
void cover_triangle(const Point v[3], int width, int height, bool bbox_form, F&& span) {
  bool inside_guard = true;
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(v[i].x) <= kMeshCoordLimit && std::abs(v[i].y) <= kMeshCoordLimit)) return;  // NaN too
    inside_guard = inside_guard && std::abs(v[i].x) <= kMeshGuard && std::abs(v[i].y) <= kMeshGuard;
  }
  auto cover = [&](Point p, Point q, Point r) {
    const Fixed x[3] = {snap(p.x), snap(q.x), snap(r.x)}, y[3] = {snap(p.y), snap(q.y), snap(r.y)};
    SnappedTriangle t;
    if (!t.setup(x, y, width, height)) return;
    // Small boxes: the box scan is cheaper than solving three edges per row.
    if (bbox_form || (t.x1 - t.x0) <= 8) {
      t.for_each_span_bbox(span);
    } else {
      t.for_each_span(span);
    }
  };
  if (inside_guard) {
    cover(v[0], v[1], v[2]);
    return;
  }
  Point poly[9];
  const int n = clip_to_guard(v, poly);
  for (int i = 1; i + 1 < n; ++i) cover(poly[0], poly[i], poly[i + 1]);
}

}  // namespace vraster::mesh_detail
