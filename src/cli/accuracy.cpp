// vraster accuracy: every antialiasing method on a set of scenes, time against error.
//
//   1. scenes: the given SVG files, or by default the shared benchmark scenes plus built-in hard cases
//      (downscaled so the longer side is at most --max-side px)
//   2. per scene and method:
//        time:     median ms per frame of the real render path (clear + svg::render [+ fxaa]), a few frames
//        coverage: every item filled in opaque white into a float alpha buffer, a = a + c (1 - a), through
//                  Rasterizer::fill -> CoverageSink like any render (fxaa: the filter runs on that alpha buffer)
//        error:    against exact's coverage: max |d|, RMS, share of pixels with |d| > 1/255 and > 8/255
//   3. DIR/accuracy.md (tables, Pareto front) and DIR/accuracy.png (time-vs-RMS plot drawn with vraster, and a
//      strip of zoomed crops of hard regions under each method)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli/bitmap_font.hpp"
#include "cli/cli.hpp"
#include "svg_subset/svg.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/files.hpp"
#include "vraster/stroke.hpp"
#include "vraster/vraster.hpp"

namespace vraster::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr AntiAliasMethod kMethods[] = {
    {AntiAlias::None},  {AntiAlias::Analytic}, {AntiAlias::Exact},  {AntiAlias::Ssaa2},
    {AntiAlias::Ssaa4}, {AntiAlias::Ssaa8},    {AntiAlias::Ssaa16}, {AntiAlias::Msaa4},
    {AntiAlias::Msaa8}, {AntiAlias::Msaa16},   {AntiAlias::None, /*fxaa=*/true}};
constexpr int kMethodCount = static_cast<int>(std::size(kMethods));

Color method_color(int m) {
  static const Color colors[] = {
      Color::rgb8(120, 120, 120), Color::rgb8(214, 39, 40),  Color::rgb8(0, 0, 0),      Color::rgb8(158, 202, 225),
      Color::rgb8(66, 146, 198),  Color::rgb8(8, 81, 156),   Color::rgb8(8, 48, 107),   Color::rgb8(161, 217, 155),
      Color::rgb8(65, 171, 93),   Color::rgb8(0, 90, 50),    Color::rgb8(230, 140, 20)};
  return colors[m];
}

struct Crop {
  int x = 0, y = 0, size = 0;  // size 0: no crop from this scene
};

struct Scene {
  std::string name;
  svg::Document doc;
  Crop crop;
};

struct Result {
  double ms = 0;
  double max_abs = 0, rms = 0, over1 = 0, over8 = 0;
  std::vector<float> coverage;
};

// ---- built-in hard scenes --------------------------------------------------------------------------------------

class Lcg {
 public:
  explicit Lcg(std::uint64_t seed) : s_(seed) {}
  double next() {  // [0, 1)
    s_ = s_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s_ >> 11) * 0x1p-53;
  }

 private:
  std::uint64_t s_;
};

void add_fill(svg::Document& doc, Path path, FillRule rule, Color color = Color{0, 0, 0, 1}) {
  svg::DrawItem item;
  item.path = std::move(path);
  item.rule = rule;
  item.color = color;
  doc.items.push_back(std::move(item));
}

Scene builtin_slivers() {
  Scene s{"hard_slivers", {}, {96, 96, 32}};
  s.doc.width = s.doc.height = 256;
  Lcg rng(7);
  for (int i = 0; i < 120; ++i) {
    const double cx = 16 + rng.next() * 224, cy = 16 + rng.next() * 224;
    const double angle = rng.next() * std::numbers::pi, len = 20 + rng.next() * 100;
    const double width = 0.02 + rng.next() * 0.6;
    const double dx = std::cos(angle) * len / 2, dy = std::sin(angle) * len / 2;
    const double nx = -std::sin(angle) * width, ny = std::cos(angle) * width;
    Path p;
    p.move_to(cx - dx, cy - dy).line_to(cx + dx + nx, cy + dy + ny).line_to(cx + dx - nx, cy + dy - ny).close();
    add_fill(s.doc, std::move(p), FillRule::NonZero);
  }
  return s;
}

