// Cell accumulation shared by the analytic sweeps: pieces of edges inside one pixel row -> signed area deltas
// in cells -> a running sum per row -> coverage under a fill rule -> CoverageSink.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "vraster/raster.hpp"

namespace vraster::detail {

// Coverage from the accumulated signed area s (the winding number, averaged over the pixel).
// Exact where one pixel sees a single winding transition; an approximation where edges cross inside a pixel.
// Coverage this close to 0 or 1 is 0 or 1: round-off left by edges that cancel must not become coverage (it would
// cost spans and break exact invariance under translation). Far below the area of a 1e-6 x 1e-6 px shape.
constexpr double kSnap = 0x1p-43;

inline float snapped(double c) { return static_cast<float>(c < kSnap ? 0.0 : (c > 1.0 - kSnap ? 1.0 : c)); }

template <FillRule R>
inline float coverage_of(double s) {
  if constexpr (R == FillRule::EvenOdd) {
    // Fold |s| into [0, 2) (rarely needed: windings beyond 2 inside one pixel), then mirror (1, 2) onto (1, 0).
    double a = std::abs(s);
    if (a >= 2.0) a -= 2.0 * std::floor(a * 0.5);
    return snapped(a > 1.0 ? 2.0 - a : a);
  } else if constexpr (R == FillRule::Positive) {
    return snapped(std::clamp(s, 0.0, 1.0));
  } else if constexpr (R == FillRule::Negative) {
    return snapped(std::clamp(-s, 0.0, 1.0));
  } else if constexpr (R == FillRule::AbsGeq2) {
    return snapped(std::clamp(std::abs(s) - 1.0, 0.0, 1.0));
  } else {
    const double a = std::abs(s);
    return snapped(a < 1.0 ? a : 1.0);
  }
}

// Adds one straight piece of an edge inside a row to the accumulation cells. The piece runs between x = xa and
// x = xb (either order) and covers height h of the row (signed by winding). Cell i receives the part of h
// times the share of the cell right of the piece, cell i + 1 the rest; the running sum along the row is then the
// signed area of each pixel that lies right of the edge (the winding number averaged over the pixel).
inline void accumulate_piece(double* acc, double xa, double xb, double h) {
  if (xa > xb) std::swap(xa, xb);
  const int i0 = static_cast<int>(xa);
  const int i1 = static_cast<int>(xb);
  if (i0 == i1) {
    const double m = 0.5 * (xa + xb) - i0;
    acc[i0] += h * (1.0 - m);
    acc[i0 + 1] += h * m;
    return;
  }
  const double per_x = h / (xb - xa);
  // First, partial cell.
  const double f0 = (i0 + 1) - xa;
  const double h0 = per_x * f0;
  const double m0 = 1.0 - 0.5 * f0;  // mean x of the piece inside cell i0, relative to i0
  acc[i0] += h0 * (1.0 - m0);
  acc[i0 + 1] += h0 * m0;
  // Whole cells: the piece crosses each at mean x 0.5.
  const double half = 0.5 * per_x;
  for (int i = i0 + 1; i < i1; ++i) {
    acc[i] += half;
    acc[i + 1] += half;
  }
  // Last, partial cell.
  const double f1 = xb - i1;
  if (f1 > 0) {
    const double h1 = per_x * f1;
    const double m1 = 0.5 * f1;
    acc[i1] += h1 * (1.0 - m1);
    acc[i1 + 1] += h1 * m1;
  }
}

inline void mark_cells(std::uint64_t* bits, int from, int to) {  // inclusive range
  int w0 = from >> 6, w1 = to >> 6;
  const std::uint64_t first = ~std::uint64_t{0} << (from & 63);
  const std::uint64_t last = ~std::uint64_t{0} >> (63 - (to & 63));
  if (w0 == w1) {
    bits[w0] |= first & last;
    return;
  }
  bits[w0] |= first;
  for (int w = w0 + 1; w < w1; ++w) bits[w] = ~std::uint64_t{0};
  bits[w1] |= last;
}

// First set bit at or after `from`, or `limit` when there is none before it.
inline int next_set(const std::uint64_t* bits, int from, int limit) {
  int w = from >> 6;
  std::uint64_t word = bits[w] & (~std::uint64_t{0} << (from & 63));
  const int last_word = (limit - 1) >> 6;
  while (word == 0) {
    if (++w > last_word) return limit;
    word = bits[w];
  }
  return std::min((w << 6) + std::countr_zero(word), limit);
}

inline int next_clear(const std::uint64_t* bits, int from, int limit) {
  int w = from >> 6;
  std::uint64_t word = ~bits[w] & (~std::uint64_t{0} << (from & 63));
  const int last_word = (limit - 1) >> 6;
  while (word == 0) {
    if (++w > last_word) return limit;
    word = ~bits[w];
  }
  return std::min((w << 6) + std::countr_zero(word), limit);
}

// Untouched stretches shorter than this inside a run of touched cells are written into the run's coverage instead
// of being a span of their own: one compositor call covers several edges.
constexpr int kMergeGap = 24;

// Sweeps one accumulated row: a running sum over touched cells, constant spans over long untouched stretches.
// Leaves the accumulation cells and the touched bits zero.
template <FillRule R>
[[gnu::always_inline]] inline void resolve_row(int y, int width, int x_lo, int x_hi, double* acc, std::uint64_t* bits, float* cov,
                 CoverageSink& sink) {
  double sum = 0;
  int x = x_lo;
  int run = -1;  // first pixel of the open coverage run (cov[i - run] is pixel i), -1 when none is open
  const int limit = x_hi + 1;
  auto flush = [&](int end) {
    end = std::min(end, width);
    int a = run, b = end;
    while (a < b && cov[a - run] == 0) ++a;
    while (b > a && cov[b - 1 - run] == 0) --b;
    if (b - a == 1) {
      sink.span(y, a, b, cov[a - run]);
    } else if (b > a) {
      sink.row(y, a, b, cov + (a - run));
    }
    run = -1;
  };
  for (;;) {
    const int t = x >= limit ? limit : next_set(bits, x, limit);
    // Untouched cells [x, gap_end) keep the running sum; past the last touched cell that holds to the end of the
    // row (edges right of the image were dropped, so the sum need not return to 0 there).
    const int gap_end = t >= limit ? width : std::min(t, width);
    if (gap_end > x) {
      const float c = coverage_of<R>(sum);
      if (run >= 0 && t < limit && t - x <= kMergeGap && t <= width) {
        std::fill(cov + (x - run), cov + (t - run), c);
      } else {
        if (run >= 0) flush(x);
        if (c > 0) sink.span(y, x, gap_end, c);
      }
    }
    if (t >= limit) break;
    const int e = next_clear(bits, t, limit);
    if (run < 0) run = t;
    for (int i = t; i < e; ++i) {
      sum += acc[i];
      acc[i] = 0;
      cov[i - run] = coverage_of<R>(sum);
    }
    x = e;
  }
  if (run >= 0) flush(x);
  for (int w = x_lo >> 6; w <= (x_hi >> 6); ++w) bits[w] = 0;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VRASTER_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define VRASTER_CLONES
#endif

// Calls f with the fill rule as a compile-time constant, so the per-cell coverage function (and
// any other per-rule test) is chosen once per fill.
template <class F>
void with_rule(FillRule rule, F&& f) {
  switch (rule) {
    case FillRule::EvenOdd: return f(std::integral_constant<FillRule, FillRule::EvenOdd>{});
    case FillRule::Positive: return f(std::integral_constant<FillRule, FillRule::Positive>{});
    case FillRule::Negative: return f(std::integral_constant<FillRule, FillRule::Negative>{});
    case FillRule::AbsGeq2: return f(std::integral_constant<FillRule, FillRule::AbsGeq2>{});
    case FillRule::NonZero:
    case FillRule::NonExterior: return f(std::integral_constant<FillRule, FillRule::NonZero>{});
  }
}

}  // namespace vraster::detail
