// vraster_mesh_bench: triangle-mesh throughput against Cairo, and against the same triangles as paths through
// vraster's own path rasterizer, single-threaded, median ms per frame (frames of the engines interleaved).
//
// Usage: vraster_mesh_bench [--frames N] [--size PX]
//
// Scenes (each on a SIZE x SIZE canvas, default 1024):
//   grid-20k / grid-100k   a 2D grid of triangles with a colour per vertex (Gouraud), jittered vertices, no depth
//   sphere-100k            a lit sphere of ~100,000 triangles, orthographic, with depth (z-buffer or painter's)
// Engines: vraster MeshRenderer (aliased; antialiased), vraster Renderer filling each triangle as a path (solid
// mean colour, analytic AA), Cairo mesh pattern (one Gouraud patch per triangle, cairo_paint), Cairo filling each
// triangle as a path (solid mean colour). Cairo has no depth buffer: on the sphere it gets the painter's order.
// A frame = clear + draw + (Cairo) flush.
#include <cairo.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "vraster/mesh.hpp"
#include "vraster/mesh_io.hpp"
#include "vraster/renderer.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using namespace vraster;

struct Scene {
  std::string name;
  Mesh mesh;
  bool depth = false;
  bool lit = false;
};

Scene grid_scene(int quads, int size) {
  Scene s;
  s.name = "grid-" + std::to_string(2 * quads * quads / 1000) + "k";
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), unit(0, 1);
  const double step = static_cast<double>(size) / quads;
  for (int j = 0; j <= quads; ++j) {
    for (int i = 0; i <= quads; ++i) {
      const bool border = i == 0 || j == 0 || i == quads || j == quads;
      MeshVertex v;
      v.position = Point{step * (i + (border ? 0 : jitter(rng))), step * (j + (border ? 0 : jitter(rng)))};
      v.color = Color{static_cast<float>(unit(rng)), static_cast<float>(unit(rng)), static_cast<float>(unit(rng)), 1};
      s.mesh.vertices.push_back(v);
    }
  }
  for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(quads); ++j) {
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(quads); ++i) {
      const std::uint32_t a = j * (quads + 1) + i, b = a + 1, c = a + quads + 1, d = c + 1;
      s.mesh.triangles.push_back({a, b, d});
      s.mesh.triangles.push_back({a, d, c});
    }
  }
  return s;
}

Scene sphere_scene(int size) {
  Scene s;
  s.name = "sphere-100k";
  Camera camera;
  s.mesh = project(make_sphere(224, 224), camera, size, size, Color{0.85f, 0.5f, 0.3f, 1});
  s.depth = true;
  s.lit = true;
  return s;
}

// Per-triangle colour (the mean of its vertices', lit once for lit scenes) for the solid-fill engines.
std::vector<Color> flat_colors(const Scene& s) {
  std::vector<Color> out;
  Lighting light;
  light.enabled = s.lit;
  for (const auto& t : s.mesh.triangles) {
    const MeshVertex &a = s.mesh.vertices[t[0]], &b = s.mesh.vertices[t[1]], &c = s.mesh.vertices[t[2]];
    const Color mean{(a.color.r + b.color.r + c.color.r) / 3, (a.color.g + b.color.g + c.color.g) / 3,
                     (a.color.b + b.color.b + c.color.b) / 3, 1};
    const Vec3 n{(a.normal.x + b.normal.x + c.normal.x) / 3, (a.normal.y + b.normal.y + c.normal.y) / 3,
                 (a.normal.z + b.normal.z + c.normal.z) / 3};
    out.push_back(shade(light, mean, n, Vec3{}));
  }
  return out;
}