Path star(double cx, double cy, double r, int points, int step, double rotation) {
  Path p;
  for (int k = 0; k < points; ++k) {
    const double a = rotation + 2 * std::numbers::pi * k * step / points;
    const Point q{cx + r * std::sin(a), cy - r * std::cos(a)};
    if (k == 0) {
      p.move_to(q);
    } else {
      p.line_to(q);
    }
  }
  p.close();
  return p;
}

Scene builtin_pentagram() {
  Scene s{"hard_pentagram", {}, {48, 36, 32}};
  s.doc.width = 256;
  s.doc.height = 128;
  add_fill(s.doc, star(64, 66, 60, 5, 2, 0.013), FillRule::EvenOdd);
  add_fill(s.doc, star(192, 66, 60, 5, 2, 0.013), FillRule::NonZero);
  // Many-pointed stars: edges cross many times inside single pixels near the centre.
  add_fill(s.doc, star(64, 66, 20, 31, 15, 0.1), FillRule::EvenOdd);
  add_fill(s.doc, star(192, 66, 20, 31, 15, 0.1), FillRule::NonZero);
  return s;
}

// Glyph-like shapes 9 px tall (o, e, l, s, c, n shapes from curves): a stand-in for 9 px text that needs no
// font file. (The bench's text_outlines, scaled to 9 px, is added as text9 when the bench scenes are found.)
Scene builtin_glyphs() {
  Scene s{"hard_glyphs9", {}, {0, 0, 32}};
  s.doc.width = 256;
  s.doc.height = 128;
  Lcg rng(11);
  const double h = 9, w = 5.2;
  int count = 0;
  for (double y = 4; y + h < 124; y += 11.5) {
    for (double x = 3 + rng.next(); x + w < 252; x += 6.3) {
      const int kind = count++ % 5;
      const double ox = x + rng.next() * 0.3, oy = y + rng.next() * 0.3;
      Path p;
      const double cx = ox + w / 2, xh = 0.55 * h, cy = oy + h - xh / 2;  // x-height bowl centre
      switch (kind) {
        case 0:  // o: ring
          p.add_ellipse({cx, cy}, w / 2, xh / 2);
          p.add_ellipse({cx, cy}, w / 2 - 0.9, xh / 2 - 0.75);
          break;
        case 1: {  // l / i stem with a serif-ish cap
          p.add_rect(Rect{ox + 1.8, oy, ox + 2.75, oy + h});
          p.add_rect(Rect{ox + 0.8, oy + h - 0.8, ox + 3.8, oy + h});
          break;
        }
        case 2: {  // s: stroked S-curve as an outline
          Path c;
          c.move_to(ox + w - 0.7, cy - xh / 2 + 0.8);
          c.cubic_to({ox, cy - xh / 2 - 0.6}, {ox - 0.2, cy}, {cx, cy});
          c.cubic_to({ox + w + 0.2, cy}, {ox + w, cy + xh / 2 + 0.6}, {ox + 0.7, cy + xh / 2 - 0.8});
          StrokeStyle st;
          st.width = 0.9;
          p = stroke_to_path(c, st, 0.02);
          break;
        }
        case 3: {  // n: stem + arch
          p.add_rect(Rect{ox + 0.5, cy - xh / 2, ox + 1.4, oy + h});
          Path c;
          c.move_to(ox + 0.95, cy - xh / 2 + 1.2);
          c.cubic_to({ox + 1.5, cy - xh / 2 - 0.4}, {ox + w - 0.5, cy - xh / 2 - 0.4}, {ox + w - 0.5, cy});
          c.line_to(ox + w - 0.5, oy + h);
          StrokeStyle st;
          st.width = 0.9;
          p.add_path(stroke_to_path(c, st, 0.02));
          break;
        }
        default: {  // e: ring cut by a bar
          p.add_ellipse({cx, cy}, w / 2, xh / 2);
          p.add_ellipse({cx, cy}, w / 2 - 0.85, xh / 2 - 0.75);
          p.add_rect(Rect{cx - w / 2 + 0.5, cy - 0.2, cx + w / 2 - 0.5, cy + 0.5});
          break;
        }
      }
      add_fill(s.doc, std::move(p), FillRule::NonZero);
    }
  }
  return s;
}

