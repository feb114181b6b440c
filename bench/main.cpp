// vraster_bench: renders the shared benchmark scenes with vraster, Cairo, FreeType's smooth rasterizer and (when
// built with -DVRASTER_BENCH_BLEND2D_ROOT) Blend2D in the same run, one thread each, plus vraster with --threads N
// threads (default 2), and prints ms per frame as a Markdown table: the best of rounds (default) or the median.
//
//   vraster_bench [SCENE_DIR | --generated] [--frames N] [--time SECONDS] [--scene NAME]... [--threads N] [--check]
//                 [--no-timing] [--out DIR]
//
// --generated renders the scenes of generated_scenes.cpp instead of a folder's: shapes the shared scenes lack, to
// check a speed-up beyond the scenes it was tuned on.
//
// A frame is: clear to white + fill every path in file order (source-over, antialiased) + flush. Parsing and
// path building happen before timing. Each engine renders 1 warm-up frame, then frames in batches of ~0.1 s,
// the engines taking turns (so a burst of load from other processes hits all of them), until each has
// rendered N frames (--frames) or at least 5 frames and --time seconds (default 0.5). A round is one engine's batch:
// its median is what the engine did in that stretch of time, and the best round (--stat best, the default) is the
// figure least touched by other load on the machine; --stat median gives the median of all timed frames instead.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "engines.hpp"
#include "generated_scenes.hpp"
#include "svg_subset/svg.hpp"
#include "vraster/png.hpp"

namespace fs = std::filesystem;
using bench::Engine;

namespace {

struct Options {
  std::string scene_dir = std::string(VRASTER_SOURCE_DIR) + "/../shared/bench/scenes";
  int frames = 0;  // 0: time-based
  double seconds = 0.5;
  std::vector<std::string> scenes;
  int threads = 2;  // the threaded vraster column; 1: none
  bool check = false;
  bool timing = true;
  bool best_of_rounds = true;  // --stat best (default) or median
  std::string out_dir;
  bool generated = false;  // the built-in scenes (generated_scenes.cpp) instead of scene_dir's
  double tolerance = vraster::kDefaultTolerance;  // curve flattening, for every engine that takes one
};

[[noreturn]] void usage(int status) {
  std::fprintf(status ? stderr : stdout,
               "usage: vraster_bench [SCENE_DIR] [options]\n"
               "  SCENE_DIR        folder of *.svg scenes (default: <repo>/../shared/bench/scenes)\n"
               "  --generated      the built-in generated scenes instead of a folder's (discs, rings, ellipses,\n"
               "                   rectangles, turned rectangles, opaque ones, opaque triangles, thin lines)\n"
               "  --frames N       timed frames per engine and scene (default: >= 5 frames and --time)\n"
               "  --time SECONDS   minimum timed seconds per engine and scene (default 0.5)\n"
               "  --scene NAME     only this scene (file name without .svg); repeatable, or comma-separated\n"
               "  --threads N      add vraster with N threads (default 2; 1: no such column)\n"
               "  --tolerance PX   curves flattened to within PX device pixels by vraster, Cairo and Blend2D alike\n"
               "                   (default 0.1, vraster's and Cairo's default; Blend2D's own is 0.2)\n"
               "  --check          compare vraster's image with the other engines' per scene (and the threaded\n"
               "                   vraster's with vraster's: it must be identical)\n"
               "  --stat best|median  best of rounds (default: the lowest of the per-batch medians) or the median\n"
               "                   of all timed frames\n"
               "  --no-timing      render one frame per engine only (with --check or --out)\n"
               "  --out DIR        write DIR/SCENE.ENGINE.png for every scene and engine\n");
  std::exit(status);
}

Options parse_args(int argc, char** argv) {
  Options o;
  bool dir_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "vraster_bench: %s needs a value\n", a.c_str());
        usage(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      usage(0);
    } else if (a == "--frames") {
      o.frames = std::atoi(value().c_str());
      if (o.frames < 1) {
        std::fprintf(stderr, "vraster_bench: --frames needs a positive number\n");
        usage(2);
      }
    } else if (a == "--time") {
      o.seconds = std::atof(value().c_str());
      if (!(o.seconds > 0)) {
        std::fprintf(stderr, "vraster_bench: --time needs a positive number of seconds\n");
        usage(2);
      }
    } else if (a == "--scene") {
      std::string list = value();
      std::size_t start = 0;
      while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        if (comma > start) o.scenes.push_back(list.substr(start, comma - start));
        start = comma + 1;
      }
    } else if (a == "--threads") {
      o.threads = std::atoi(value().c_str());
      if (o.threads < 1 || o.threads > 64) {
        std::fprintf(stderr, "vraster_bench: --threads needs a number from 1 to 64\n");
        usage(2);
      }
    } else if (a == "--tolerance") {
      o.tolerance = std::atof(value().c_str());
      if (!(o.tolerance > 0) || !std::isfinite(o.tolerance)) {
        std::fprintf(stderr, "vraster_bench: --tolerance needs a positive number of pixels\n");
        usage(2);
      }
    } else if (a == "--check") {
      o.check = true;
    } else if (a == "--stat") {
      const std::string v = value();
      if (v != "best" && v != "median") {
        std::fprintf(stderr, "vraster_bench: --stat is best or median, not %s\n", v.c_str());
        usage(2);
      }
      o.best_of_rounds = v == "best";
    } else if (a == "--generated") {
      o.generated = true;
    } else if (a == "--no-timing") {
      o.timing = false;
    } else if (a == "--out") {
      o.out_dir = value();
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "vraster_bench: unknown option %s\n", a.c_str());
      usage(2);
    } else if (!dir_given) {
      o.scene_dir = a;
      dir_given = true;
    } else {
      std::fprintf(stderr, "vraster_bench: more than one scene folder given\n");
      usage(2);
    }
  }
  if (o.generated && dir_given) {
    std::fprintf(stderr, "vraster_bench: give a scene folder or --generated, not both\n");
    usage(2);
  }
  return o;
}

