// vraster: command-line front end.
//
//   vraster render IN.svg -o OUT.png [options]   SVG subset -> PNG
//   vraster demo [-o FILE]                        an embedded scene -> PNG
//
// Errors: a message naming the problem on stderr, exit status 2, and no output file.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "cli/image_compare.hpp"
#include "svg_subset/draw.hpp"
#include "svg_subset/scene.hpp"
#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"
#include "vraster/canvas.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/files.hpp"
#include "vraster/vraster.hpp"
#if VRASTER_WITH_TEXT
#include "vraster_text/cli.hpp"
#include "vraster_text/font_db.hpp"
#endif

namespace vraster::cli {
namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  vraster render IN.svg -o OUT.png [-w|--width W] [-h|--height H] [--quiet] [--aa MODE] [--rule RULE]\n"
    "                 [--tolerance T] [--depth 8|16] [--background COLOR|transparent] [--bench N]\n"
    "                 [--threads N]   (large fills in bands on N threads, 1 to 64; same pixels)\n"
    "                 [--hairline bresenham|dda|wu|analytic]   (every stroke as a 1-px hairline)\n"
    "                 [--allow-dir DIR]   (<image> files may come from DIR too, not only IN.svg's folder)\n"
    "                 [--no-plan]   (replay every draw call as recorded: no culling, no layer folding)\n"
    "                 [--font-dir DIR]... [--no-system-fonts] [--serif-family F] [--sans-serif-family F]\n"
    "                 [--monospace-family F] [--cursive-family F] [--fantasy-family F] [--default-family F]\n"
    "                 [--default-font-size PX]   (fonts for <text>: DIRs, then the system's via fontconfig)\n"
    "  vraster explain IN.svg [--json] [render's size, --aa, --allow-dir and font options]   (the render plan)\n"
    "  vraster fill-rules IN.svg -o SHEET.png [--winding] [--aa MODE] [--panel PX]\n"
    "  vraster text \"TEXT\" -o OUT.png [--font FILE]... [--face-index N] [--size PX] [--width W]\n"
    "               [--align left|center|right] [--line-height PX] [--color C] [--background C] [--aa MODE]\n"
    "               [--features F] [--lang L] [--script S] [--dir auto|ltr|rtl] [--hinting none|light]\n"
    "               [--margin PX] [--font-dir DIR]... [--no-system-fonts]\n"
    "  vraster accuracy [SCENE.svg...] -o DIR [--frames N] [--max-side PX]   (AA methods: time vs error)\n"
    "  vraster compare REFERENCE.png OURS.png [--diff DIFF.png]   (the conformance pass rule)\n"
    "  vraster mesh IN.vmesh|IN.obj -o OUT.png [--shading flat|gouraud|phong] [--depth zbuffer|painter|none]\n"
    "               [--aa] [--cull] [--camera ortho|perspective] [--yaw DEG] [--pitch DEG] [--distance D]\n"
    "               [--width PX] [--height PX] [--bits 8|16] [--background #rrggbb|transparent]\n"
    "  vraster shading -o SHEET.png [--panel PX] [--aa]   (flat / Gouraud / Phong on a sphere and a torus)\n"
    "  vraster depth -o SHEET.png [--panel PX] [--aa]     (painter's algorithm beside the z-buffer)\n"
    "  vraster demo [-o FILE]\n"
    "MODE: none | analytic | exact | ssaa-2|4|8|16 | msaa-4|8|16 | fxaa\n"
    "RULE: evenodd | nonzero | nonexterior | positive | negative | abs-geq-2 (overrides the file's fill-rule)\n";

struct RenderArgs {
  std::string input;
  std::string output;
  svg::RenderSettings settings;
  AntiAliasMethod aa;  ///< --aa: settings.aa is its coverage mode; the post-filter runs on each finished frame
  int depth = 8;
  Color background = Color::transparent();
  int bench_frames = 0;
  int threads = 1;            ///< --threads: band threads of the renderer / canvas
  int width = 0, height = 0;  ///< requested output size (0: from the document)
  bool quiet = false;         ///< no warnings on stderr
  // Fonts for <text>.
  std::vector<std::string> font_dirs;
  bool system_fonts = true;
  std::vector<std::pair<std::string, std::string>> generic_families;  ///< (generic name, family)
  std::string default_family = "serif";
  double default_font_size = 16;
  bool help = false;
  bool plan = true;           ///< --no-plan: replay the recorded scene naively
  bool json = false;          ///< explain --json
  std::string allow_dir;      ///< --allow-dir: a wider folder <image> files may come from
};

double parse_number(std::string_view flag, std::string_view text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
    throw UsageError{std::string(flag) + ": " + quoted(text) + " is not a number"};
  }
  return v;
}