Scene builtin_fan() {
  Scene s{"hard_fan", {}, {10, 100, 32}};
  s.doc.width = s.doc.height = 256;
  const double cx = 4, cy = 252;  // lines from near a corner: every slope
  for (int k = 0; k < 90; ++k) {
    const double a = (k + 0.5) / 90.0 * std::numbers::pi / 2;
    const double ux = std::cos(a), uy = -std::sin(a), nx = -uy * 0.35, ny = ux * 0.35;  // 0.7 px wide lines
    const double r0 = 8, r1 = 248;
    Path p;
    p.move_to(cx + ux * r0 + nx, cy + uy * r0 + ny)
        .line_to(cx + ux * r1 + nx, cy + uy * r1 + ny)
        .line_to(cx + ux * r1 - nx, cy + uy * r1 - ny)
        .line_to(cx + ux * r0 - nx, cy + uy * r0 - ny)
        .close();
    add_fill(s.doc, std::move(p), FillRule::NonZero);
  }
  return s;
}

// Zone plate: rings between radii r = c sqrt(k); ring width shrinks outward until it is far below a pixel.
Scene builtin_rings() {
  Scene s{"hard_rings", {}, {96, 96, 32}};
  s.doc.width = s.doc.height = 256;
  Path p;
  const double c = 12.0;
  for (int k = 1;; k += 2) {
    const double r_in = c * std::sqrt(static_cast<double>(k)), r_out = c * std::sqrt(static_cast<double>(k + 1));
    if (r_in > 180) break;
    p.add_circle({0, 0}, r_out);
    p.add_circle({0, 0}, r_in);
  }
  p.transform(Affine::translate(6, 6));
  add_fill(s.doc, std::move(p), FillRule::EvenOdd);
  return s;
}

// ---- scenes from files -----------------------------------------------------------------------------------------

void downscale(svg::Document& doc, int max_side) {
  const int side = std::max(doc.width, doc.height);
  if (max_side <= 0 || side <= max_side) return;
  const double f = static_cast<double>(max_side) / side;
  doc.width = std::max(1, static_cast<int>(std::lround(doc.width * f)));
  doc.height = std::max(1, static_cast<int>(std::lround(doc.height * f)));
  for (svg::DrawItem& item : doc.items) item.transform = Affine::scale(f) * item.transform;
}

fs::path find_bench_scenes() {
  std::error_code ec;
  if (const char* env = std::getenv("VRASTER_BENCH_SCENES")) {
    if (!fs::is_directory(env, ec))
      throw Error("accuracy: VRASTER_BENCH_SCENES=" + quoted(env, 1024) + " is not a directory");
    return env;
  }
  std::vector<fs::path> bases;
  if (fs::path cwd = fs::current_path(ec); !ec) bases.push_back(cwd);  // none when the directory was deleted
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) bases.push_back(exe.parent_path());
  for (fs::path base : bases) {
    for (int up = 0; up < 5 && !base.empty(); ++up) {
      for (const char* rel : {"../shared/bench/scenes", "shared/bench/scenes"}) {
        const fs::path p = base / rel;
        if (fs::is_directory(p, ec)) return fs::weakly_canonical(p, ec);
      }
      if (base == base.parent_path()) break;
      base = base.parent_path();
    }
  }
  return {};
}

// ---- coverage, timing, error -----------------------------------------------------------------------------------

// Source-over of coverage into a float alpha buffer: every item counts as opaque white.
class AlphaSink final : public CoverageSink {
 public:
  AlphaSink(std::vector<float>& alpha, int width) : alpha_(alpha), width_(width) {}
  void span(int y, int x0, int x1, float c) override {
    float* a = alpha_.data() + static_cast<std::size_t>(y) * width_;
    for (int x = x0; x < x1; ++x) a[x] += c * (1 - a[x]);
  }
  void row(int y, int x0, int x1, const float* c) override {
    float* a = alpha_.data() + static_cast<std::size_t>(y) * width_;
    for (int x = x0; x < x1; ++x) a[x] += c[x - x0] * (1 - a[x]);
  }

 private:
  std::vector<float>& alpha_;
  int width_;
};

