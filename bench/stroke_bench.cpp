// vraster_stroke_bench: (1) hairline algorithms in lines per second (random lines of 1..500 px on 1024x1024);
// (2) stroking the shared benchmark scenes (every path stroked with one style) against Cairo, median ms/frame.
//
// Usage: vraster_stroke_bench [--frames N] [--scenes DIR] [--no-hairlines] [scene names...]
// A frame = clear + stroke every item (vraster: stroke_path = stroker + non-zero analytic fill; Cairo:
// cairo_append_path + cairo_stroke with the same width, cap, join, tolerance 0.1) + flush.
#include <cairo.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "svg_subset/svg.hpp"
#include "vraster/lines.hpp"
#include "vraster/renderer.hpp"
#include "vraster/stroke.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using vraster::Point;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// ---- (1) hairlines ----

struct Line {
  Point p, q;
};

std::vector<Line> random_lines(int n, int size) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> pos(0, size), len(1, 500), ang(0, 2 * 3.14159265358979323846);
  std::vector<Line> out;
  while (static_cast<int>(out.size()) < n) {
    const Point p{pos(rng), pos(rng)};
    const double l = len(rng), a = ang(rng);
    const Point q{p.x + l * std::cos(a), p.y + l * std::sin(a)};
    if (q.x < 0 || q.y < 0 || q.x >= size || q.y >= size) continue;  // keep every line fully visible
    out.push_back({p, q});
  }
  return out;
}

template <class F>
double best_of(int reps, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    f();
    t.push_back(ms_since(t0));
  }
  return median(t);
}

void bench_hairlines() {
  const int size = 1024, n = 20000;
  const auto lines = random_lines(n, size);
  double total_len = 0;
  for (const Line& l : lines) total_len += std::max(std::fabs(l.q.x - l.p.x), std::fabs(l.q.y - l.p.y));
  vraster::Image img(size, size);
  const vraster::Color c{0, 0, 0, 0.5f};
  vraster::PixelBlender blender(img, c);
  auto ip = [](Point p) { return vraster::IPoint{static_cast<int>(p.x), static_cast<int>(p.y)}; };
  std::printf("hairlines: %d random lines of 1..500 px (mean %.0f px along the major axis) on %dx%d, alpha 0.5\n", n,
              total_len / n, size, size);
  std::printf("%-34s %10s %12s %14s\n", "algorithm", "ms", "lines/s", "pixels/s");
  auto report = [&](const char* name, double ms) {
    std::printf("%-34s %10.2f %12.0f %14.3g\n", name, ms, n / (ms / 1000), total_len / (ms / 1000));
  };
  long sink = 0;
  report("bresenham (count pixels only)", best_of(5, [&] {
    for (const Line& l : lines) vraster::bresenham_line(ip(l.p), ip(l.q), size, size, vraster::LineEnd::Closed, [&](int x, int y) { sink += x ^ y; });
  }));
  report("dda (count pixels only)", best_of(5, [&] {
    for (const Line& l : lines) vraster::dda_line(ip(l.p), ip(l.q), size, size, vraster::LineEnd::Closed, [&](int x, int y) { sink += x ^ y; });
  }));
  report("bresenham + blend", best_of(5, [&] {
    for (const Line& l : lines) vraster::bresenham_line(ip(l.p), ip(l.q), size, size, vraster::LineEnd::Closed, [&](int x, int y) { blender.blend_full(x, y); });
  }));
  report("dda + blend", best_of(5, [&] {
    for (const Line& l : lines) vraster::dda_line(ip(l.p), ip(l.q), size, size, vraster::LineEnd::Closed, [&](int x, int y) { blender.blend_full(x, y); });
  }));
  report("wu + blend", best_of(5, [&] {
    for (const Line& l : lines) vraster::wu_line(l.p, l.q, size, size, [&](int x, int y, float cov) { blender.blend(x, y, cov); });
  }));
  // Through the public hairline entry point: one path holding every line as a subpath.
  vraster::Path all;
  for (const Line& l : lines) all.move_to(l.p).line_to(l.q);
  for (auto mode : {vraster::HairlineMode::Bresenham, vraster::HairlineMode::Dda, vraster::HairlineMode::Wu,
                    vraster::HairlineMode::Analytic}) {
    const std::string name = std::string("draw_hairlines ") + std::string(vraster::to_string(mode));
    report(name.c_str(), best_of(5, [&] { vraster::draw_hairlines(img, all, vraster::Affine{}, c, mode); }));
  }
  if (sink == 42) std::printf(" ");
}

// ---- (2) stroking scenes ----

struct Scene {
  std::string name;
  vraster::svg::Document doc;
};

void append_cairo_path(cairo_t* cr, const vraster::Path& path, const vraster::Affine& m) {
  const auto pts = path.points();
  std::size_t i = 0;
  Point cur{};
  for (vraster::Verb v : path.verbs()) {
    switch (v) {
      case vraster::Verb::Move: cur = m.apply(pts[i++]); cairo_move_to(cr, cur.x, cur.y); break;
      case vraster::Verb::Line: cur = m.apply(pts[i++]); cairo_line_to(cr, cur.x, cur.y); break;
      case vraster::Verb::Quad: {
        const Point q = m.apply(pts[i]), e = m.apply(pts[i + 1]);
        const Point c1 = cur + (q - cur) * (2.0 / 3), c2 = e + (q - e) * (2.0 / 3);
        cairo_curve_to(cr, c1.x, c1.y, c2.x, c2.y, e.x, e.y);
        cur = e;
        i += 2;
        break;
      }
      case vraster::Verb::Cubic: {
        const Point a = m.apply(pts[i]), b = m.apply(pts[i + 1]), e = m.apply(pts[i + 2]);
        cairo_curve_to(cr, a.x, a.y, b.x, b.y, e.x, e.y);
        cur = e;
        i += 3;
        break;
      }
      case vraster::Verb::Close: cairo_close_path(cr); break;
    }
  }
}