// Triangle order for engines without a depth buffer: farthest first (painter's), or as given.
std::vector<std::size_t> draw_order(const Scene& s) {
  std::vector<std::size_t> order(s.mesh.triangles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (s.depth) {
    std::vector<double> z;
    for (const auto& t : s.mesh.triangles) {
      z.push_back(s.mesh.vertices[t[0]].depth + s.mesh.vertices[t[1]].depth + s.mesh.vertices[t[2]].depth);
    }
    order = depth_order(z);
  }
  return order;
}

struct Engine {
  std::string name;
  std::function<void()> frame;
  std::vector<double> ms = {};
};

// The seam measurement: a square split into 2 n^2 jittered triangles, antialiased, against the square as one path
// through the Renderer (analytic); and the same triangles composited one by one (per-triangle coverage).
void report_seams(int n) {
  const double x0 = 10.3, y0 = 9.7, x1 = 245.6, y1 = 240.2;
  Mesh mesh;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      MeshVertex v;
      v.position = Point{x0 + (x1 - x0) * (i + (border ? 0 : jitter(rng))) / n,
                         y0 + (y1 - y0) * (j + (border ? 0 : jitter(rng))) / n};
      v.color = Color{0.1f, 0.4f, 0.8f, 1};
      mesh.vertices.push_back(v);
    }
  }
  for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(n); ++j) {
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(n); ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  }
  Image meshed(256, 256), separate(256, 256), reference(256, 256);
  for (Image* im : {&meshed, &separate, &reference}) im->clear(Color{1, 1, 1, 1});
  MeshRenderer r;
  MeshOptions o;
  o.antialias = true;
  o.depth = DepthMode::None;
  r.draw(meshed, mesh, o);
  for (const auto& t : mesh.triangles) {
    Mesh one;
    one.vertices = mesh.vertices;
    one.triangles = {t};
    r.draw(separate, one, o);
  }
  Path square;
  square.move_to(x0, y0);
  square.line_to(x1, y0);
  square.line_to(x1, y1);
  square.line_to(x0, y1);
  square.close();
  Renderer renderer;
  renderer.fill(reference, square, Affine{}, Color{0.1f, 0.4f, 0.8f, 1}, FillOptions{});
  auto compare = [&](const Image& im, int& worst, int& pixels) {
    worst = 0, pixels = 0;
    for (std::size_t i = 0; i < im.data.size(); i += 4) {
      int d = 0;
      for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(im.data[i + c]) - int(reference.data[i + c])));
      worst = std::max(worst, d);
      pixels += d > 1;
    }
  };
  int w1, p1, w2, p2;
  compare(meshed, w1, p1);
  compare(separate, w2, p2);
  std::printf("seams: a square as %zu antialiased triangles against the square as one path (8-bit levels):\n"
              "  mesh accumulation: max difference %d, pixels off by more than 1: %d\n"
              "  triangles composited one by one: max difference %d, pixels off by more than 1: %d\n\n",
              mesh.triangles.size(), w1, p1, w2, p2);
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 5, size = 1024;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--size" && i + 1 < argc) {
      size = std::clamp(std::atoi(argv[++i]), 64, 4096);
    } else {
      std::fprintf(stderr, "usage: vraster_mesh_bench [--frames N] [--size PX]\n");
      return 2;
    }
  }
  report_seams(16);
  std::printf("%d x %d, median ms per frame of %d (single thread)\n\n", size, size, frames);
  std::printf("| scene | triangles | engine | ms | vs vraster mesh |\n| --- | ---: | --- | ---: | ---: |\n");
  const Scene scenes[] = {grid_scene(100, size), grid_scene(224, size), sphere_scene(size)};
  for (const Scene& s : scenes) {
    const std::vector<Color> colors = flat_colors(s);
    const std::vector<std::size_t> order = draw_order(s);
    const auto& tris = s.mesh.triangles;
    const auto& verts = s.mesh.vertices;

    Image image(size, size);
    MeshRenderer mesh_renderer;
    Renderer renderer;
    std::vector<Path> paths;
    for (const std::size_t k : order) {
      Path p;
      p.move_to(verts[tris[k][0]].position.x, verts[tris[k][0]].position.y);
      p.line_to(verts[tris[k][1]].position.x, verts[tris[k][1]].position.y);
      p.line_to(verts[tris[k][2]].position.x, verts[tris[k][2]].position.y);
      p.close();
      paths.push_back(std::move(p));
    }
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, size, size);
    cairo_t* cr = cairo_create(surface);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
    cairo_pattern_t* pattern = cairo_pattern_create_mesh();
    for (const std::size_t k : order) {
      cairo_mesh_pattern_begin_patch(pattern);
      cairo_mesh_pattern_move_to(pattern, verts[tris[k][0]].position.x, verts[tris[k][0]].position.y);
      cairo_mesh_pattern_line_to(pattern, verts[tris[k][1]].position.x, verts[tris[k][1]].position.y);
      cairo_mesh_pattern_line_to(pattern, verts[tris[k][2]].position.x, verts[tris[k][2]].position.y);
      Lighting light;
      light.enabled = s.lit;
      for (int c = 0; c < 3; ++c) {
        const MeshVertex& v = verts[tris[k][static_cast<std::size_t>(c)]];
        const Color lit = shade(light, v.color, v.normal, v.eye);
        cairo_mesh_pattern_set_corner_color_rgb(pattern, static_cast<unsigned>(c), lit.r, lit.g, lit.b);
      }
      cairo_mesh_pattern_end_patch(pattern);
    }
    MeshOptions mesh_options;
    mesh_options.depth = s.depth ? DepthMode::ZBuffer : DepthMode::None;
    mesh_options.lighting.enabled = s.lit;
    std::vector<Engine> engines;
    const Color white{1, 1, 1, 1};
    engines.push_back({"vraster mesh, Gouraud" + std::string(s.depth ? ", z-buffer" : ""), [&] {
                         image.clear(white);
                         mesh_renderer.draw(image, s.mesh, mesh_options);
                       }});
    if (s.depth) {
      engines.push_back({"vraster mesh, Gouraud, painter's", [&] {
                           image.clear(white);
                           MeshOptions o = mesh_options;
                           o.depth = DepthMode::Painter;
                           mesh_renderer.draw(image, s.mesh, o);
                         }});
    }
    engines.push_back({"vraster mesh, Phong" + std::string(s.depth ? ", z-buffer" : ""), [&] {
                         image.clear(white);
                         MeshOptions o = mesh_options;
                         o.shading = Shading::Phong;
                         mesh_renderer.draw(image, s.mesh, o);
                       }});
    engines.push_back({"vraster mesh, Gouraud, antialiased" + std::string(s.depth ? ", z-buffer" : ""), [&] {
                         image.clear(white);
                         MeshOptions o = mesh_options;
                         o.antialias = true;
                         mesh_renderer.draw(image, s.mesh, o);
                       }});
    engines.push_back({"vraster paths (solid, analytic AA)", [&] {
                         image.clear(white);
                         FillOptions fo;
                         for (std::size_t i = 0; i < paths.size(); ++i) {
                           renderer.fill(image, paths[i], Affine{}, colors[order[i]], fo);
                         }
                       }});
    engines.push_back({"Cairo mesh pattern (Gouraud patches)", [&] {
                         cairo_set_source_rgb(cr, 1, 1, 1);
                         cairo_paint(cr);
                         cairo_set_source(cr, pattern);
                         cairo_paint(cr);
                         cairo_surface_flush(surface);
                       }});
    engines.push_back({"Cairo paths (solid, AA)", [&] {
                         cairo_set_source_rgb(cr, 1, 1, 1);
                         cairo_paint(cr);
                         for (std::size_t i = 0; i < paths.size(); ++i) {
                           const auto& t = tris[order[i]];
                           cairo_move_to(cr, verts[t[0]].position.x, verts[t[0]].position.y);
                           cairo_line_to(cr, verts[t[1]].position.x, verts[t[1]].position.y);
                           cairo_line_to(cr, verts[t[2]].position.x, verts[t[2]].position.y);
                           cairo_close_path(cr);
                           const Color c = colors[order[i]];
                           cairo_set_source_rgb(cr, c.r, c.g, c.b);
                           cairo_fill(cr);
                         }
                         cairo_surface_flush(surface);
                       }});
    for (Engine& e : engines) e.frame();  // warm-up
    for (int f = 0; f < frames; ++f) {
      for (Engine& e : engines) {
        const auto t0 = Clock::now();
        e.frame();
        e.ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      }
    }
    auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    const double base = median(engines[0].ms);
    for (Engine& e : engines) {
      const double m = median(e.ms);
      std::printf("| %s | %zu | %s | %.2f | %.2fx |\n", s.name.c_str(), tris.size(), e.name.c_str(), m, m / base);
    }
    std::fflush(stdout);
    cairo_pattern_destroy(pattern);
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
  return 0;
}