std::vector<float> scene_coverage(const svg::Document& doc, const AntiAliasMethod& aa, Renderer& renderer) {
  std::vector<float> alpha(static_cast<std::size_t>(doc.width) * doc.height, 0.0f);
  AlphaSink sink(alpha, doc.width);
  const double tol = kDefaultTolerance;
  for (const svg::DrawItem& item : doc.items) {
    if (!(item.color.a > 0) || item.path.empty()) continue;
    FillRule rule = item.rule;
    const Path* path = &item.path;
    Path outline;
    if (item.is_stroke()) {
      outline = stroke_to_path(item.path, item.stroke, user_tolerance(item.transform, tol));
      path = &outline;
      rule = FillRule::NonZero;
    }
    const Polylines& lines = renderer.flatten_for_fill(*path, item.transform, tol, doc.width, doc.height);
    renderer.rasterizer().fill(lines, rule, aa.coverage, doc.width, doc.height, sink);
  }
  post_filter(aa, std::span<float>(alpha), doc.width, doc.height);
  return alpha;
}

// `coverage_ms`: how long the coverage pass of the same method took (it has already grown the buffers, so a slow
// case needs no separate warm-up frame).
double median_ms(const svg::Document& doc, const AntiAliasMethod& aa, int frames, double coverage_ms, Renderer& renderer,
                 Image& image) {
  svg::RenderSettings settings;
  settings.aa = aa.coverage;
  auto frame = [&] {
    const auto t0 = Clock::now();
    image.clear(Color{1, 1, 1, 1});
    svg::render(doc, image, settings, renderer);
    post_filter(aa, image);
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  // Slow cases get fewer frames (and no warm-up) so the default run stays short.
  std::vector<double> ms;
  if (coverage_ms > 300) {
    ms.push_back(frame());
    if (ms.back() < 120 && frames > 1) ms.push_back(frame());
    std::sort(ms.begin(), ms.end());
    return ms.size() % 2 ? ms[0] : 0.5 * (ms[0] + ms[1]);
  }
  const double warm = frame();
  // Fast cases get more frames (up to ~25 ms of them, at most 25) so the median is stable.
  const int n = warm > 400 ? 1
                : warm > 120 ? std::min(frames, 2)
                             : std::max(frames, std::min(25, static_cast<int>(25.0 / std::max(warm, 1e-3))));
  for (int i = 0; i < n; ++i) ms.push_back(frame());
  std::sort(ms.begin(), ms.end());
  return ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
}

void compare(const std::vector<float>& got, const std::vector<float>& ref, Result& r) {
  double sum2 = 0;
  std::size_t over1 = 0, over8 = 0;
  r.max_abs = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const double d = std::abs(static_cast<double>(got[i]) - ref[i]);
    r.max_abs = std::max(r.max_abs, d);
    sum2 += d * d;
    over1 += d > 1.0 / 255;
    over8 += d > 8.0 / 255;
  }
  const double n = static_cast<double>(std::max<std::size_t>(ref.size(), 1));
  r.rms = std::sqrt(sum2 / n);
  r.over1 = over1 / n;
  r.over8 = over8 / n;
}

// ---- the picture -----------------------------------------------------------------------------------------------

constexpr Color kInk = {0.12f, 0.16f, 0.22f, 1.f};
constexpr double kTiny = 1e-6;  // RMS below this counts as "equal to exact" in the plot (round-off)

void fill_rect(Renderer& r, Image& img, double x0, double y0, double x1, double y1, Color c) {
  Path p;
  p.add_rect(Rect{x0, y0, x1, y1});
  r.fill(img, p, Affine{}, c, FillOptions{FillRule::NonZero, AntiAlias::Analytic, 0.1});
}

