// Axis-aligned rectangles without a sweep: the coverage of such a path is the same in every row strictly inside it,
// so it is computed for at most three rows (the partial top row, one inside row, the partial bottom row), each with
// the same arithmetic as the sweep of its mode, and replayed: the inside of every row goes to the sink as one
// full-coverage span, only the border pixels as a row. A full-frame fill becomes one store per row.
//
// "The same arithmetic": the analytic cells are accumulated exactly as accumulate_piece does for the two vertical
// edges (same products, same sums, in the same grouping), the aliased and point-sampled modes count the same
// sample positions with the same ceil() tests, so the coverage is bit for bit the sweep's (tests/rect_fill_test.cpp).
#include "raster/rect.hpp"

#include <algorithm>
#include <cmath>

#include "raster/cells.hpp"
#include "raster/rasterizer_p.hpp"
#include "raster/supersample.hpp"

namespace vraster {

bool detail::axis_aligned_rectangle(const Polylines& lines, Rect& box, int& winding) {
  if (lines.contour_count() != 1) return false;
  const auto pts = lines.contour(0);
  Point corner[5];
  int n = 0;
  for (const Point& p : pts) {
    if (n > 0 && p == corner[n - 1]) continue;
    if (n == 5) return false;
    corner[n++] = p;
  }
  if (n == 5 && corner[4] == corner[0]) n = 4;
  if (n != 4) return false;
  for (int i = 0; i < 4; ++i) {
    if (!std::isfinite(corner[i].x) || !std::isfinite(corner[i].y)) return false;
  }
  // Sides alternate horizontal and vertical (so no side is both, and the area is not zero).
  const bool first_horizontal = corner[0].y == corner[1].y;
  for (int i = 0; i < 4; ++i) {
    const Point a = corner[i], b = corner[(i + 1) % 4];
    const bool horizontal = a.y == b.y, vertical = a.x == b.x;
    if (horizontal == vertical || horizontal != (first_horizontal == (i % 2 == 0))) return false;
  }
  box = Rect::from_point(corner[0]);
  for (int i = 1; i < 4; ++i) box.include(corner[i]);
  // The inside winds like the left side: +1 when it runs down.
  for (int i = 0; i < 4; ++i) {
    const Point a = corner[i], b = corner[(i + 1) % 4];
    if (a.x == box.x0 && b.x == box.x0) winding = b.y > a.y ? 1 : -1;
  }
  return true;
}

namespace {

// One row's coverage and how it is replayed: pixels [x, x + n) with coverage cov[0 .. n) (zero ends trimmed), of
// which [mid0, mid1) (relative to x) is one constant value sent as a span, the rest as rows.
struct RowPlan {
  int x = 0, n = 0, mid0 = 0, mid1 = 0;
  float* cov = nullptr;

  void plan() {
    int a = 0, b = n;
    while (a < b && cov[a] == 0) ++a;
    while (b > a && cov[b - 1] == 0) --b;
    x += a;
    cov += a;
    n = b - a;
    // The longest run of one value (the inside of the rectangle; a border pixel where nothing is wider).
    mid0 = mid1 = 0;
    for (int i = 0; i < n;) {
      int j = i + 1;
      while (j < n && cov[j] == cov[i]) ++j;
      if (j - i > mid1 - mid0) {
        mid0 = i;
        mid1 = j;
      }
      i = j;
    }
  }