class ArgReader {
 public:
  ArgReader(int argc, char** argv, int first) : args_(argv + first, argv + argc) {}
  bool done() const { return i_ >= args_.size(); }
  std::string_view next() { return args_[i_++]; }
  std::string_view value(std::string_view flag) {
    if (done()) throw UsageError{std::string(flag) + " needs a value"};
    return next();
  }

 private:
  std::vector<std::string_view> args_;
  std::size_t i_ = 0;
};

RenderArgs parse_render_args(int argc, char** argv) {
  RenderArgs a;
  ArgReader r(argc, argv, 2);
  while (!r.done()) {
    const std::string_view arg = r.next();
    if (arg == "-o" || arg == "--output") {
      a.output = r.value(arg);
    } else if (arg == "--help") {
      a.help = true;
      return a;
    } else if (arg == "-w" || arg == "--width" || arg == "-h" || arg == "--height") {
      const double n = parse_number(arg, r.value(arg));
      if (!(n >= 1 && n <= kMaxImageSide) || n != std::floor(n)) {
        throw UsageError{std::string(arg) + " needs a whole number of pixels from 1 to " +
                         std::to_string(kMaxImageSide)};
      }
      (arg == "-w" || arg == "--width" ? a.width : a.height) = static_cast<int>(n);
    } else if (arg == "--allow-dir") {
      a.allow_dir = r.value(arg);
    } else if (arg == "--quiet") {
      a.quiet = true;
    } else if (arg == "--no-plan") {
      a.plan = false;
    } else if (arg == "--json") {
      a.json = true;
    } else if (arg == "--aa") {
      const auto v = r.value(arg);
      if (!parse_anti_alias_method(v, a.aa)) throw UsageError{"--aa: unknown mode " + quoted(v)};
      a.settings.aa = a.aa.coverage;
    } else if (arg == "--rule") {
      const auto v = r.value(arg);
      FillRule rule;
      if (!parse_fill_rule(v, rule)) throw UsageError{"--rule: unknown fill rule " + quoted(v)};
      a.settings.rule_override = rule;
    } else if (arg == "--tolerance") {
      a.settings.tolerance = parse_number(arg, r.value(arg));
      if (!(a.settings.tolerance >= 1e-4 && a.settings.tolerance <= 100)) {
        throw UsageError{"--tolerance must be between 0.0001 and 100 pixels"};
      }
    } else if (arg == "--hairline") {
      const auto v = r.value(arg);
      HairlineMode mode;
      if (!parse_hairline_mode(v, mode)) throw UsageError{"--hairline: unknown mode " + quoted(v)};
      a.settings.hairline = mode;
    } else if (arg == "--depth") {
      const double d = parse_number(arg, r.value(arg));
      if (d != 8 && d != 16) throw UsageError{"--depth must be 8 or 16"};
      a.depth = static_cast<int>(d);
    } else if (arg == "--background") {
      const auto v = r.value(arg);
      if (v == "transparent") {
        a.background = Color::transparent();
      } else {
        bool none = false;
        const auto c = svg::parse_color(v, none);
        if (!c) throw UsageError{"--background: " + quoted(v) + " is not a colour"};
        a.background = *c;
      }
    } else if (arg == "--font-dir") {
      a.font_dirs.emplace_back(r.value(arg));
    } else if (arg == "--no-system-fonts") {
      a.system_fonts = false;
    } else if (arg == "--serif-family" || arg == "--sans-serif-family" || arg == "--monospace-family" ||
               arg == "--cursive-family" || arg == "--fantasy-family") {
      std::string generic(arg.substr(2));
      generic.resize(generic.size() - 7);  // "-family"
      a.generic_families.emplace_back(generic, std::string(r.value(arg)));
    } else if (arg == "--default-family") {
      a.default_family = r.value(arg);
    } else if (arg == "--default-font-size") {
      a.default_font_size = parse_number(arg, r.value(arg));
      if (!(a.default_font_size > 0 && a.default_font_size <= 4096)) {
        throw UsageError{"--default-font-size must be between 0 and 4096 pixels"};
      }
    } else if (arg == "--bench") {
      const double n = parse_number(arg, r.value(arg));
      if (!(n >= 1 && n <= 1e6) || n != std::floor(n)) throw UsageError{"--bench needs a frame count from 1 to 1000000"};
      a.bench_frames = static_cast<int>(n);
    } else if (arg == "--threads") {
      const double n = parse_number(arg, r.value(arg));
      if (!(n >= 1 && n <= 64) || n != std::floor(n)) throw UsageError{"--threads needs a thread count from 1 to 64"};
      a.threads = static_cast<int>(n);
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError{"unknown option " + quoted(arg)};
    } else if (a.input.empty()) {
      a.input = arg;
    } else {
      throw UsageError{"more than one input file given"};
    }
  }
  if (a.input.empty()) throw UsageError{"render: no input file"};
  if (a.output.empty() && a.bench_frames == 0) throw UsageError{"render: no output file (-o OUT.png)"};
  return a;
}