void fill_circle(Renderer& r, Image& img, double x, double y, double radius, Color c) {
  Path p;
  p.add_circle({x, y}, radius);
  r.fill(img, p, Affine{}, c, FillOptions{FillRule::NonZero, AntiAlias::Analytic, 0.05});
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void draw_report_png(const std::vector<Scene>& scenes, const std::vector<std::vector<Result>>& results,
                     OutputFile& file) {
  const int cell = 128, gap = 8;
  const int strip_w = kMethodCount * (cell + gap) + gap + 120;
  const int plot_w = std::max(strip_w, 900), plot_h = 560;
  std::vector<std::size_t> crop_scenes;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    if (scenes[s].crop.size > 0) crop_scenes.push_back(s);
  }
  const int strip_h = static_cast<int>(crop_scenes.size()) * (cell + 2 * gap + 12) + 30;
  Image img(plot_w, plot_h + strip_h);
  img.clear(Color{1, 1, 1, 1});
  Renderer r;

  // Plot: log10(ms) across, log10(RMS) up.
  double tmin = 1e300, tmax = 0, emin = 1e300, emax = 0;
  for (const auto& row : results) {
    for (int m = 0; m < kMethodCount; ++m) {
      tmin = std::min(tmin, row[m].ms);
      tmax = std::max(tmax, row[m].ms);
      if (row[m].rms > kTiny) {
        emin = std::min(emin, row[m].rms);
        emax = std::max(emax, row[m].rms);
      }
    }
  }
  if (!(emax > 0)) emin = 1e-4, emax = 1e-1;
  const double lt0 = std::floor(std::log10(std::max(tmin, 1e-3))), lt1 = std::ceil(std::log10(std::max(tmax, 1e-3)));
  const double le0 = std::floor(std::log10(emin)) - 1, le1 = std::ceil(std::log10(emax));  // one decade for exact
  const double px0 = 80, px1 = plot_w - 220, py0 = 40, py1 = plot_h - 50;
  auto X = [&](double ms) { return px0 + (std::log10(std::max(ms, 1e-3)) - lt0) / std::max(lt1 - lt0, 1.0) * (px1 - px0); };
  auto Y = [&](double e) {
    const double le = e > kTiny ? std::log10(e) : le0;
    return py1 - (le - le0) / std::max(le1 - le0, 1.0) * (py1 - py0);
  };
  const Color grid = Color::rgb8(225, 225, 225);
  for (double d = lt0; d <= lt1; d += 1) {
    const double x = X(std::pow(10.0, d));
    fill_rect(r, img, x - 0.5, py0, x + 0.5, py1, grid);
    const std::string label = fmt(d >= 0 ? "%.0f" : "%g", std::pow(10.0, d));
    draw_label(img, static_cast<int>(x) - label_width(label) / 2, static_cast<int>(py1) + 6, label, kInk);
  }
  for (double d = le0; d <= le1; d += 1) {
    const double y = Y(std::pow(10.0, d));
    fill_rect(r, img, px0, y - 0.5, px1, y + 0.5, grid);
    const std::string label = "1e" + std::to_string(static_cast<int>(d));
    draw_label(img, static_cast<int>(px0) - 8 - label_width(label), static_cast<int>(y) - 3, label, kInk);
  }
  fill_rect(r, img, px0 - 1, py0, px0, py1 + 1, kInk);
  fill_rect(r, img, px0 - 1, py1, px1, py1 + 1, kInk);
  draw_label(img, static_cast<int>((px0 + px1) / 2) - label_width("median ms per frame (log)", 2) / 2,
             static_cast<int>(py1) + 22, "median ms per frame (log)", kInk, 2);
  draw_label(img, 8, 10, "RMS coverage error vs exact (log) - exact itself (and RMS < 1e-6) on the bottom line", kInk, 2);
  // One small marker per scene and method; one big, labelled marker per method at the geometric means.
  for (const auto& row : results) {
    for (int m = 0; m < kMethodCount; ++m) fill_circle(r, img, X(row[m].ms), Y(row[m].rms), 2.5, method_color(m).with_alpha(0.7f));
  }
  for (int m = 0; m < kMethodCount; ++m) {
    double lt = 0, le = 0;
    int ne = 0;
    for (const auto& row : results) {
      lt += std::log(std::max(row[m].ms, 1e-6));
      if (row[m].rms > kTiny) le += std::log(row[m].rms), ++ne;
    }
    const double gt = std::exp(lt / results.size()), ge = ne ? std::exp(le / ne) : 0.0;
    const double x = X(gt), y = Y(ge);
    fill_circle(r, img, x, y, 7, kInk);
    fill_circle(r, img, x, y, 5.5, method_color(m));
    const std::string_view name = to_string(kMethods[m]);
    draw_label(img, static_cast<int>(x) + 9, static_cast<int>(y) - 3 - 8 * (m % 2), name, kInk);
  }
  // Legend.
  for (int m = 0; m < kMethodCount; ++m) {
    const double lx = px1 + 30, ly = py0 + 10 + m * 20;
    fill_circle(r, img, lx, ly, 5.5, method_color(m));
    draw_label(img, static_cast<int>(lx) + 12, static_cast<int>(ly) - 6, to_string(kMethods[m]), kInk, 2);
  }
  draw_label(img, static_cast<int>(px1) + 20, static_cast<int>(py0 + 10 + kMethodCount * 20),
             "big: mean over scenes", kInk);
  draw_label(img, static_cast<int>(px1) + 20, static_cast<int>(py0 + 22 + kMethodCount * 20),
             "small: one per scene", kInk);

  // Strip of crops: coverage as black on white, nearest-neighbour upscaled.
  int y = plot_h;
  draw_label(img, gap, y + 4, "zoomed crops (32x32 px, x4), coverage black on white", kInk, 2);
  y += 26;
  for (const std::size_t s : crop_scenes) {
    const Scene& sc = scenes[s];
    const int size = std::min({sc.crop.size, sc.doc.width - sc.crop.x, sc.doc.height - sc.crop.y});
    if (size <= 0) continue;
    const int zoom = cell / sc.crop.size;
    draw_label(img, gap, y + cell / 2, sc.name, kInk);
    for (int m = 0; m < kMethodCount; ++m) {
      const int ox = 120 + m * (cell + gap), oy = y;
      const std::vector<float>& cov = results[s][m].coverage;
      for (int cy = 0; cy < size; ++cy) {
        for (int cx = 0; cx < size; ++cx) {
          const float c = cov[static_cast<std::size_t>(sc.crop.y + cy) * sc.doc.width + sc.crop.x + cx];
          const auto v = static_cast<std::uint8_t>(std::lround(255 * (1 - std::clamp(c, 0.f, 1.f))));
          for (int dy = 0; dy < zoom; ++dy) {
            for (int dx = 0; dx < zoom; ++dx) {
              std::uint8_t* p = img.pixel(ox + cx * zoom + dx, oy + cy * zoom + dy);
              p[0] = p[1] = p[2] = v;
              p[3] = 255;
            }
          }
        }
      }
      const std::string_view name = to_string(kMethods[m]);
      draw_label(img, ox + (cell - label_width(name)) / 2, oy + cell + 3, name, kInk);
    }
    y += cell + 2 * gap + 12;
  }
  write_png(file, img);
}