  void emit(int y, CoverageSink& sink) const {
    auto part = [&](int a, int b) {
      if (b - a == 1) {
        if (cov[a] > 0) sink.span(y, x + a, x + b, cov[a]);
      } else if (b > a) {
        sink.row(y, x + a, x + b, cov + a);
      }
    };
    if (n <= 0) return;
    part(0, mid0);
    if (cov[mid0] > 0) sink.span(y, x + mid0, x + mid1, cov[mid0]);
    part(mid1, n);
  }
};

}  // namespace

bool detail::RasterizerImpl::fill_rect(const Polylines& lines, FillRule rule, AntiAlias aa, int width, int height,
                                       CoverageSink& sink, CoverageRecording* recording) {
  Rect r;
  int winding = 0;
  // Switched off (tests compare), or exact fills told to take the boundary sweep: the general path.
  if (!rect_shortcut_ || (aa == AntiAlias::Exact && !exact_shortcut_)) return false;
  if (!axis_aligned_rectangle(lines, r, winding)) return false;
  if (rule == FillRule::NonExterior) rule = FillRule::NonZero;  // a rectangle's inside is all it encloses
  if (!winding_fills(rule, winding)) return true;
  // The edges as the sweep sees them after clipping: the left side moves to x = 0 when left of the image (parts
  // right of it change no pixel, so the right side may stop at x = width), top and bottom are cut at 0 and height.
  const double xl = std::max(r.x0, 0.0), xr = std::min(r.x1, static_cast<double>(width));
  const double yt = std::max(r.y0, 0.0), yb = std::min(r.y1, static_cast<double>(height));
  if (!(xr > xl && yb > yt)) return true;

  // Pixels a row can touch: [px0, px1).
  const int px0 = static_cast<int>(xl);
  const int px1 = std::min(static_cast<int>(xr) + 2, width);
  const int n = px1 - px0;
  const std::size_t stride = static_cast<std::size_t>(n);
  if (rect_coverage_.size() < 3 * stride) rect_coverage_.resize(3 * stride);
  const SamplePattern pattern = sample_pattern(aa);
  const bool analytic = pattern.grid == 0 && aa != AntiAlias::None;  // Analytic, or Exact (analytic is exact here)
  if (analytic && rect_cells_.size() < stride + 2) rect_cells_.assign(stride + 2, 0.0);

  // The coverage of row y into cov[0 .. n) for pixels px0 ..
  auto coverage_row = [&](int y, float* cov) {
    if (analytic) {
      // accumulate_piece for the two vertical edges, then the running sum (cells relative to px0).
      const double top = y, bottom = y + 1.0;
      const double h = (std::min(yb, bottom) - std::max(yt, top)) * winding;
      double* cell = rect_cells_.data() - px0;
      const int i0 = static_cast<int>(xl), i1 = static_cast<int>(xr);
      const double m0 = xl - i0, m1 = xr - i1;
      cell[i0] += h * (1.0 - m0);
      cell[i0 + 1] += h * m0;
      cell[i1] += -h * (1.0 - m1);
      cell[i1 + 1] += -h * m1;
      // The running sum changes only at those four cells (adding an untouched cell's 0 changes no bit): coverage
      // is computed there, and the stretches between them are filled with the value they hold.
      int touched[4] = {i0, i0 + 1, i1, i1 + 1};
      std::sort(touched, touched + 4);
      with_rule(rule, [&](auto rc) {
        double sum = 0;
        float c = 0;
        int x = px0;
        for (int k = 0; k < 4; ++k) {
          const int t = touched[k];
          if (t >= px1 || (k > 0 && t == touched[k - 1])) continue;
          std::fill(cov + (x - px0), cov + (t - px0), c);
          sum += cell[t];
          c = coverage_of<decltype(rc)::value>(sum);
          cov[t - px0] = c;
          x = t + 1;
        }
        std::fill(cov + (x - px0), cov + n, c);
      });
      cell[i0] = cell[i0 + 1] = cell[i1] = cell[i1 + 1] = 0;
      return;
    }
    std::fill(cov, cov + n, 0.f);
    if (pattern.grid == 0) {  // aliased: the pixel centres, rows with y0 <= y + 0.5 < y1
      const double sample = y + 0.5;
      if (!(yt <= sample && sample < yb)) return;
      const int a = std::max(static_cast<int>(std::ceil(xl - 0.5)), 0), b = std::min(static_cast<int>(std::ceil(xr - 0.5)), width);
      for (int p = a; p < b; ++p) cov[p - px0] = 1;
      return;
    }
    // Point-sampled: count the samples inside, sub-row by sub-row, as sweep_sampled does.
    const int g = pattern.grid;
    const double inv_n = 1.0 / g;
    const float per_sample = 1.0f / static_cast<float>(pattern.samples());
    const auto perm = pattern.permutation();
    for (int j = 0; j < g; ++j) {
      const double ys = y + (j + 0.5) * inv_n;
      if (!(yt <= ys && ys < yb)) continue;
      if (pattern.sparse) {
        const double offset = (perm[j] + 0.5) * inv_n;
        const int a = static_cast<int>(std::clamp(std::ceil(xl - offset), 0.0, double(width)));
        const int b = static_cast<int>(std::clamp(std::ceil(xr - offset), 0.0, double(width)));
        for (int p = a; p < b; ++p) cov[p - px0] += per_sample;
      } else {
        const double limit = static_cast<double>(width) * g;
        const auto c0 = static_cast<std::int64_t>(std::clamp(std::ceil(xl * g - 0.5), 0.0, limit));
        const auto c1 = static_cast<std::int64_t>(std::clamp(std::ceil(xr * g - 0.5), 0.0, limit));
        for (int p = px0; p < px1; ++p) {
          const std::int64_t base = static_cast<std::int64_t>(p) * g;
          const std::int64_t k = std::clamp<std::int64_t>(c1 - base, 0, g) - std::clamp<std::int64_t>(c0 - base, 0, g);
          cov[p - px0] += static_cast<float>(k) * per_sample;
        }
      }
    }
  };
  // Sample counts are summed as floats above, k / samples per sub-row: every partial sum is a multiple of
  // 1 / samples below 1, exact in float, so the total equals the sweep's count * per_sample.

  // Rows strictly inside [yt, yb) all look alike; at most the first and the last differ.
  const int y0 = static_cast<int>(yt), y1 = static_cast<int>(std::ceil(yb));
  sink.expect(y0, y1, px0, px1);  // the rows' pixels come in together instead of one row after another
  RowPlan plans[3];
  bool made[3] = {false, false, false};
  for (int y = y0; y < y1; ++y) {
    const int kind = y + 1.0 <= yb && y >= yt ? 1 : (y == y0 ? 0 : 2);
    RowPlan& p = plans[kind];
    if (!made[kind]) {
      p.x = px0;
      p.n = n;
      p.cov = rect_coverage_.data() + kind * stride;
      coverage_row(y, p.cov);
      p.plan();
      made[kind] = true;
    }
    p.emit(y, sink);
    if (kind == 1 && recording) {
      // The rows up to the last inside one (y + 1 <= yb) are this one again.
      const int inside_end = static_cast<int>(yb);
      recording->repeat_row(y, inside_end);
      y = inside_end - 1;
    }
  }
  return true;
}

}  // namespace vraster
