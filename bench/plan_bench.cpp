// vraster_plan_bench: what the scene planner saves, and what it costs where nothing can be saved.
//
//   vraster_plan_bench [--frames N] [--scene NAME]... [SCENE.svg...]
//
// A mesh scene (100,000 triangles with depth) shows the planner drawing opaque z-buffered meshes front to back.
// The frame columns redraw the scene into the image it was last drawn into: Canvas::draw_frame clears and draws only the
// tiles touched (the scene touching 5% of the canvas is where that shows).
//
// Each scene is recorded once (Canvas over a Scene) and analysed once (plan_scene, timed on its own), then
// rendered the naive way (draw_scene without a plan) and the planned way (draw_scene with the plan), frame by
// frame alternating, median of N frames each after a warm-up. A third render replays only the calls the plan keeps, naively: the
// difference between it and the planned render is what the culled calls still cost (the target: under 5% of
// what drawing them costs, naive minus kept). SVG files given on the command line (the shared benchmark scenes)
// are scenes where nothing can be skipped: there the planned render should be within 3% of the naive one.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "svg_subset/svg.hpp"
#include "vraster/canvas.hpp"
#include "vraster/mesh_io.hpp"
#include "vraster/scene.hpp"

using namespace vraster;

namespace {

struct BenchScene {
  std::string name, what;
  Scene scene;
};

Scene record(int w, int h, const std::function<void(Canvas&)>& draw) {
  Scene scene;
  scene.width = w;
  scene.height = h;
  Canvas c(scene);
  draw(c);
  return scene;
}

Color random_colour(std::mt19937& rng, float alpha) {
  std::uniform_real_distribution<float> u(0, 1);
  return {u(rng), u(rng), u(rng), alpha};
}

std::vector<BenchScene> built_in() {
  std::vector<BenchScene> out;
  out.push_back({"background_over_10k", "10,000 translucent circles, then an opaque 1024x1024 background over them",
                 record(1024, 1024, [](Canvas& c) {
                   std::mt19937 rng(1);
                   std::uniform_real_distribution<double> pos(0, 1024), rad(4, 40);
                   for (int i = 0; i < 10000; ++i) {
                     c.set_fill_color(random_colour(rng, 0.6f));
                     c.begin_path();
                     c.arc(pos(rng), pos(rng), rad(rng), 0, 6.283185307179586);
                     c.fill();
                   }
                   c.set_fill_color({0.95f, 0.95f, 0.9f, 1});
                   c.fill_rect(0, 0, 1024, 1024);
                   c.set_fill_color({0.2f, 0.3f, 0.6f, 1});
                   c.begin_path();
                   c.arc(512, 512, 300, 0, 6.283185307179586);
                   c.fill();
                 })});
  out.push_back({"group_opacity_disjoint", "a group at opacity 0.5 over 4,096 disjoint circles (64 x 64 grid)",
                 record(1024, 1024, [](Canvas& c) {
                   std::mt19937 rng(2);
                   c.begin_layer(0.5f);
                   for (int y = 0; y < 64; ++y) {
                     for (int x = 0; x < 64; ++x) {
                       c.set_fill_color(random_colour(rng, 1));
                       c.begin_path();
                       c.arc(x * 16 + 8, y * 16 + 8, 6, 0, 6.283185307179586);
                       c.fill();
                     }
                   }
                   c.end_layer();
                 })});
  out.push_back({"rects_100k", "100,000 pixel-aligned rectangles, translucent",
                 record(1024, 1024, [](Canvas& c) {
                   std::mt19937 rng(3);
                   std::uniform_int_distribution<int> pos(0, 1000), size(1, 24);
                   for (int i = 0; i < 100000; ++i) {
                     c.set_fill_color(random_colour(rng, 0.7f));
                     c.fill_rect(pos(rng), pos(rng), size(rng), size(rng));
                   }
                 })});
  out.push_back({"corner_5pct", "2,000 circles inside 5% of the canvas (a 229 x 229 corner), 1,000 outside it",
                 record(1024, 1024, [](Canvas& c) {
                   std::mt19937 rng(4);
                   std::uniform_real_distribution<double> pos(0, 229), far(1100, 3000), rad(2, 12);
                   for (int i = 0; i < 3000; ++i) {
                     c.set_fill_color(random_colour(rng, 0.8f));
                     c.begin_path();
                     if (i % 3 == 2) c.arc(far(rng), pos(rng), rad(rng), 0, 6.283185307179586);
                     else c.arc(pos(rng), pos(rng), rad(rng), 0, 6.283185307179586);
                     c.fill();
                   }
                 })});
  out.push_back({"mesh_100k_depth", "40 lit spheres (Phong, z-buffer) in one mesh of 100,000 triangles, in random order",
                 record(1024, 1024, [](Canvas& c) {
                   std::mt19937 rng(5);
                   std::uniform_real_distribution<double> pos(100, 924), rad(60, 200), depth(0, 40);
                   const MeshModel sphere = make_sphere(25, 50);  // 2,500 triangles
                   Mesh mesh;
                   for (int k = 0; k < 40; ++k) {
                     const double r = rad(rng), cx = pos(rng), cy = pos(rng), dz = depth(rng);
                     const int side = static_cast<int>(2 * r);
                     Camera camera;
                     camera.margin = 0;
                     const Mesh one = project(sphere, camera, side, side, random_colour(rng, 1));
                     const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
                     for (MeshVertex v : one.vertices) {
                       v.position.x += cx - r;
                       v.position.y += cy - r;
                       v.depth += dz;
                       mesh.vertices.push_back(v);
                     }
                     for (const auto& t : one.triangles) mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
                   }
                   MeshOptions options;
                   options.shading = Shading::Phong;
                   options.lighting.enabled = true;
                   c.draw_mesh(mesh, options);
                 })});
  return out;
}

/// An SVG file as a scene: each item through the canvas (a fill or a stroke in its colour).
Scene svg_scene(const std::string& file) {
  const svg::Document doc = svg::load_svg(file);
  return record(doc.width, doc.height, [&](Canvas& c) {
    for (const svg::DrawItem& item : doc.items) {
      c.set_transform(item.transform);
      if (item.is_fill()) {
        c.set_fill_color(item.color);
        c.fill(item.path, item.rule);
      } else {
        c.set_stroke_color(item.color);
        c.set_line_width(item.stroke.width);
        c.set_line_cap(item.stroke.cap);
        c.set_line_join(item.stroke.join);
        c.set_miter_limit(item.stroke.miter_limit);
        c.set_line_dash(item.stroke.dashes);
        c.set_line_dash_offset(item.stroke.dash_offset);
        c.stroke(item.path);
      }
    }
  });
}

double now_ms() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double, std::milli>(clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// The calls the plan keeps, as a scene of their own (with the plan's changes left out: a lower bound).
Scene kept_only(const Scene& scene, const ScenePlan& plan) {
  Scene out;
  out.width = scene.width;
  out.height = scene.height;
  for (std::size_t i = 0; i < scene.commands.size(); ++i) {
    if (plan.decisions[i].action != PlanDecision::Action::Cull) out.commands.push_back(scene.commands[i]);
  }
  return out;
}

void run(const BenchScene& s, int frames) {
  Image image(s.scene.width, s.scene.height);
  Canvas canvas(image);
  const ScenePlan plan = plan_scene(s.scene);
  const Scene kept = kept_only(s.scene, plan);
  std::vector<double> naive, planned, plan_only, kept_times, frame_naive, frame_tiles;
  for (int f = -1; f < frames; ++f) {  // frame -1 warms up
    image.clear(Color::transparent());
    double t0 = now_ms();
    canvas.draw_scene(s.scene);
    const double t_naive = now_ms() - t0;

    t0 = now_ms();
    const ScenePlan p = plan_scene(s.scene);
    const double t_plan = now_ms() - t0;
    image.clear(Color::transparent());
    t0 = now_ms();
    canvas.draw_scene(s.scene, &p);
    const double t_planned = now_ms() - t0;

    image.clear(Color::transparent());
    t0 = now_ms();
    canvas.draw_scene(kept);
    const double t_kept = now_ms() - t0;

    // Whole frames redrawn into one image: everything cleared and drawn naively, against draw_frame, which
    // clears and redraws only the tiles this frame and the one before touch.
    t0 = now_ms();
    image.clear(Color::transparent());
    canvas.draw_scene(s.scene);
    const double t_frame_naive = now_ms() - t0;
    canvas.draw_frame(s.scene, plan, nullptr, Color::transparent());  // the frame before: this scene
    t0 = now_ms();
    canvas.draw_frame(s.scene, plan, &plan, Color::transparent());
    const double t_frame_tiles = now_ms() - t0;
    if (f >= 0) {
      naive.push_back(t_naive);
      planned.push_back(t_planned);
      plan_only.push_back(t_plan);
      kept_times.push_back(t_kept);
      frame_naive.push_back(t_frame_naive);
      frame_tiles.push_back(t_frame_tiles);
    }
  }
  const double n = median(naive), p = median(planned), k = median(kept_times), pl = median(plan_only);
  const double culled_work = n - k;
  char overhead[32] = "-";
  if (plan.culled > 0 && culled_work > 0) std::snprintf(overhead, sizeof overhead, "%.1f%%", 100 * (p - k) / culled_work);
  const double fn = median(frame_naive), ft = median(frame_tiles);
  std::printf("| %s | %zu | %d | %d+%d | %.2f | %.2f | %.2f | %.3f | %.2f | %s | %d/%d | %.2f | %.2f | %.2f | %s |\n",
              s.name.c_str(), s.scene.commands.size(), plan.culled, plan.layers_dropped, plan.layers_folded, n, p, k,
              pl, n / p, overhead, plan.touched_tile_count(), plan.tiles_x * plan.tiles_y, fn, ft, fn / ft,
              s.what.c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 9;
  std::vector<std::string> wanted, files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--scene" && i + 1 < argc) {
      wanted.push_back(argv[++i]);
    } else if (!a.empty() && a[0] != '-') {
      files.push_back(a);
    } else {
      std::fprintf(stderr, "usage: vraster_plan_bench [--frames N] [--scene NAME]... [SCENE.svg...]\n");
      return 2;
    }
  }
  std::printf("frames %d (median); ms per frame; planned = draw_scene(plan), the plan made once (plan ms)\n\n", frames);
  std::printf("frame ms: the same scene redrawn into one image, cleared whole and drawn naively, against draw_frame "
              "(clears and draws only the tiles touched)\n\n");
  std::printf("| scene | calls | culled | layers dropped+folded | naive ms | planned ms | kept-only ms | plan ms | "
              "naive / planned | culled calls' cost | tiles touched | frame ms naive | frame ms tiles | ratio | what |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  try {
    for (const BenchScene& s : built_in()) {
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), s.name) == wanted.end()) continue;
      run(s, frames);
    }
    for (const std::string& f : files) {
      const std::string name = f.substr(f.find_last_of('/') + 1);
      run(BenchScene{name, "shared scene (nothing to skip)", svg_scene(f)}, frames);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vraster_plan_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