// "poly10_8" < "poly10_16": digit runs compare as numbers.
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      const unsigned long long x = std::stoull(a.substr(i, ie - i)), y = std::stoull(b.substr(j, je - j));
      if (x != y) return x < y;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

using Clock = std::chrono::steady_clock;

double frame_ms(Engine& e, bool& ok) {
  const auto t0 = Clock::now();
  ok = e.frame();
  const auto t1 = Clock::now();
  return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Diff {
  double mean = 0;        // mean absolute difference per channel (0..255)
  int max = 0;            // largest channel difference
  std::size_t over = 0;   // pixels with some channel differing by more than 16
  int worst_x = -1, worst_y = -1;  // where `max` first occurs
};

Diff compare(const vraster::Image& a, const vraster::Image& b) {
  Diff d;
  if (a.width != b.width || a.height != b.height) {
    d.mean = -1;
    return d;
  }
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < a.data.size(); i += 4) {
    int pixel_max = 0;
    for (int c = 0; c < 4; ++c) {
      const int diff = std::abs(int{a.data[i + c]} - int{b.data[i + c]});
      sum += static_cast<unsigned>(diff);
      pixel_max = std::max(pixel_max, diff);
    }
    if (pixel_max > d.max) {
      d.max = pixel_max;
      d.worst_x = static_cast<int>((i / 4) % static_cast<std::size_t>(a.width));
      d.worst_y = static_cast<int>((i / 4) / static_cast<std::size_t>(a.width));
    }
    if (pixel_max > 16) ++d.over;
  }
  d.mean = static_cast<double>(sum) / static_cast<double>(a.data.size());
  return d;
}

std::string fmt_ms(double ms) {
  char buf[32];
  if (ms < 10) {
    std::snprintf(buf, sizeof buf, "%.2f", ms);
  } else if (ms < 100) {
    std::snprintf(buf, sizeof buf, "%.1f", ms);
  } else {
    std::snprintf(buf, sizeof buf, "%.0f", ms);
  }
  return buf;
}

