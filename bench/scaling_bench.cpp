// vraster_scaling_bench: does the rasterizer's time grow linearly with the number of segments? (Timings belong
// here, not in the unit tests, where a loaded machine makes them flaky; tests/hard_cases_test.cpp checks that the
// same paths come out right.)
//
// Two polygons, each at n and 10 n segments (--quick: n / 10 and n), filled into a 33 x 32 image:
//   smooth: a wobbly circle (simple, star-shaped), analytic non-zero, exact non-zero, exact non-exterior
//   zigzag: the same with alternate vertices moved in and out, so nearly every vertex is a y-extremum and hundreds
//           of edges cross each row (what made the boundary sweep quadratic before 82f4180), exact non-exterior
// and Cairo filling the same polygons (non-zero) as the peer in the same run. Prints the best-of-3 CPU time of each
// and the ratio t(10 n) / t(n): linear growth gives about 10, quadratic about 100.
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <numbers>
#include <string>

#include "vraster/vraster.hpp"

using namespace vraster;

namespace {

Polylines wobbly_circle(int n, bool zigzag) {
  Polylines lines;
  lines.points.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    const double r = 14 + 0.3 * std::sin(37.0 * a) + (zigzag ? 0.2 * ((i & 1) ? 1 : -1) : 0.0);
    lines.points.push_back({16.2 + r * std::cos(a), 15.9 + r * std::sin(a)});
  }
  lines.ends.push_back(static_cast<std::uint32_t>(n));
  lines.closed.push_back(1);
  return lines;
}

class NullSink final : public CoverageSink {
 public:
  void span(int, int, int, float c) override { sum += c; }
  void row(int, int x0, int x1, const float* c) override {
    for (int x = x0; x < x1; ++x) sum += c[x - x0];
  }
  double sum = 0;
};

double cpu_seconds(const std::function<void()>& f) {
  double best = 1e300;
  for (int k = 0; k < 3; ++k) {
    const std::clock_t t0 = std::clock();
    f();
    best = std::min(best, static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC);
  }
  return best;
}

void vraster_fill(const Polylines& lines, FillRule rule, AntiAlias aa) {
  Rasterizer r;
  NullSink sink;
  r.fill(lines, rule, aa, 33, 32, sink);
}

void cairo_fill(const Polylines& lines) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_A8, 33, 32);
  cairo_t* cr = cairo_create(s);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
  cairo_move_to(cr, lines.points[0].x, lines.points[0].y);
  for (std::size_t i = 1; i < lines.points.size(); ++i) cairo_line_to(cr, lines.points[i].x, lines.points[i].y);
  cairo_close_path(cr);
  cairo_fill(cr);
  cairo_surface_flush(s);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
}

void row(const char* name, int n, const std::function<void(const Polylines&)>& fill, bool zigzag) {
  const Polylines small = wobbly_circle(n, zigzag), big = wobbly_circle(10 * n, zigzag);
  const double t_small = cpu_seconds([&] { fill(small); }), t_big = cpu_seconds([&] { fill(big); });
  std::printf("%-28s n=%-8d %9.4f s   10n=%-8d %9.4f s   ratio %6.1f\n", name, n, t_small, 10 * n, t_big,
              t_big / std::max(t_small, 1e-9));
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int smooth_n = quick ? 10000 : 100000, zigzag_n = quick ? 1000 : 10000;
  std::printf("CPU time, best of 3; ratio = t(10n) / t(n) (linear: ~10, quadratic: ~100)\n");
  row("smooth analytic nonzero", smooth_n, [](const Polylines& l) { vraster_fill(l, FillRule::NonZero, AntiAlias::Analytic); }, false);
  row("smooth exact nonzero", smooth_n, [](const Polylines& l) { vraster_fill(l, FillRule::NonZero, AntiAlias::Exact); }, false);
  row("smooth exact nonexterior", smooth_n, [](const Polylines& l) { vraster_fill(l, FillRule::NonExterior, AntiAlias::Exact); }, false);
  row("smooth cairo nonzero (peer)", smooth_n, [](const Polylines& l) { cairo_fill(l); }, false);
  row("zigzag exact nonzero", zigzag_n, [](const Polylines& l) { vraster_fill(l, FillRule::NonZero, AntiAlias::Exact); }, true);
  row("zigzag exact nonexterior", zigzag_n, [](const Polylines& l) { vraster_fill(l, FillRule::NonExterior, AntiAlias::Exact); }, true);
  row("zigzag cairo nonzero (peer)", zigzag_n, [](const Polylines& l) { cairo_fill(l); }, true);
  return 0;
}
