// The box of a list of points in one pass, SSE2 where there is SSE2 (part of x86-64).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

#include "vraster/geometry.hpp"

namespace vraster::detail {

// The box of the points, and whether they are all finite (the box means nothing when they are not): the glyph mask's
// rows and whether its points lie inside it (mask.cpp), the bound on a small fill's work (sweep.cpp), and
// Path::control_bounds (the canvas asks it twice per fill: its box, then flatten's clip test). With SSE2,
// an [x, y] pair at a time with two sets of running bounds: one minimum and maximum after another per point made
// chains of dependent instructions that took a tenth of a small glyph's time (and 1.5 % of a frame of small
// polygons on two threads).
struct PointBounds {
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;
  bool finite = true;
};

inline PointBounds point_bounds(const std::vector<Point>& points) {
  PointBounds b;
  if (points.empty()) return b;
#if defined(__SSE2__) || defined(_M_X64)
  static_assert(sizeof(Point) == 2 * sizeof(double));
  const double* xy = &points[0].x;
  const std::size_t n = points.size();
  __m128d lo0 = _mm_loadu_pd(xy), hi0 = lo0, lo1 = lo0, hi1 = lo0;
  __m128d bad = _mm_setzero_pd();  // all ones in a lane that saw an infinity or NaN (x - x is NaN only for those)
  auto take = [&](__m128d v, __m128d& lo, __m128d& hi) {
    lo = _mm_min_pd(lo, v);
    hi = _mm_max_pd(hi, v);
    const __m128d zero_if_finite = _mm_sub_pd(v, v);
    bad = _mm_or_pd(bad, _mm_cmpunord_pd(zero_if_finite, zero_if_finite));
  };
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    take(_mm_loadu_pd(xy + 2 * i), lo0, hi0);
    take(_mm_loadu_pd(xy + 2 * i + 2), lo1, hi1);
  }
  if (i < n) take(_mm_loadu_pd(xy + 2 * i), lo0, hi0);
  double lo[2], hi[2];
  _mm_storeu_pd(lo, _mm_min_pd(lo0, lo1));
  _mm_storeu_pd(hi, _mm_max_pd(hi0, hi1));
  b = {lo[0], hi[0], lo[1], hi[1], _mm_movemask_pd(bad) == 0};
#else
  b = {points[0].x, points[0].x, points[0].y, points[0].y, true};
  for (const Point& p : points) {
    b.x_lo = std::min(b.x_lo, p.x);
    b.x_hi = std::max(b.x_hi, p.x);
    b.y_lo = std::min(b.y_lo, p.y);
    b.y_hi = std::max(b.y_hi, p.y);
    b.finite = b.finite && std::isfinite(p.x) && std::isfinite(p.y);
  }
#endif
  return b;
}

}  // namespace vraster::detail
