// vraster_paint_bench: paint-heavy scenes on a 1024 x 1024 frame, vraster against Cairo in the same run,
// single-threaded, plus the memory bandwidth of the machine measured in the same run (memset / memcpy of the
// frame's 4 MiB), so compositing can be read against it.
//
//   vraster_paint_bench [--frames N] [--scene NAME]...
//
// A frame = clear to white (except `multiply`, which keeps blending onto the previous frame) + the scene's
// drawing. The engines alternate frame by frame after one warm-up frame each; the figure is the median ms.
// vraster draws through the compositor directly (Renderer's flattening and rasterizer + Compositor<uint8_t>), the
// clipped fill through vraster::Canvas (clip + fill, as Cairo's cairo_clip + cairo_fill); Cairo through its image
// surface with the same geometry, paint and tolerance (0.1).
#include <cairo.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vraster/canvas.hpp"
#include "vraster/composite.hpp"
#include "vraster/renderer.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using namespace vraster;

constexpr int kSize = 1024;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// ---- shared scene content ----

const ColorStop kStops[] = {{0, {0.9f, 0.2f, 0.1f, 1}}, {0.4, {1, 0.8f, 0.2f, 1}}, {0.7, {0.2f, 0.6f, 0.9f, 1}},
                            {1, {0.3f, 0.1f, 0.5f, 1}}};
const ColorStop kAlphaStops[] = {{0, {0.9f, 0.2f, 0.1f, 0.9f}}, {0.5, {1, 0.8f, 0.2f, 0.4f}}, {1, {0.2f, 0.6f, 0.9f, 0.8f}}};

Path big_ellipse() {
  Path p;
  p.add_ellipse({512, 512}, 480, 420);
  return p;
}
Path clip_circle() {
  Path p;
  p.add_circle({512, 512}, 400);
  return p;
}
Path rotated_square() {
  Path p;
  const Point c{512, 512};
  for (int i = 0; i < 4; ++i) {
    const double a = 0.3 + i * 1.5707963267948966;
    const Point q{c.x + 600 * std::cos(a), c.y + 600 * std::sin(a)};
    if (i == 0) {
      p.move_to(q);
    } else {
      p.line_to(q);
    }
  }
  p.close();
  return p;
}
std::vector<Path> layer_shapes() {
  std::vector<Path> v(3);
  v[0].add_ellipse({400, 420}, 300, 260);
  v[1].add_ellipse({620, 460}, 280, 300);
  v[2].add_ellipse({512, 640}, 320, 240);
  return v;
}
const Color kLayerColors[] = {{0.9f, 0.1f, 0.1f, 1}, {0.1f, 0.7f, 0.2f, 1}, {0.1f, 0.2f, 0.9f, 1}};

std::shared_ptr<Image> make_tile() {
  auto tile = std::make_shared<Image>(256, 256);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      std::uint8_t* p = tile->pixel(x, y);
      const bool check = ((x >> 5) ^ (y >> 5)) & 1;
      p[0] = static_cast<std::uint8_t>(check ? x : 255 - y);
      p[1] = static_cast<std::uint8_t>((x * y) >> 8);
      p[2] = static_cast<std::uint8_t>(check ? 200 : y);
      p[3] = 255;
    }
  }
  return tile;
}
const Affine kTileTransform = Affine::rotate(10, 512, 512) * Affine::scale(1.7);

Paint linear_paint() {
  Paint p = Paint::linear({100, 80}, {920, 900});
  for (const ColorStop& s : kStops) p.add_stop(s.offset, s.color);
  return p;
}
Paint radial_paint() {
  Paint p = Paint::radial({420, 400}, 20, {512, 512}, 500);
  for (const ColorStop& s : kAlphaStops) p.add_stop(s.offset, s.color);
  p.set_extend(Extend::Reflect);
  return p;
}

// ---- vraster ----

class VrasterScenes {
 public:
  VrasterScenes() : image_(kSize, kSize), layer_(kSize, kSize), tile_(make_tile()), canvas_(image_) {}
  Image& image() { return image_; }

  void clear() { std::memset(image_.data.data(), 255, image_.data.size()); }