std::string fmt_ratio(double r) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", r);
  return buf;
}

double geomean(const std::vector<double>& v) {
  if (v.empty()) return 0;
  double s = 0;
  for (double x : v) s += std::log(x);
  return std::exp(s / static_cast<double>(v.size()));
}

// Anchor figures from ../shared/bench/README.md (median ms per frame on this class of machine; the scenes are
// generated from fixed seeds and never change). 0 = fails.
struct Anchor {
  double cairo, agg, freetype, blend2d;
};
const std::map<std::string, Anchor> kAnchors = {
    {"poly10_8", {7.75, 2.90, 3.52, 1.14}},     {"poly10_16", {12.2, 5.46, 5.09, 1.57}},
    {"poly10_32", {20.2, 10.9, 8.36, 2.51}},    {"poly10_64", {35.5, 21.3, 15.8, 5.20}},
    {"poly10_128", {61.2, 41.2, 33.2, 10.8}},   {"poly10_256", {116, 82.3, 76.3, 23.0}},
    {"cubic_16", {13.2, 4.74, 5.00, 3.18}},     {"cubic_64", {43.2, 16.7, 13.7, 6.95}},
    {"cubic_256", {145, 60.9, 54.8, 22.1}},     {"star_big", {220, 167, 0, 7.97}},
    {"star_big_nz", {154, 162, 0, 8.02}},       {"tiny_many", {18.6, 9.99, 36.4, 9.04}},
    {"text_outlines", {8.13, 3.07, 3.28, 1.49}}, {"thin_slivers", {42.0, 56.1, 59.7, 13.9}},
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown CPU";
}

struct Result {
  std::string scene;
  int pixels_w = 0, pixels_h = 0;
  std::size_t items = 0;
  std::vector<std::optional<double>> ms;  // per engine; nothing = failed
  std::vector<int> frames;
  std::vector<std::string> errors;
  std::optional<Diff> vs_cairo, vs_freetype, cairo_vs_freetype, vs_blend2d, threaded_vs_one;
  std::string worst;  // where the largest differences are, with the pixels of each engine
};

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse_args(argc, argv);

  // A scene: SVG text (generated) or a file.
  struct Scene {
    std::string name;
    fs::path file;
    std::string svg;
  };
  std::vector<Scene> scenes;
  const std::string source = opt.generated ? std::string("the generated scenes") : opt.scene_dir;
  auto wanted = [&](const std::string& name) {
    return opt.scenes.empty() || std::find(opt.scenes.begin(), opt.scenes.end(), name) != opt.scenes.end();
  };
  if (opt.generated) {
    for (bench::GeneratedScene& g : bench::generated_scenes()) {
      if (wanted(g.name)) scenes.push_back({g.name, {}, std::move(g.svg)});
    }
  } else {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(opt.scene_dir, ec)) {
      if (entry.path().extension() != ".svg") continue;
      const std::string name = entry.path().stem().string();
      if (wanted(name)) scenes.push_back({name, entry.path(), {}});
    }
    if (ec) {
      std::fprintf(stderr, "vraster_bench: cannot read scene folder %s: %s\n", opt.scene_dir.c_str(),
                   ec.message().c_str());
      return 1;
    }
  }
  for (const std::string& name : opt.scenes) {
    if (std::none_of(scenes.begin(), scenes.end(), [&](const Scene& s) { return s.name == name; })) {
      std::fprintf(stderr, "vraster_bench: no scene %s in %s\n", name.c_str(), source.c_str());
      return 1;
    }
  }
  if (scenes.empty()) {
    std::fprintf(stderr, "vraster_bench: no *.svg scenes in %s\n", source.c_str());
    return 1;
  }
  std::sort(scenes.begin(), scenes.end(), [](const Scene& a, const Scene& b) { return natural_less(a.name, b.name); });
  if (!opt.out_dir.empty()) fs::create_directories(opt.out_dir);

  std::vector<std::unique_ptr<Engine>> engines;
  engines.push_back(bench::make_vraster_engine());
  engines.push_back(bench::make_cairo_engine());
  engines.push_back(bench::make_freetype_engine());
  constexpr std::size_t kVraster = 0, kCairo = 1, kFreeType = 2, kNone = ~std::size_t{0};
  std::size_t kBlend2D = kNone, kThreaded = kNone;