void bench_scene(const Scene& s, const vraster::StrokeStyle& style, const char* style_name, int frames) {
  const int w = s.doc.width, h = s.doc.height;
  // vraster: the items are stroked in device space here (their transforms are identity or uniform in these
  // scenes); stroke_path does stroke_to_path + transform + non-zero fill per item.
  vraster::Image img(w, h);
  vraster::Renderer renderer;
  vraster::StrokeRenderOptions options;
  options.renderer = &renderer;
  std::vector<double> tv, ts;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    img.clear(vraster::Color{1, 1, 1, 1});
    for (const auto& item : s.doc.items) vraster::stroke_path(img, item.path, item.transform, style, item.color, options);
    tv.push_back(ms_since(t0));
    // Stroker alone (outline construction, no rasterization).
    const auto t1 = Clock::now();
    std::size_t pts = 0;
    for (const auto& item : s.doc.items) pts += vraster::stroke_to_path(item.path, style, 0.1).points().size();
    ts.push_back(ms_since(t1));
    if (pts == 1) std::printf(" ");
  }
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  cairo_t* cr = cairo_create(surface);
  cairo_set_tolerance(cr, 0.1);
  cairo_set_line_width(cr, style.width);
  cairo_set_line_cap(cr, style.cap == vraster::LineCap::Butt ? CAIRO_LINE_CAP_BUTT
                         : style.cap == vraster::LineCap::Round ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_SQUARE);
  cairo_set_line_join(cr, style.join == vraster::LineJoin::Miter ? CAIRO_LINE_JOIN_MITER
                          : style.join == vraster::LineJoin::Round ? CAIRO_LINE_JOIN_ROUND : CAIRO_LINE_JOIN_BEVEL);
  cairo_set_miter_limit(cr, style.miter_limit);
  if (!style.dashes.empty()) cairo_set_dash(cr, style.dashes.data(), static_cast<int>(style.dashes.size()), style.dash_offset);
  // Paths are built once (device space), as the fill benchmark does; the stroker runs every frame.
  std::vector<cairo_path_t*> paths;
  for (const auto& item : s.doc.items) {
    cairo_new_path(cr);
    append_cairo_path(cr, item.path, item.transform);
    paths.push_back(cairo_copy_path(cr));
  }
  cairo_new_path(cr);
  std::vector<double> tc;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const auto& col = s.doc.items[i].color;
      cairo_set_source_rgba(cr, col.r, col.g, col.b, col.a);
      cairo_append_path(cr, paths[i]);
      cairo_stroke(cr);
    }
    cairo_surface_flush(surface);
    tc.push_back(ms_since(t0));
  }
  for (cairo_path_t* p : paths) cairo_path_destroy(p);
  cairo_destroy(cr);
  cairo_surface_destroy(surface);
  const double v = median(tv), c = median(tc);
  std::printf("%-16s %-22s %9.2f %9.2f %9.2f %8.2f\n", s.name.c_str(), style_name, median(ts), v, c, c / v);
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 7;
  bool hairlines = true;
  std::string dir = std::string(VRASTER_SOURCE_DIR) + "/../shared/bench/scenes";
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--scenes") && i + 1 < argc) dir = argv[++i];
    else if (!std::strcmp(argv[i], "--no-hairlines")) hairlines = false;
    else names.push_back(argv[i]);
  }
  if (names.empty()) names = {"poly10_16", "poly10_64", "cubic_16", "cubic_64", "text_outlines"};
  std::printf("vraster_stroke_bench (Cairo %s), %d frames, medians\n\n", cairo_version_string(), frames);
  if (hairlines) bench_hairlines();

  std::printf("\nstroking scenes: every path stroked; ms per frame (clear + stroke all + flush)\n");
  std::printf("%-16s %-22s %9s %9s %9s %8s\n", "scene", "style", "outline", "vraster", "cairo", "cairo/v");
  vraster::StrokeStyle solid;
  solid.width = 2;
  solid.join = vraster::LineJoin::Round;
  solid.cap = vraster::LineCap::Round;
  vraster::StrokeStyle miter;
  miter.width = 4;
  miter.join = vraster::LineJoin::Miter;
  vraster::StrokeStyle dashed = solid;
  dashed.dashes = {6, 3};
  dashed.cap = vraster::LineCap::Butt;
  for (const std::string& n : names) {
    Scene s;
    s.name = n;
    try {
      s.doc = vraster::svg::load_svg(dir + "/" + n + ".svg");
      // The scenes' fill outlines are what gets stroked here (with the styles below): drop the file's own strokes.
      std::erase_if(s.doc.items, [](const vraster::svg::DrawItem& item) { return !item.is_fill(); });
    } catch (const std::exception& e) {
      std::printf("%-16s skipped: %s\n", n.c_str(), e.what());
      continue;
    }
    bench_scene(s, solid, "w2 round/round", frames);
    bench_scene(s, miter, "w4 miter/butt", frames);
    bench_scene(s, dashed, "w2 dash 6,3 round", frames);
  }
  return 0;
}