  void fill(const Path& path, const Paint& paint, CompositeOp op, ImageView<std::uint8_t> view) {
    comp_.set(view, paint, Affine{}, op);
    if (comp_.draws_nothing()) return;
    const Polylines& lines = renderer_.flatten_for_fill(path, Affine{}, 0.1, kSize, kSize);
    renderer_.rasterizer().fill(lines, FillRule::NonZero, AntiAlias::Analytic, kSize, kSize, comp_);
  }
  void fill(const Path& path, const Paint& paint, CompositeOp op = CompositeOp::SourceOver) {
    fill(path, paint, op, ImageView<std::uint8_t>::of(image_));
  }

  void clipped_fill(const Path& clip_path, const Path& path, const Paint& paint) {
    // Through the canvas, as Cairo's side goes through cairo_clip: the clip's coverage mask is made every frame.
    canvas_.save();
    canvas_.clip(clip_path, FillRule::NonZero);
    canvas_.set_fill_paint(paint);
    canvas_.fill(path);
    canvas_.restore();
  }

  void layer(const std::vector<Path>& shapes, float opacity) {
    std::memset(layer_.data.data(), 0, layer_.data.size());
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      fill(shapes[i], Paint::solid(kLayerColors[i]), CompositeOp::SourceOver, ImageView<std::uint8_t>::of(layer_));
    }
    for (int y = 0; y < kSize; ++y) {
      blend_row_alpha(CompositeOp::SourceOver, image_.pixel(0, y), layer_.pixel(0, y), opacity, nullptr, kSize);
    }
  }

  const std::shared_ptr<Image>& tile() const { return tile_; }

 private:
  Image image_, layer_;
  std::shared_ptr<Image> tile_;
  Renderer renderer_;
  Compositor<std::uint8_t> comp_;
  Canvas canvas_;  // on image_
};

// ---- Cairo ----

void cairo_path_of(cairo_t* cr, const Path& path) {
  Polylines lines;
  FlattenOptions options;
  options.tolerance = 0.05;  // finer than both engines' 0.1: the same polygon for Cairo as a curve would give
  flatten(path, Affine{}, options, lines);
  for (std::size_t c = 0; c < lines.contour_count(); ++c) {
    const auto pts = lines.contour(c);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (i == 0) {
        cairo_move_to(cr, pts[i].x, pts[i].y);
      } else {
        cairo_line_to(cr, pts[i].x, pts[i].y);
      }
    }
    cairo_close_path(cr);
  }
}

cairo_pattern_t* cairo_gradient(const Paint& p) {
  cairo_pattern_t* g = p.kind() == Paint::Kind::Linear
                           ? cairo_pattern_create_linear(p.p0().x, p.p0().y, p.p1().x, p.p1().y)
                           : cairo_pattern_create_radial(p.p0().x, p.p0().y, p.r0(), p.p1().x, p.p1().y, p.r1());
  for (const ColorStop& s : p.stops()) cairo_pattern_add_color_stop_rgba(g, s.offset, s.color.r, s.color.g, s.color.b, s.color.a);
  cairo_pattern_set_extend(g, p.extend_x() == Extend::Reflect  ? CAIRO_EXTEND_REFLECT
                              : p.extend_x() == Extend::Repeat ? CAIRO_EXTEND_REPEAT
                                                               : CAIRO_EXTEND_PAD);
  return g;
}

class CairoScenes {
 public:
  CairoScenes() {
    surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, kSize, kSize);
    cr_ = cairo_create(surface_);
    cairo_set_tolerance(cr_, 0.1);
    const auto tile = make_tile();
    tile_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 256, 256);
    cairo_surface_flush(tile_);
    for (int y = 0; y < 256; ++y) {
      for (int x = 0; x < 256; ++x) {
        const std::uint8_t* p = tile->pixel(x, y);
        const std::uint32_t v = std::uint32_t{p[3]} << 24 | std::uint32_t{p[0]} << 16 | std::uint32_t{p[1]} << 8 | p[2];
        std::memcpy(cairo_image_surface_get_data(tile_) + y * cairo_image_surface_get_stride(tile_) + x * 4, &v, 4);
      }
    }
    cairo_surface_mark_dirty(tile_);
  }
  ~CairoScenes() {
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
    cairo_surface_destroy(tile_);
  }
  cairo_t* cr() { return cr_; }
  cairo_surface_t* tile() { return tile_; }
  void clear() {
    cairo_set_operator(cr_, CAIRO_OPERATOR_SOURCE);
    cairo_set_source_rgba(cr_, 1, 1, 1, 1);
    cairo_paint(cr_);
    cairo_set_operator(cr_, CAIRO_OPERATOR_OVER);
  }
  void flush() { cairo_surface_flush(surface_); }

 private:
  cairo_surface_t* surface_ = nullptr;
  cairo_surface_t* tile_ = nullptr;
  cairo_t* cr_ = nullptr;
};