#ifdef VRASTER_BENCH_WITH_BLEND2D
  kBlend2D = engines.size();
  engines.push_back(bench::make_blend2d_engine());
#endif
  const bool kHaveBlend2D = kBlend2D != kNone;
  if (opt.threads > 1) {
    kThreaded = engines.size();
    engines.push_back(bench::make_vraster_engine(opt.threads));
  }
  const bool have_threaded = kThreaded != kNone;
  for (const auto& engine : engines) engine->set_tolerance(opt.tolerance);
  const std::size_t E = engines.size();

  std::vector<Result> results;
  bool load_failed = false;
  for (const Scene& scene : scenes) {
    const std::string& name = scene.name;
    vraster::svg::Document doc;
    try {
      doc = scene.svg.empty() ? vraster::svg::load_svg(scene.file.string()) : vraster::svg::parse_svg(scene.svg, name);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vraster_bench: %s: cannot load: %s\n", name.c_str(), e.what());
      load_failed = true;
      continue;
    }
    Result r;
    r.scene = name;
    r.pixels_w = doc.width;
    r.pixels_h = doc.height;
    r.items = static_cast<std::size_t>(
        std::count_if(doc.items.begin(), doc.items.end(), [](const auto& item) { return item.is_fill(); }));
    r.ms.assign(E, std::nullopt);
    r.frames.assign(E, 0);
    r.errors.assign(E, "");
    std::fprintf(stderr, "%s (%dx%d, %zu paths):", name.c_str(), doc.width, doc.height, r.items);
    std::fflush(stderr);

    // Prepare and warm up every engine.
    std::vector<bool> ok(E, true);
    std::vector<double> warm(E, 0);
    for (std::size_t k = 0; k < E; ++k) {
      try {
        engines[k]->prepare(doc);
        bool good = false;
        warm[k] = frame_ms(*engines[k], good);
        if (!good) {
          ok[k] = false;
          r.errors[k] = engines[k]->error();
        }
      } catch (const std::exception& e) {
        ok[k] = false;
        r.errors[k] = e.what();
      }
    }

    // Timed frames: engines take turns in batches of about 0.1 s.
    std::vector<std::vector<double>> times(E);
    std::vector<double> best_round(E, std::numeric_limits<double>::infinity());
    if (opt.timing) {
      std::vector<int> needed(E, 0), batch(E, 1);
      for (std::size_t k = 0; k < E; ++k) {
        if (!ok[k]) continue;
        const double est = std::max(warm[k], 1e-3);
        needed[k] = opt.frames > 0 ? opt.frames
                                   : std::clamp(static_cast<int>(std::ceil(opt.seconds * 1000.0 / est)), 5, 20000);
        batch[k] = std::max(1, static_cast<int>(100.0 / est));
        times[k].reserve(static_cast<std::size_t>(needed[k]));
      }
      bool more = true;
      while (more) {
        more = false;
        for (std::size_t k = 0; k < E; ++k) {
          const int todo = std::min(batch[k], needed[k] - static_cast<int>(times[k].size()));
          const std::size_t first = times[k].size();
          for (int i = 0; i < todo && ok[k]; ++i) {
            bool good = false;
            times[k].push_back(frame_ms(*engines[k], good));
            if (!good) {
              ok[k] = false;
              r.errors[k] = engines[k]->error();
            }
          }
          if (ok[k] && times[k].size() > first) {
            const std::vector<double> round(times[k].begin() + static_cast<std::ptrdiff_t>(first), times[k].end());
            best_round[k] = std::min(best_round[k], median(round));
          }
          if (ok[k] && static_cast<int>(times[k].size()) < needed[k]) more = true;
        }
      }
    }
    for (std::size_t k = 0; k < E; ++k) {
      if (!ok[k]) {
        std::fprintf(stderr, " %s fails (%s)", engines[k]->name(), r.errors[k].c_str());
        continue;
      }
      r.frames[k] = static_cast<int>(times[k].size());
      r.ms[k] = !opt.timing ? warm[k] : opt.best_of_rounds ? best_round[k] : median(times[k]);
      if (opt.timing) {
        std::fprintf(stderr, " %s %s ms (%d frames)", engines[k]->name(), fmt_ms(*r.ms[k]).c_str(), r.frames[k]);
      } else {
        std::fprintf(stderr, " %s %s ms (1 cold frame)", engines[k]->name(), fmt_ms(*r.ms[k]).c_str());
      }
    }
    std::fprintf(stderr, "\n");

    if (opt.check || !opt.out_dir.empty()) {
      std::vector<std::optional<vraster::Image>> images(E);
      for (std::size_t k = 0; k < E; ++k) {
        if (ok[k]) images[k] = engines[k]->image();
      }
      if (opt.check && images[kVraster]) {
        if (images[kCairo]) r.vs_cairo = compare(*images[kVraster], *images[kCairo]);
        if (images[kFreeType]) r.vs_freetype = compare(*images[kVraster], *images[kFreeType]);
      }
      if (opt.check && images[kCairo] && images[kFreeType]) {
        r.cairo_vs_freetype = compare(*images[kCairo], *images[kFreeType]);
      }
      if (opt.check && images[kVraster] && kHaveBlend2D && images[kBlend2D]) {
        r.vs_blend2d = compare(*images[kVraster], *images[kBlend2D]);
      }
      if (opt.check && images[kVraster] && have_threaded && images[kThreaded]) {
        r.threaded_vs_one = compare(*images[kThreaded], *images[kVraster]);
      }
      if (opt.check) {
        auto px = [&](int x, int y) {
          std::string s;
          for (std::size_t k = 0; k < E; ++k) {
            if (!images[k]) continue;
            const std::uint8_t* p = images[k]->pixel(x, y);
            char buf[64];
            std::snprintf(buf, sizeof buf, " %s=(%d,%d,%d,%d)", engines[k]->name(), p[0], p[1], p[2], p[3]);
            s += buf;
          }
          return s;
        };
        for (const auto& [label, d] : {std::pair{"vraster/cairo", r.vs_cairo}, std::pair{"vraster/freetype", r.vs_freetype},
                                       std::pair{"vraster/blend2d", r.vs_blend2d}}) {
          if (d && d->max > 0) {
            r.worst += std::string(r.worst.empty() ? "" : "; ") + label + " max at (" + std::to_string(d->worst_x) +
                       "," + std::to_string(d->worst_y) + "):" + px(d->worst_x, d->worst_y);
          }
        }
      }
      if (!opt.out_dir.empty()) {
        for (std::size_t k = 0; k < E; ++k) {
          if (!images[k]) continue;
          const std::string png = (fs::path(opt.out_dir) / (name + "." + engines[k]->name() + ".png")).string();
          try {
            vraster::write_png(png, *images[k]);
          } catch (const std::exception& e) {
            std::fprintf(stderr, "vraster_bench: %s\n", e.what());
          }
        }
      }
    }
    results.push_back(std::move(r));
  }

  // ---- Report (stdout, Markdown).
  const std::string method =
      !opt.timing ? std::string("--no-timing: one cold frame per engine, not timed")
      : (opt.best_of_rounds ? std::string("best of rounds (lowest per-batch median, batches of about 0.1 s, engines "
                                          "taking turns) in ms per frame")
                            : std::string("median ms per frame")) +
            (opt.frames > 0 ? " of " + std::to_string(opt.frames) + " frames after 1 warm-up"
                            : " after 1 warm-up, at least 5 frames and " + fmt_ms(opt.seconds) + " s per engine and scene");
  std::printf("%s; %s%s%s; %s; %u hardware threads, 1 used per engine%s; curves flattened to %s px (vraster, "
              "Cairo%s); %s.\n\n",
              engines[kCairo]->version().c_str(),
              engines[kFreeType]->version().c_str(), kHaveBlend2D ? "; " : "",
              kHaveBlend2D ? engines[kBlend2D]->version().c_str() : "", cpu_model().c_str(),
              std::thread::hardware_concurrency(),
              have_threaded ? (" (" + std::to_string(opt.threads) + " for " + engines[kThreaded]->name() + ")").c_str()
                            : "",
              fmt_ms(opt.tolerance).c_str(), kHaveBlend2D ? ", Blend2D" : "", method.c_str());

  if (opt.timing) {
    // One table: every engine's ms, then vraster's ratio to each (one thread each), then the threaded speed-up.
    auto cell = [](const std::optional<double>& v) { return v ? fmt_ms(*v) : std::string("fails"); };
    std::vector<std::size_t> columns = {kVraster};
    if (have_threaded) columns.push_back(kThreaded);
    columns.insert(columns.end(), {kCairo, kFreeType});
    if (kHaveBlend2D) columns.push_back(kBlend2D);
    // Ratios: other / vraster for Cairo and FreeType (> 1: vraster is faster); vraster / Blend2D as issue 17 states
    // its target (<= 1: vraster is as fast or faster); one thread / N threads for the speed-up.
    struct Ratio {
      std::string label;
      std::size_t num, den;
    };
    std::vector<Ratio> ratios = {{"cairo/vraster", kCairo, kVraster}, {"freetype/vraster", kFreeType, kVraster}};
    if (kHaveBlend2D) ratios.push_back({"vraster/blend2d", kVraster, kBlend2D});
    if (have_threaded) ratios.push_back({"speed-up " + std::string(engines[kThreaded]->name()), kVraster, kThreaded});
    std::printf("| scene |");
    for (const std::size_t k : columns) std::printf(" %s ms |", engines[k]->name());
    for (const Ratio& q : ratios) std::printf(" %s |", q.label.c_str());
    std::printf("\n| --- |");
    for (std::size_t i = 0; i < columns.size() + ratios.size(); ++i) std::printf(" ---: |");
    std::printf("\n");
    std::vector<std::vector<double>> ms_of(E), ratio_of(ratios.size());
    for (const Result& r : results) {
      std::printf("| %s |", r.scene.c_str());
      for (const std::size_t k : columns) {
        if (r.ms[k]) ms_of[k].push_back(*r.ms[k]);
        std::printf(" %s |", cell(r.ms[k]).c_str());
      }
      for (std::size_t i = 0; i < ratios.size(); ++i) {
        const auto& a = r.ms[ratios[i].num];
        const auto& b = r.ms[ratios[i].den];
        if (a && b) {
          ratio_of[i].push_back(*a / *b);
          std::printf(" %s |", fmt_ratio(*a / *b).c_str());
        } else {
          std::printf(" - |");
        }
      }
      std::printf("\n");
    }
    std::printf("| **geometric mean** |");
    for (const std::size_t k : columns) std::printf(" %s |", ms_of[k].empty() ? "-" : fmt_ms(geomean(ms_of[k])).c_str());
    for (const auto& v : ratio_of) std::printf(" **%s** |", v.empty() ? "-" : fmt_ratio(geomean(v)).c_str());
    std::printf("\n\ncairo/vraster, freetype/vraster > 1: vraster is faster; vraster/blend2d < 1: vraster is faster "
                "(single-threaded, same run). Geometric means of ms are over the scenes each engine renders "
                "(FreeType's excludes its failures); ratio means are over the scenes both engines render.\n");

    // Without Blend2D in the run: vraster's speed-up over FreeType (and Cairo), measured here, next to Blend2D's in
    // ../shared/bench/README.md. "vs Blend2D" = our ratio / Blend2D's ratio (> 1: we would be faster).
    bool any_anchor = false;
    for (const Result& r : results) any_anchor = any_anchor || kAnchors.count(r.scene);
    if (any_anchor && !kHaveBlend2D) {
      std::printf("\n| scene | freetype/vraster | freetype/Blend2D (anchor) | vs Blend2D via FreeType | cairo/vraster | "
                  "cairo/Blend2D (anchor) | vs Blend2D via Cairo |\n");
      std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
      std::vector<double> vf, vc;
      for (const Result& r : results) {
        const auto it = kAnchors.find(r.scene);
        if (it == kAnchors.end()) continue;
        const Anchor& a = it->second;
        std::string ours_f = "-", theirs_f = a.freetype > 0 ? fmt_ratio(a.freetype / a.blend2d) : "fails", rel_f = "-";
        std::string ours_c = "-", theirs_c = fmt_ratio(a.cairo / a.blend2d), rel_c = "-";
        if (r.ms[kVraster] && r.ms[kFreeType]) {
          const double ours = *r.ms[kFreeType] / *r.ms[kVraster];
          ours_f = fmt_ratio(ours);
          if (a.freetype > 0) {
            const double rel = ours / (a.freetype / a.blend2d);
            rel_f = fmt_ratio(rel);
            vf.push_back(rel);
          }
        }
        if (r.ms[kVraster] && r.ms[kCairo]) {
          const double ours = *r.ms[kCairo] / *r.ms[kVraster];
          ours_c = fmt_ratio(ours);
          const double rel = ours / (a.cairo / a.blend2d);
          rel_c = fmt_ratio(rel);
          vc.push_back(rel);
        }
        std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", r.scene.c_str(), ours_f.c_str(), theirs_f.c_str(),
                    rel_f.c_str(), ours_c.c_str(), theirs_c.c_str(), rel_c.c_str());
      }
      std::printf("| **geometric mean** | | | **%s** | | | **%s** |\n", vf.empty() ? "-" : fmt_ratio(geomean(vf)).c_str(),
                  vc.empty() ? "-" : fmt_ratio(geomean(vc)).c_str());
      std::printf("\n\"vs Blend2D\" > 1: vraster would be faster than Blend2D on this machine class (estimate through "
                  "the anchor engine's ratio).\n");
    }
  }


  if (opt.check) {
    std::printf("\n| scene | vraster vs cairo: mean abs diff | max | px > 16 | vraster vs freetype: mean abs diff | max | "
                "px > 16 |%s (reference) cairo vs freetype: mean | max | px > 16 |%s\n",
                kHaveBlend2D ? " vraster vs blend2d: mean abs diff | max | px > 16 |" : "",
                have_threaded ? " threaded vraster = vraster |" : "");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |%s%s\n",
                kHaveBlend2D ? " ---: | ---: | ---: |" : "", have_threaded ? " :---: |" : "");
    for (const Result& r : results) {
      auto cells = [](const std::optional<Diff>& d) {
        if (!d) return std::string("- | - | -");
        char buf[96];
        std::snprintf(buf, sizeof buf, "%.3f | %d | %zu", d->mean, d->max, d->over);
        return std::string(buf);
      };
      std::printf("| %s | %s | %s |", r.scene.c_str(), cells(r.vs_cairo).c_str(), cells(r.vs_freetype).c_str());
      if (kHaveBlend2D) std::printf(" %s |", cells(r.vs_blend2d).c_str());
      std::printf(" %s |", cells(r.cairo_vs_freetype).c_str());
      if (have_threaded) {
        // Threads must not change a bit.
        std::printf(" %s |", !r.threaded_vs_one ? "-" : r.threaded_vs_one->max == 0 ? "yes" : "**NO**");
      }
      std::printf("\n");
    }
    std::printf("\nDifferences are per 8-bit channel of the premultiplied RGBA frames (0..255); \"px > 16\" counts "
                "pixels where some channel differs by more than 16.\n\nLargest differences (x, y; RGBA of each engine):\n\n");
    for (const Result& r : results) {
      if (!r.worst.empty()) std::printf("- %s: %s\n", r.scene.c_str(), r.worst.c_str());
    }
  }
  return load_failed ? 1 : 0;
}