// ---- the report ------------------------------------------------------------------------------------------------

std::string write_markdown(const std::vector<Scene>& scenes, const std::vector<std::vector<Result>>& results,
                           const std::string& command, double total_s, int frames, int max_side) {
  std::ostringstream md;
  md << "# Antialiasing methods: time vs accuracy\n\n"
     << "Generated by `" << command << "` in " << fmt("%.1f", total_s) << " s (frames per timing: " << frames
     << ", fewer for slow cases, up to 25 for fast ones; scenes larger than " << max_side << " px downscaled).\n\n"
     << "- **ms**: median ms per frame of the render path (clear + fill every item [+ the fxaa filter]), one thread.\n"
     << "- **errors**: coverage of the whole scene (every item opaque white, a = a + c(1 - a)) against `exact`; "
        "max |d|, RMS over all pixels, and the share of all pixels with |d| > 1/255 and > 8/255.\n"
     << "- fxaa's coverage is the filter run on the aliased (none) coverage buffer.\n\n";
  // Summary per method.
  std::vector<double> gt(kMethodCount), mean_rms(kMethodCount), mean_max(kMethodCount);
  for (int m = 0; m < kMethodCount; ++m) {
    double lt = 0;
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      lt += std::log(std::max(results[s][m].ms, 1e-6));
      mean_rms[m] += results[s][m].rms / scenes.size();
      mean_max[m] += results[s][m].max_abs / scenes.size();
    }
    gt[m] = std::exp(lt / std::max<std::size_t>(scenes.size(), 1));
  }
  const double analytic_t = gt[1];
  // Pareto front on the summary (geometric-mean time, mean RMS), and per scene.
  std::vector<int> front_count(kMethodCount, 0);
  std::vector<bool> front(kMethodCount, true);
  auto dominated = [](double t, double e, double t2, double e2) { return t2 <= t && e2 <= e && (t2 < t || e2 < e); };
  for (int m = 0; m < kMethodCount; ++m) {
    for (int k = 0; k < kMethodCount; ++k) {
      if (k != m && dominated(gt[m], mean_rms[m], gt[k], mean_rms[k])) front[m] = false;
    }
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      bool on = true;
      for (int k = 0; k < kMethodCount; ++k) {
        if (k != m && dominated(results[s][m].ms, results[s][m].rms, results[s][k].ms, results[s][k].rms)) on = false;
      }
      front_count[m] += on;
    }
  }
  md << "## Summary over " << scenes.size() << " scenes\n\n"
     << "| method | geo-mean ms | time / analytic | mean RMS | mean max abs | Pareto (summary) | on the front in scenes |\n"
     << "| --- | ---: | ---: | ---: | ---: | :---: | ---: |\n";
  for (int m = 0; m < kMethodCount; ++m) {
    md << "| " << to_string(kMethods[m]) << " | " << fmt("%.3f", gt[m]) << " | " << fmt("%.2f", gt[m] / analytic_t)
       << " | " << fmt("%.2e", mean_rms[m]) << " | " << fmt("%.3f", mean_max[m]) << " | " << (front[m] ? "yes" : "")
       << " | " << front_count[m] << "/" << scenes.size() << " |\n";
  }
  // Pairwise: in how many scenes is method m beaten on both axes by method k?
  md << "\n## Beaten on both axes\n\nFor each method, the methods that are both faster and more accurate (lower RMS) in "
        "at least half of the scenes (count in brackets).\n\n| method | beaten by |\n| --- | --- |\n";
  for (int m = 0; m < kMethodCount; ++m) {
    std::string by;
    for (int k = 0; k < kMethodCount; ++k) {
      int n = 0;
      for (std::size_t s = 0; s < scenes.size(); ++s) {
        n += results[s][k].ms < results[s][m].ms && results[s][k].rms < results[s][m].rms;
      }
      if (k != m && 2 * n >= static_cast<int>(scenes.size())) {
        by += (by.empty() ? "" : ", ") + std::string(to_string(kMethods[k])) + " (" + std::to_string(n) + ")";
      }
    }
    md << "| " << to_string(kMethods[m]) << " | " << (by.empty() ? "-" : by) << " |\n";
  }
  md << "\n## Per scene\n";
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    md << "\n### " << scenes[s].name << " (" << scenes[s].doc.width << "x" << scenes[s].doc.height << ", "
       << scenes[s].doc.items.size() << " items)\n\n"
       << "| method | ms | max abs | RMS | > 1/255 | > 8/255 |\n| --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (int m = 0; m < kMethodCount; ++m) {
      const Result& r = results[s][m];
      md << "| " << to_string(kMethods[m]) << " | " << fmt("%.3f", r.ms) << " | " << fmt("%.4f", r.max_abs) << " | "
         << fmt("%.2e", r.rms) << " | " << fmt("%.3f%%", 100 * r.over1) << " | " << fmt("%.3f%%", 100 * r.over8)
         << " |\n";
    }
  }
  return md.str();
}

}  // namespace