struct PaintScene {
  std::string name;
  std::string what;
  std::function<void(VrasterScenes&)> ours;
  std::function<void(CairoScenes&)> cairo;
};

std::vector<PaintScene> scenes() {
  std::vector<PaintScene> s;
  const Path ellipse = big_ellipse();
  s.push_back({"linear", "ellipse 960x840, linear gradient, 4 opaque stops",
               [=](VrasterScenes& v) { v.clear(); v.fill(ellipse, linear_paint()); },
               [=](CairoScenes& c) {
                 c.clear();
                 cairo_pattern_t* g = cairo_gradient(linear_paint());
                 cairo_set_source(c.cr(), g);
                 cairo_path_of(c.cr(), ellipse);
                 cairo_fill(c.cr());
                 cairo_pattern_destroy(g);
                 c.flush();
               }});
  s.push_back({"radial", "ellipse 960x840, two-circle radial gradient, translucent stops, reflect",
               [=](VrasterScenes& v) { v.clear(); v.fill(ellipse, radial_paint()); },
               [=](CairoScenes& c) {
                 c.clear();
                 cairo_pattern_t* g = cairo_gradient(radial_paint());
                 cairo_set_source(c.cr(), g);
                 cairo_path_of(c.cr(), ellipse);
                 cairo_fill(c.cr());
                 cairo_pattern_destroy(g);
                 c.flush();
               }});
  s.push_back({"pattern_bilinear", "ellipse 960x840, 256x256 image pattern, rotated and scaled 1.7, repeat, bilinear",
               [=](VrasterScenes& v) {
                 v.clear();
                 Paint p = Paint::pattern(std::shared_ptr<const Image>(v.tile()));
                 p.set_filter(ImageFilter::Bilinear);
                 p.set_extend(Extend::Repeat);
                 p.set_transform(kTileTransform);
                 v.fill(ellipse, p);
               },
               [=](CairoScenes& c) {
                 c.clear();
                 cairo_pattern_t* p = cairo_pattern_create_for_surface(c.tile());
                 cairo_pattern_set_extend(p, CAIRO_EXTEND_REPEAT);
                 cairo_pattern_set_filter(p, CAIRO_FILTER_BILINEAR);
                 const Affine inv = kTileTransform.inverse();
                 const cairo_matrix_t m{inv.a, inv.b, inv.c, inv.d, inv.e, inv.f};
                 cairo_pattern_set_matrix(p, &m);
                 cairo_set_source(c.cr(), p);
                 cairo_path_of(c.cr(), ellipse);
                 cairo_fill(c.cr());
                 cairo_pattern_destroy(p);
                 c.flush();
               }});
  s.push_back({"multiply", "ellipse 960x840, solid rgba(0.9, 0.5, 0.2, 0.7), multiply, onto the previous frame",
               [=](VrasterScenes& v) { v.fill(ellipse, Paint::solid({0.9f, 0.5f, 0.2f, 0.7f}), CompositeOp::Multiply); },
               [=](CairoScenes& c) {
                 cairo_set_operator(c.cr(), CAIRO_OPERATOR_MULTIPLY);
                 cairo_set_source_rgba(c.cr(), 0.9, 0.5, 0.2, 0.7);
                 cairo_path_of(c.cr(), ellipse);
                 cairo_fill(c.cr());
                 cairo_set_operator(c.cr(), CAIRO_OPERATOR_OVER);
                 c.flush();
               }});
  const Path clip = clip_circle(), square = rotated_square();
  s.push_back({"clipped_fill", "canvas: circle clip r 400 (an 8-bit mask made each frame) + rotated square 850 px, solid alpha 0.8",
               [=](VrasterScenes& v) { v.clear(); v.clipped_fill(clip, square, Paint::solid({0.2f, 0.4f, 0.8f, 0.8f})); },
               [=](CairoScenes& c) {
                 c.clear();
                 cairo_save(c.cr());
                 cairo_path_of(c.cr(), clip);
                 cairo_clip(c.cr());
                 cairo_set_source_rgba(c.cr(), 0.2, 0.4, 0.8, 0.8);
                 cairo_path_of(c.cr(), square);
                 cairo_fill(c.cr());
                 cairo_restore(c.cr());
                 c.flush();
               }});
  const std::vector<Path> shapes = layer_shapes();
  s.push_back({"layer_opacity", "3 opaque ellipses into a full-frame layer, composited with opacity 0.6",
               [=](VrasterScenes& v) { v.clear(); v.layer(shapes, 0.6f); },
               [=](CairoScenes& c) {
                 c.clear();
                 cairo_push_group(c.cr());
                 for (std::size_t i = 0; i < shapes.size(); ++i) {
                   cairo_set_source_rgba(c.cr(), kLayerColors[i].r, kLayerColors[i].g, kLayerColors[i].b, 1);
                   cairo_path_of(c.cr(), shapes[i]);
                   cairo_fill(c.cr());
                 }
                 cairo_pop_group_to_source(c.cr());
                 cairo_paint_with_alpha(c.cr(), 0.6);
                 c.flush();
               }});
  Path full;
  full.add_rect({0, 0, kSize, kSize});
  s.push_back({"solid_over", "full frame, solid rgba alpha 0.5, source-over (reads and writes 4 MiB)",
               [=](VrasterScenes& v) { v.fill(full, Paint::solid({0.3f, 0.6f, 0.9f, 0.5f})); },
               [=](CairoScenes& c) {
                 cairo_set_source_rgba(c.cr(), 0.3, 0.6, 0.9, 0.5);
                 cairo_rectangle(c.cr(), 0, 0, kSize, kSize);
                 cairo_fill(c.cr());
                 c.flush();
               }});
  s.push_back({"solid_opaque", "full frame, opaque solid, source-over (writes 4 MiB)",
               [=](VrasterScenes& v) { v.fill(full, Paint::solid({0.3f, 0.6f, 0.9f, 1})); },
               [=](CairoScenes& c) {
                 cairo_set_source_rgba(c.cr(), 0.3, 0.6, 0.9, 1);
                 cairo_rectangle(c.cr(), 0, 0, kSize, kSize);
                 cairo_fill(c.cr());
                 c.flush();
               }});
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 21;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--scene" && i + 1 < argc) {
      only.push_back(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: vraster_paint_bench [--frames N] [--scene NAME]...\n");
      return 2;
    }
  }
  VrasterScenes ours;
  CairoScenes cairo;

  // Memory bandwidth in the same run: the frame's 4 MiB written (memset) and copied (memcpy).
  {
    std::vector<std::uint8_t> a(static_cast<std::size_t>(kSize) * kSize * 4, 1), b(a.size(), 2);
    std::vector<double> set, copy;
    for (int i = 0; i < 41; ++i) {
      auto t0 = Clock::now();
      std::memset(a.data(), i, a.size());
      set.push_back(ms_since(t0));
      t0 = Clock::now();
      std::memcpy(b.data(), a.data(), a.size());
      copy.push_back(ms_since(t0));
    }
    const double mib = a.size() / 1048576.0;
    std::printf("memory: memset 4 MiB %.3f ms (%.1f GiB/s), memcpy 4 MiB %.3f ms (%.1f GiB/s read + write)\n\n",
                median(set), mib / 1024 / (median(set) / 1000), median(copy), 2 * mib / 1024 / (median(copy) / 1000));
  }

  std::printf("| scene | vraster ms | Cairo ms | Cairo / vraster | what |\n|---|---:|---:|---:|---|\n");
  for (const PaintScene& s : scenes()) {
    if (!only.empty() && std::find(only.begin(), only.end(), s.name) == only.end()) continue;
    std::vector<double> tv, tc;
    s.ours(ours);
    s.cairo(cairo);
    for (int f = 0; f < frames; ++f) {
      auto t0 = Clock::now();
      s.ours(ours);
      tv.push_back(ms_since(t0));
      t0 = Clock::now();
      s.cairo(cairo);
      tc.push_back(ms_since(t0));
    }
    const double mv = median(tv), mc = median(tc);
    std::printf("| %s | %.2f | %.2f | %.2f | %s |\n", s.name.c_str(), mv, mc, mc / mv, s.what.c_str());
    std::fflush(stdout);
  }
  return 0;
}