/// Renders frames (one, or --bench N timed after a warm-up) with `draw`, then writes the PNG.
template <class T, class Draw>
void render_frames(int width, int height, const RenderArgs& a, Draw&& draw) {
  BasicImage<T> image(width, height);
  auto frame = [&] {
    image.clear(a.background);
    draw(image);
    post_filter(a.aa, image);  // fxaa: the aliased render, then the filter
  };
  if (a.bench_frames > 0) {
    frame();  // warm-up: buffers reach their steady-state size
    std::vector<double> ms;
    ms.reserve(static_cast<std::size_t>(a.bench_frames));
    for (int i = 0; i < a.bench_frames; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      frame();
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted.size() % 2 ? sorted[sorted.size() / 2]
                                            : 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);
    std::printf("frames=%d ms_per_frame_median=%.3f ms_min=%.3f\n", a.bench_frames, median, sorted.front());
  } else {
    frame();
  }
  if (!a.output.empty()) write_png(a.output, image);
}

/// --hairline: the flat draw items and the core Renderer (every stroke becomes a hairline; solid colours only).
template <class T>
void render_document(const svg::Document& doc, const RenderArgs& a) {
  Renderer renderer;
  renderer.set_threads(a.threads);
  render_frames<T>(doc.width, doc.height, a,
                   [&](BasicImage<T>& image) { svg::render(doc, image, a.settings, renderer); });
  warn_about_exact_fallbacks(renderer);
}

/// How the document is read: the folders images may come from, and the fonts text may use.
svg::ParseOptions parse_options(const RenderArgs& a) {
  svg::ParseOptions options;
  options.allowed_dir = a.allow_dir;
  options.default_font_size = a.default_font_size;
#if VRASTER_WITH_TEXT
  // Text uses only these fonts: the directories named, the system's (fontconfig) unless disabled, and the
  // embedded default font as the last resort.
  auto fonts = std::make_shared<text::FontDb>();
  for (const std::string& dir : a.font_dirs) fonts->add_directory(dir);
  if (a.system_fonts) fonts->add_system_fonts();
  fonts->add_embedded_default();
  for (const auto& [generic, family] : a.generic_families) {
    text::GenericFamily g;
    if (text::parse_generic_family(generic, g)) fonts->set_generic_family(g, family);
  }
  fonts->set_default_family(a.default_family);
  if (!a.quiet) {
    for (const std::string& w : fonts->warnings()) std::cerr << "vraster: font skipped: " << printable(w, 1024) << "\n";
  }
  options.fonts = fonts;
#endif
  return options;
}

svg::DrawSettings draw_settings(const RenderArgs& a) {
  svg::DrawSettings settings;
  settings.aa = a.settings.aa;
  settings.tolerance = a.settings.tolerance;
  settings.rule_override = a.settings.rule_override;
  return settings;
}

/// Everything else: the resolved tree drawn on a canvas (paint servers, clips, masks, layers, blend modes),
/// recorded once as a scene, analysed once (the plan) and replayed for each frame.
template <class T>
void render_tree(const svg::Tree& tree, const RenderArgs& a) {
  const auto [w, h] = svg::tree_output_size(tree, a.width, a.height);
  svg::DrawStats recorded;
  const Scene scene = svg::record_tree(tree, w, h, draw_settings(a), &recorded);
  std::uint64_t fallbacks = recorded.exact_fallbacks;
  const bool over_budget = recorded.over_budget;
  const std::optional<ScenePlan> plan = a.plan ? std::optional<ScenePlan>(plan_scene(scene)) : std::nullopt;
  render_frames<T>(w, h, a, [&](BasicImage<T>& image) {
    Canvas canvas(image);
    canvas.set_threads(a.threads);
    canvas.draw_scene(scene, plan ? &*plan : nullptr);
    fallbacks += canvas.exact_fallbacks();
  });
  warn_about_exact_fallbacks(fallbacks);
  if (over_budget) {
    std::cerr << "vraster: warning: some groups, clip paths, masks or patterns were left out: their offscreen images "
                 "would have needed more than 2^26 pixels at once (nested effects on a large image)\n";
  }
}