int run_accuracy(int argc, char** argv) {
  std::vector<std::string> inputs;
  std::string out_dir;
  int frames = 3, max_side = 512;
  std::string command = "vraster accuracy";
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    command.append(" ").append(arg);
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw UsageError{std::string(arg) + " needs a value"};
      command.append(" ").append(argv[i + 1]);
      return argv[++i];
    };
    auto integer = [&](int lo, int hi) {
      const std::string v(value());
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n < lo || n > hi) {
        throw UsageError{std::string(arg) + " needs a whole number from " + std::to_string(lo) + " to " +
                         std::to_string(hi)};
      }
      return static_cast<int>(n);
    };
    if (arg == "-o" || arg == "--output") {
      out_dir = value();
    } else if (arg == "--frames") {
      frames = integer(1, 1000);
    } else if (arg == "--max-side") {
      max_side = integer(0, kMaxImageSide);
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError{"accuracy: unknown option " + quoted(arg)};
    } else {
      inputs.emplace_back(arg);
    }
  }
  if (out_dir.empty()) throw UsageError{"accuracy: no output directory (-o DIR)"};

  // The output first, so a bad -o fails before the measurements. Both files or neither: each goes to a
  // temporary that is renamed only at the end, and a failed second rename takes the first file back.
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error("accuracy: cannot create directory " + quoted(out_dir, 1024) + ": " + ec.message());
  const std::string md_path = (fs::path(out_dir) / "accuracy.md").string();
  const std::string png_path = (fs::path(out_dir) / "accuracy.png").string();
  OutputFile png_file(png_path), md_file(md_path);

  const auto start = Clock::now();
  std::vector<Scene> scenes;
  if (inputs.empty()) {
    const fs::path dir = find_bench_scenes();
    if (dir.empty()) {
      std::cerr << "vraster accuracy: shared bench scenes not found (set VRASTER_BENCH_SCENES); built-in scenes only\n";
    } else {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() == ".svg") files.push_back(e.path());
      }
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) {
        Scene s{f.stem().string(), svg::load_svg(f.string()), {}};
        downscale(s.doc, max_side);
        if (s.name == "text_outlines") {  // also at 9 px (16 px text scaled by 9/16): real glyphs, small
          Scene t{"text9", svg::load_svg(f.string()), {40, 8, 32}};
          const double k = 9.0 / 16.0;
          t.doc.width = static_cast<int>(std::lround(t.doc.width * k));
          t.doc.height = static_cast<int>(std::lround(t.doc.height * k));
          for (svg::DrawItem& item : t.doc.items) item.transform = Affine::scale(k) * item.transform;
          scenes.push_back(std::move(t));
        }
        scenes.push_back(std::move(s));
      }
    }
    scenes.push_back(builtin_slivers());
    scenes.push_back(builtin_pentagram());
    scenes.push_back(builtin_glyphs());
    scenes.push_back(builtin_fan());
    scenes.push_back(builtin_rings());
  } else {
    for (const std::string& f : inputs) {
      Scene s{fs::path(f).stem().string(), svg::load_svg(f), {}};
      for (const std::string& w : s.doc.warnings) std::cerr << printable(f, 1024) << ":" << w << "\n";
      downscale(s.doc, max_side);
      scenes.push_back(std::move(s));
    }
  }
  // Files given: crop the centre of the first scene.
  if (!inputs.empty() && !scenes.empty()) {
    Scene& s = scenes.front();
    const int size = std::min({32, s.doc.width, s.doc.height});
    s.crop = {(s.doc.width - size) / 2, (s.doc.height - size) / 2, size};
  }


  Renderer renderer;
  std::vector<std::vector<Result>> results(scenes.size(), std::vector<Result>(kMethodCount));
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const svg::Document& doc = scenes[s].doc;
    Image image(doc.width, doc.height);
    for (int m = 0; m < kMethodCount; ++m) {
      const auto t0 = Clock::now();
      results[s][m].coverage = scene_coverage(doc, kMethods[m], renderer);
      const double coverage_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      results[s][m].ms = median_ms(doc, kMethods[m], frames, coverage_ms, renderer, image);
    }
    const std::vector<float>& ref = results[s][2].coverage;  // exact
    for (int m = 0; m < kMethodCount; ++m) compare(results[s][m].coverage, ref, results[s][m]);
    std::cerr << "  " << scenes[s].name << ": done ("
              << fmt("%.1f", std::chrono::duration<double>(Clock::now() - start).count()) << " s)\n";
  }
  const double total = std::chrono::duration<double>(Clock::now() - start).count();
  draw_report_png(scenes, results, png_file);
  const std::string markdown = write_markdown(scenes, results, command, total, frames, max_side);
  std::fwrite(markdown.data(), 1, markdown.size(), md_file.stream());
  png_file.commit();
  try {
    md_file.commit();
  } catch (...) {
    std::remove(png_path.c_str());
    throw;
  }
  std::cout << "vraster accuracy: " << scenes.size() << " scenes x " << kMethodCount << " methods in "
            << fmt("%.1f", total) << " s; wrote " << md_path << " and " << png_path << "\n";
  return 0;
}

}  // namespace vraster::cli