/// `vraster explain IN.svg`: the plan of the document's scene, one line per draw call, and its summary.
int run_explain(int argc, char** argv) {
  RenderArgs a;
  ArgReader r(argc, argv, 2);
  std::vector<char*> render_style{argv[0], argv[1]};
  while (!r.done()) {
    const std::string_view arg = r.next();
    if (arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
    render_style.push_back(const_cast<char*>(arg.data()));
  }
  render_style.push_back(const_cast<char*>("--bench"));  // explain writes no image
  render_style.push_back(const_cast<char*>("1"));
  a = parse_render_args(static_cast<int>(render_style.size()), render_style.data());
  if (a.settings.hairline || a.depth != 8) throw UsageError{"explain: --hairline and --depth do not apply"};
  const svg::Tree tree = svg::load_svg_tree(a.input, parse_options(a));
  if (!a.quiet) {
    for (const std::string& w : tree.warnings) std::cerr << printable(a.input, 1024) << ":" << w << "\n";
  }
  const auto [w, h] = svg::tree_output_size(tree, a.width, a.height);
  const Scene scene = svg::record_tree(tree, w, h, draw_settings(a));
  const ScenePlan plan = plan_scene(scene);
  std::cout << (a.json ? explain_plan_json(scene, plan) : explain_plan(scene, plan));
  return 0;
}

int run_render(int argc, char** argv) {
  const RenderArgs a = parse_render_args(argc, argv);
  if (a.help) {
    std::cout << kUsage;
    return 0;
  }
  const svg::ParseOptions options = parse_options(a);
  if (a.settings.hairline) {
    svg::Document doc = svg::load_svg(a.input, options);
    if (!a.quiet) {
      for (const std::string& w : doc.warnings) std::cerr << printable(a.input, 1024) << ":" << w << "\n";
    }
    if (a.width > 0 || a.height > 0) {
      const auto [w, h] = svg::output_size(doc, a.width, a.height);
      svg::scale_to(doc, w, h);
    }
    if (a.depth == 16) {
      render_document<std::uint16_t>(doc, a);
    } else {
      render_document<std::uint8_t>(doc, a);
    }
    return 0;
  }
  const svg::Tree tree = svg::load_svg_tree(a.input, options);
  if (!a.quiet) {
    for (const std::string& w : tree.warnings) std::cerr << printable(a.input, 1024) << ":" << w << "\n";
  }
  if (a.depth == 16) {
    render_tree<std::uint16_t>(tree, a);
  } else {
    render_tree<std::uint8_t>(tree, a);
  }
  return 0;
}

int run_demo(int argc, char** argv) {
  std::string output = "vraster-demo.png";
  ArgReader r(argc, argv, 2);
  while (!r.done()) {
    const std::string_view arg = r.next();
    if (arg == "-o" || arg == "--output") {
      output = r.value(arg);
    } else {
      throw UsageError{"demo: unknown argument " + quoted(arg)};
    }
  }
  const svg::Tree tree = svg::parse_svg_tree(demo_svg(), "<demo>");
  const auto [width, height] = svg::tree_output_size(tree);
  Image image(width, height + kDemoPanelHeight);
  image.clear(Color{1, 1, 1, 1});
  {
    Canvas canvas(image);
    svg::draw_tree(tree, canvas);
    draw_canvas_panel(canvas, height, width, kDemoPanelHeight);
  }
  write_png(output, image);
  std::cout << "vraster demo: wrote " << output << " (" << image.width << "x" << image.height << ")\n";
  return 0;
}

}  // namespace
}  // namespace vraster::cli

int main(int argc, char** argv) {
  using namespace vraster;
  install_output_cleanup_handlers();  // a signal or timeout while writing leaves no partial file
  try {
    if (argc < 2) throw cli::UsageError{"no command given"};
    const std::string_view command = argv[1];
    if (command == "render") return cli::run_render(argc, argv);
    if (command == "demo") return cli::run_demo(argc, argv);
    if (command == "explain") return cli::run_explain(argc, argv);
    if (command == "compare") return cli::run_compare(argc, argv);
    if (command == "fill-rules") return cli::run_fill_rules(argc, argv);
    if (command == "accuracy") return cli::run_accuracy(argc, argv);
    if (command == "mesh") return cli::run_mesh(argc, argv);
    if (command == "shading") return cli::run_shading(argc, argv);
    if (command == "depth") return cli::run_depth(argc, argv);
#if VRASTER_WITH_TEXT
    if (command == "text") return text::run_text_command(argc, argv);
#endif
    if (command == "--help" || command == "-h" || command == "help") {
      std::cout << cli::kUsage;
      return 0;
    }
    throw cli::UsageError{"unknown command '" + std::string(command) + "'"};
  } catch (const cli::UsageError& e) {
    std::cerr << "vraster: " << printable(e.message, kMaxMessageBytes) << "\n" << cli::kUsage;
    return 2;
  } catch (...) {
    // Everything else, std::filesystem errors included: a message and status 2, never std::terminate.
    std::cerr << "vraster: " << describe_current_exception() << "\n";
    return 2;
  }
}
