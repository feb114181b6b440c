// `vraster render` and `vraster explain`: SVG documents to PNG images (one file, a batch on several threads, or
// standard input to standard output), and the render plan of one document.
//
//   1. parse_render_args: the command line -> RenderArgs (a mistake throws UsageError)
//   2. plan_jobs: each input's output (a file, "-" for standard output, or DIR/NAME.png in a batch); two inputs
//      that would write the same file are an error before anything is rendered
//   3. load_tree: the document (a file, or standard input for "-"), cut down to --export-id's element
//   4. render_tree: recorded once as a scene, planned once, replayed for each frame, encoded, then written whole
//   5. run_jobs: step 3-4 for every input on -j workers, each with its own font database (FontDb is not
//      thread-safe); a file that fails is reported with its name, the others are still written, the status is 2
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "cli/cli.hpp"
#include "svg_subset/draw.hpp"
#include "svg_subset/scene.hpp"
#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"
#include "vraster/canvas.hpp"
#include "vraster/files.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/png.hpp"
#include "vraster/vraster.hpp"
#if VRASTER_WITH_TEXT
#include "vraster_text/font_db.hpp"
#endif

namespace vraster::cli {

const char* const kRenderUsage =
    "usage: vraster render IN.svg -o OUT.png [options]\n"
    "       vraster render IN.svg... -o DIR/ [-j N] [options]   (DIR/IN.png for each input)\n"
    "       vraster render - -o -   (the SVG from standard input, the PNG to standard output)\n"
    "Size (the document's own size by default: width and height, else the viewBox's):\n"
    "  -w, --width W     output width in pixels; alone, the height keeps the aspect ratio\n"
    "  -h, --height H    output height in pixels; alone, the width keeps the aspect ratio\n"
    "  -z, --zoom F      the intrinsic size times F (F > 0). With -w and/or -h they are a maximum, as in\n"
    "                    rsvg-convert: when the zoomed size is larger, the size is what -w/-h alone give\n"
    "  --dpi N           pixels per inch for physical units (in, cm, mm, pt, pc) in the document, 10 to 4000\n"
    "                    (default 96: 1in = 96px)\n"
    "  --export-id ID    draw only the element with this id (under its ancestors' transforms); the size is its\n"
    "                    bounding box, stroke included, unless -w/-h/-z say otherwise\n"
    "Input and output:\n"
    "  -o, --output F    the PNG file; '-' writes it to standard output; a DIR/ (ending in '/' or an existing\n"
    "                    directory) takes one PNG per input, named after it\n"
    "  -                 as IN.svg: read the document from standard input (<image> files then come from the\n"
    "                    current directory, or --allow-dir)\n"
    "  -j, --jobs N      render a batch on N threads, one file each (default 1; 0: one per processor)\n"
    "  --threads N       large fills of one file in bands on N threads, 1 to 64 (default 1; same pixels)\n"
    "  --allow-dir DIR   <image> files may also come from DIR, not only from IN.svg's folder\n"
    "  --quiet           no warnings\n"
    "Drawing:\n"
    "  --background C    a colour under the drawing (CSS colour or 'transparent', the default)\n"
    "  --aa MODE         none | analytic | exact | ssaa-2|4|8|16 | msaa-4|8|16 | fxaa (default analytic)\n"
    "  --rule RULE       evenodd | nonzero | nonexterior | positive | negative | abs-geq-2 (overrides fill-rule)\n"
    "  --tolerance T     curve flattening tolerance in pixels (default 0.1)\n"
    "  --depth 8|16      bits per channel of the PNG\n"
    "  --hairline bresenham|dda|wu|analytic   every stroke as a 1-px hairline (solid colours only)\n"
    "  --no-plan         replay every draw call as recorded: no culling, no layer folding\n"
    "  --bench N         render N timed frames after a warm-up; prints one line of timings\n"
    "Fonts for <text> (the directories named, then the system's through fontconfig, then the embedded font):\n"
    "  --font-dir DIR... --no-system-fonts --default-family F --default-font-size PX\n"
    "  --serif-family F --sans-serif-family F --monospace-family F --cursive-family F --fantasy-family F\n"
    "Errors: a message on stderr, exit status 2, no output file (a batch still writes the files that work).\n";

const char* const kExplainUsage =
    "usage: vraster explain IN.svg [--json] [render's -w/-h/-z, --dpi, --export-id, --aa, --tolerance, --rule,\n"
    "                                        --allow-dir and font options]\n"
    "Prints the render plan of the document's scene: one line per draw call (what the planner culled, which\n"
    "layers it folded), then a summary; --json prints the same as JSON.\n";

namespace {

struct RenderArgs {
  std::vector<std::string> inputs;  ///< "-": standard input
  std::string output;               ///< a file, "-" (standard output) or a directory
  svg::RenderSettings settings;
  AntiAliasMethod aa;  ///< --aa: settings.aa is its coverage mode; the post-filter runs on each finished frame
  int depth = 8;
  Color background = Color::transparent();
  int bench_frames = 0;
  int threads = 1;            ///< --threads: band threads of the renderer / canvas (one file)
  int width = 0, height = 0;  ///< requested output size (0: from the document)
  double zoom = 0;            ///< --zoom (0: not given)
  double dpi = 96;            ///< --dpi
  std::string export_id;      ///< --export-id (empty: the whole document)
  int jobs = 1;               ///< -j (0: one per processor)
  bool quiet = false;         ///< no warnings on stderr
  // Fonts for <text>.
  std::vector<std::string> font_dirs;
  bool system_fonts = true;
  std::vector<std::pair<std::string, std::string>> generic_families;  ///< (generic name, family)
  std::string default_family = "serif";
  double default_font_size = 16;
  bool plan = true;           ///< --no-plan: replay the recorded scene naively
  bool json = false;          ///< explain --json
  std::string allow_dir;      ///< --allow-dir: a wider folder <image> files may come from
};

double parse_number(std::string_view flag, std::string_view text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
    throw UsageError{std::string(flag) + ": " + vraster::quoted(text) + " is not a number"};
  }
  return v;
}

/// A whole number from lo to hi, or a usage error saying so.
int parse_count(std::string_view flag, std::string_view text, int lo, int hi, const char* what) {
  double n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || !(n >= lo && n <= hi) || n != std::floor(n)) {
    throw UsageError{std::string(flag) + " needs a whole number of " + what + " from " + std::to_string(lo) +
                     " to " + std::to_string(hi) + ", not " + vraster::quoted(text)};
  }
  return static_cast<int>(n);
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

/// The options of render and explain (what each command requires is checked by it).
RenderArgs parse_render_args(int argc, char** argv) {
  RenderArgs a;
  ArgReader r(argc, argv, 2);
  while (!r.done()) {
    const std::string_view arg = r.next();
    if (arg == "-o" || arg == "--output") {
      a.output = r.value(arg);
      if (a.output.empty()) throw UsageError{std::string(arg) + " needs a file name"};
    } else if (arg == "-w" || arg == "--width" || arg == "-h" || arg == "--height") {
      (arg == "-w" || arg == "--width" ? a.width : a.height) = parse_count(arg, r.value(arg), 1, kMaxImageSide, "pixels");
    } else if (arg == "-z" || arg == "--zoom") {
      const std::string_view v = r.value(arg);
      double z = 0;
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), z);
      if (ec != std::errc() || end != v.data() + v.size() || !(z > 0) || !std::isfinite(z)) {
        throw UsageError{std::string(arg) + " needs a finite number greater than 0, not " + vraster::quoted(v)};
      }
      a.zoom = z;
    } else if (arg == "--dpi") {
      a.dpi = parse_number(arg, r.value(arg));
      if (!(a.dpi >= 10 && a.dpi <= 4000)) throw UsageError{"--dpi must be from 10 to 4000 pixels per inch"};
    } else if (arg == "--export-id") {
      std::string_view id = r.value(arg);
      if (!id.empty() && id[0] == '#') id.remove_prefix(1);  // rsvg's form, "#id", is accepted too
      if (id.empty()) throw UsageError{"--export-id needs an element id"};
      a.export_id = id;
    } else if (arg == "-j" || arg == "--jobs") {
      a.jobs = parse_count(arg, r.value(arg), 0, 1024, "threads");
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
      if (!parse_anti_alias_method(v, a.aa)) throw UsageError{"--aa: unknown mode " + vraster::quoted(v)};
      a.settings.aa = a.aa.coverage;
    } else if (arg == "--rule") {
      const auto v = r.value(arg);
      FillRule rule;
      if (!parse_fill_rule(v, rule)) throw UsageError{"--rule: unknown fill rule " + vraster::quoted(v)};
      a.settings.rule_override = rule;
    } else if (arg == "--tolerance") {
      a.settings.tolerance = parse_number(arg, r.value(arg));
      if (!(a.settings.tolerance >= 1e-4 && a.settings.tolerance <= 100)) {
        throw UsageError{"--tolerance must be between 0.0001 and 100 pixels"};
      }
    } else if (arg == "--hairline") {
      const auto v = r.value(arg);
      HairlineMode mode;
      if (!parse_hairline_mode(v, mode)) throw UsageError{"--hairline: unknown mode " + vraster::quoted(v)};
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
        if (!c) throw UsageError{"--background: " + vraster::quoted(v) + " is not a colour"};
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
      a.bench_frames = parse_count(arg, r.value(arg), 1, 1000000, "frames");
    } else if (arg == "--threads") {
      a.threads = parse_count(arg, r.value(arg), 1, 64, "threads");
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError{"unknown option " + vraster::quoted(arg)};
    } else {
      a.inputs.emplace_back(arg);  // "-" is standard input
    }
  }
  return a;
}

/// How documents are read: the folders images may come from, the dpi, and the fonts text may use (a database
/// of its own: FontDb is not thread-safe). Font files that were skipped are reported to `log` when given.
svg::ParseOptions parse_options(const RenderArgs& a, std::ostream* log) {
  svg::ParseOptions options;
  options.allowed_dir = a.allow_dir;
  options.default_font_size = a.default_font_size;
  options.dpi = a.dpi;
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
  if (log) {
    for (const std::string& w : fonts->warnings()) *log << "vraster: font skipped: " << printable(w, 1024) << "\n";
  }
  options.fonts = fonts;
#else
  (void)log;
#endif
  return options;
}

/// The name messages give an input.
std::string display_name(const std::string& input) { return input == "-" ? "<stdin>" : input; }

/// All of standard input, at most kMaxSvgFileBytes.
std::string read_standard_input() {
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0) {
    if (text.size() + n > kMaxSvgFileBytes) {
      throw Error("standard input is larger than the limit of " + std::to_string(kMaxSvgFileBytes >> 20) + " MiB");
    }
    text.append(buffer, n);
  }
  if (std::ferror(stdin)) throw Error(std::string("cannot read standard input: ") + std::strerror(errno));
  return text;
}

/// Standard input's document: its <image> files come from the current directory (and --allow-dir).
svg::ParseOptions for_standard_input(svg::ParseOptions options) {
  options.base_dir = std::filesystem::current_path().string();
  return options;
}

/// The resolved tree of `input`, cut down to --export-id's element when one is given.
svg::Tree load_tree(const std::string& input, const RenderArgs& a, const svg::ParseOptions& options) {
  svg::Tree tree = input == "-" ? svg::parse_svg_tree(read_standard_input(), display_name(input), for_standard_input(options))
                                : svg::load_svg_tree(input, options);
  if (a.export_id.empty()) return tree;
  std::optional<svg::Tree> element = svg::element_tree(tree, a.export_id);
  if (!element) {
    throw Error("--export-id: no drawn element has the id " + vraster::quoted(a.export_id) + " in " +
                vraster::quoted(display_name(input), 1024) + " (elements in <defs> and hidden ones are not drawn)");
  }
  return std::move(*element);
}

void print_warnings(const std::string& input, const std::vector<std::string>& warnings, const RenderArgs& a,
                    std::ostream& log) {
  if (a.quiet) return;
  for (const std::string& w : warnings) log << printable(display_name(input), 1024) << ":" << w << "\n";
}

/// Writes `bytes` to standard output (the whole PNG is encoded before, so a failure leaves nothing half-written
/// that could have been avoided).
void write_standard_output(const std::vector<std::uint8_t>& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0) {
    throw Error(std::string("cannot write the PNG to standard output: ") + std::strerror(errno));
  }
}

template <class T>
void write_image(const std::string& output, const BasicImage<T>& image) {
  if (output == "-") {
    write_standard_output(png_bytes(image));
  } else if (!output.empty()) {
    write_png(output, image);  // a temporary renamed over the target: the file appears whole or not at all
  }
}

/// Renders frames (one, or --bench N timed after a warm-up) with `draw`, then writes the PNG to `output`.
/// draw(image, first) clears what it needs and draws a frame; after the first, the image holds the frame before.
template <class T, class Draw>
void render_frames(int width, int height, const RenderArgs& a, const std::string& output, Draw&& draw) {
  BasicImage<T> image(width, height);
  bool first = true;
  auto frame = [&] {
    draw(image, first);
    first = false;
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
  write_image(output, image);
}

/// --hairline: the flat draw items and the core Renderer (every stroke becomes a hairline; solid colours only).
template <class T>
void render_document(const svg::Document& doc, const RenderArgs& a, const std::string& output, std::ostream& log) {
  Renderer renderer;
  renderer.set_threads(a.threads);
  render_frames<T>(doc.width, doc.height, a, output, [&](BasicImage<T>& image, bool) {
    image.clear(a.background);
    svg::render(doc, image, a.settings, renderer);
  });
  if (!a.quiet) warn_about_exact_fallbacks(renderer.rasterizer().exact_fallbacks(), log);
}

svg::DrawSettings draw_settings(const RenderArgs& a) {
  svg::DrawSettings settings;
  settings.aa = a.settings.aa;
  settings.tolerance = a.settings.tolerance;
  settings.rule_override = a.settings.rule_override;
  return settings;
}

/// Above this many nodes a single frame is drawn straight onto the image instead of recorded, planned and
/// replayed: a recording holds a copy of every draw call's state (about 1 KB each), which for a document of a
/// million shapes was gigabytes on top of the tree, and the plan's savings (culled calls, folded layers) are
/// small next to that. Same pixels (SvgPlan.PlannedNaiveAndDirectRendersAgree).
constexpr std::size_t kMaxRecordedNodes = 50'000;

void warn_about_offscreen_budget(bool over_budget, std::ostream& log) {
  if (!over_budget) return;
  log << "vraster: warning: some groups, clip paths, masks or patterns were left out: their offscreen images "
         "would have needed more than 2^26 pixels at once (nested effects on a large image)\n";
}

/// Everything else: the resolved tree drawn on a canvas (paint servers, clips, masks, layers, blend modes),
/// recorded once as a scene, analysed once (the plan) and replayed for each frame.
template <class T>
void render_tree(const svg::Tree& tree, const RenderArgs& a, const std::string& output, std::ostream& log) {
  const auto [w, h] = svg::tree_output_size(tree, a.width, a.height, a.zoom);
  if (a.bench_frames == 0 && svg::count_nodes(tree.root, kMaxRecordedNodes) > kMaxRecordedNodes) {
    svg::DrawStats stats;
    render_frames<T>(w, h, a, output, [&](BasicImage<T>& image, bool) {
      image.clear(a.background);
      Canvas canvas(image);
      canvas.set_threads(a.threads);
      stats = svg::draw_tree(tree, canvas, draw_settings(a));
    });
    if (a.quiet) return;
    warn_about_exact_fallbacks(stats.exact_fallbacks, log);
    warn_about_offscreen_budget(stats.over_budget, log);
    return;
  }
  svg::DrawStats recorded;
  const Scene scene = svg::record_tree(tree, w, h, draw_settings(a), &recorded);
  std::uint64_t fallbacks = recorded.exact_fallbacks;
  const std::optional<ScenePlan> plan = a.plan ? std::optional<ScenePlan>(plan_scene(scene)) : std::nullopt;
  // Frames after the first are redrawn over the one before: with a plan, only the tiles the scene touches are
  // cleared and drawn (Canvas::draw_frame). Not under FXAA: the filter changes pixels next to the tiles too.
  const bool redraw_tiles = plan && !a.aa.fxaa;
  render_frames<T>(w, h, a, output, [&](BasicImage<T>& image, bool first) {
    Canvas canvas(image);
    canvas.set_threads(a.threads);
    if (redraw_tiles) {
      canvas.draw_frame(scene, *plan, first ? nullptr : &*plan, a.background);
    } else {
      image.clear(a.background);
      canvas.draw_scene(scene, plan ? &*plan : nullptr);
    }
    fallbacks += canvas.exact_fallbacks();
  });
  if (a.quiet) return;
  warn_about_exact_fallbacks(fallbacks, log);
  warn_about_offscreen_budget(recorded.over_budget, log);
}

/// Renders one input to `output`; its warnings go to `log`. Throws what goes wrong.
void render_file(const std::string& input, const std::string& output, const RenderArgs& a,
                 const svg::ParseOptions& options, std::ostream& log) {
  if (a.settings.hairline) {
    svg::Document doc = input == "-" ? svg::parse_svg(read_standard_input(), display_name(input), for_standard_input(options))
                                     : svg::load_svg(input, options);
    print_warnings(input, doc.warnings, a, log);
    if (a.width > 0 || a.height > 0 || a.zoom > 0) {
      const auto [w, h] = svg::output_size(doc, a.width, a.height, a.zoom);
      svg::scale_to(doc, w, h);
    }
    if (a.depth == 16) {
      render_document<std::uint16_t>(doc, a, output, log);
    } else {
      render_document<std::uint8_t>(doc, a, output, log);
    }
    return;
  }
  const svg::Tree tree = load_tree(input, a, options);
  print_warnings(input, tree.warnings, a, log);
  if (a.depth == 16) {
    render_tree<std::uint16_t>(tree, a, output, log);
  } else {
    render_tree<std::uint8_t>(tree, a, output, log);
  }
}

struct Job {
  std::string input;
  std::string output;
};

bool names_directory(const std::string& output) {
  return output.back() == '/' || std::filesystem::is_directory(output);
}

/// Each input's output. A directory output takes DIR/NAME.png for each input NAME.svg; two inputs that would
/// write the same file are a usage error (before anything is rendered).
std::vector<Job> plan_jobs(const RenderArgs& a) {
  if (a.output.empty() || a.output == "-" || !names_directory(a.output)) {
    if (a.inputs.size() > 1) {
      throw UsageError{"render: several inputs need -o DIR/ (a directory, named with a trailing '/' or existing)"};
    }
    return {Job{a.inputs[0], a.output}};
  }
  std::vector<Job> jobs;
  std::map<std::string, std::string> writer;  // output -> the input that writes it
  for (const std::string& input : a.inputs) {
    if (input == "-") throw UsageError{"render: standard input ('-') has no name to write DIR/NAME.png under: use -o FILE"};
    const std::filesystem::path name = std::filesystem::path(input).filename().replace_extension(".png");
    const std::string output = (std::filesystem::path(a.output) / name).lexically_normal().string();
    const auto [it, fresh] = writer.emplace(output, input);
    if (!fresh) {
      throw UsageError{"render: " + vraster::quoted(it->second, 1024) + " and " + vraster::quoted(input, 1024) + " would both write " +
                       vraster::quoted(output, 1024)};
    }
    jobs.push_back(Job{input, output});
  }
  return jobs;
}

/// What a failure prints: the message, with the input's name in front unless the message names it already
/// (FILE:LINE:COLUMN: ..., cannot read SVG file 'FILE').
std::string failure_message(const std::string& input, const std::string& message) {
  const std::string name = printable(display_name(input), 1024);
  if (message.find(name) != std::string::npos) return "vraster: " + message + "\n";
  return "vraster: " + name + ": " + message + "\n";
}

/// Renders every job on `a.jobs` workers (each takes the next file when it is done with one). Each file's
/// messages are printed together once it is done. Returns the number of files that failed.
int run_jobs(const std::vector<Job>& jobs, const RenderArgs& a, const svg::ParseOptions& first_options) {
  const unsigned available = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers =
      std::min(jobs.size(), static_cast<std::size_t>(a.jobs == 0 ? available : static_cast<unsigned>(a.jobs)));
  std::atomic<std::size_t> next{0};
  std::atomic<int> failed{0};
  std::mutex stderr_lock;
  auto report = [&](const std::string& text) {
    if (text.empty()) return;
    const std::lock_guard<std::mutex> hold(stderr_lock);
    std::cerr << text << std::flush;
  };
  auto work = [&](std::size_t worker) {
    std::optional<svg::ParseOptions> own;
    if (worker > 0) {  // the first worker uses the options made (and checked) before the threads started
      try {
        own = parse_options(a, nullptr);
      } catch (...) {
        report("vraster: worker " + std::to_string(worker) + ": " + describe_current_exception() + "\n");
        return;  // the other workers take its files
      }
    }
    const svg::ParseOptions& options = own ? *own : first_options;
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      // One file: its warnings as they come (before a long render). Several: each file's lines together.
      std::ostringstream buffer;
      std::ostream& log = jobs.size() == 1 ? std::cerr : buffer;
      try {
        render_file(jobs[i].input, jobs[i].output, a, options, log);
      } catch (...) {
        ++failed;
        log << (jobs.size() == 1 ? "vraster: " + describe_current_exception() + "\n"
                                 : failure_message(jobs[i].input, describe_current_exception()));
      }
      report(buffer.str());
    }
  };
  std::vector<std::thread> threads;
  try {
    for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(work, w);
  } catch (const std::system_error&) {
    // No more threads to be had: the workers that started (and this thread) take every file.
  }
  work(0);
  for (std::thread& t : threads) t.join();
  return failed;
}

}  // namespace

int run_render(int argc, char** argv) {
  RenderArgs a = parse_render_args(argc, argv);
  if (a.inputs.empty()) throw UsageError{"render: no input file"};
  if (a.output.empty() && a.bench_frames == 0) throw UsageError{"render: no output file (-o OUT.png)"};
  if (a.settings.hairline && !a.export_id.empty()) throw UsageError{"render: --export-id does not apply with --hairline"};
  if (std::count(a.inputs.begin(), a.inputs.end(), "-") > 1) throw UsageError{"render: standard input given twice"};
  const std::vector<Job> jobs = plan_jobs(a);
  if (jobs.size() > 1 && a.bench_frames > 0) throw UsageError{"render: --bench takes one input"};
  if (a.output == "-" && a.bench_frames > 0) throw UsageError{"render: --bench prints on standard output: not with -o -"};
  if (!a.output.empty() && a.output != "-" && names_directory(a.output)) {
    std::filesystem::create_directories(a.output);  // "DIR/" may be new
  }
  // Font problems (a --font-dir that is not a directory) stop here, before any file; skipped fonts are reported
  // once, not once per worker.
  const svg::ParseOptions options = parse_options(a, a.quiet ? nullptr : &std::cerr);
  return run_jobs(jobs, a, options) > 0 ? 2 : 0;
}

int run_explain(int argc, char** argv) {
  const RenderArgs a = parse_render_args(argc, argv);
  if (a.inputs.size() != 1) throw UsageError{"explain: needs exactly one input file"};
  if (a.settings.hairline || a.depth != 8 || a.bench_frames > 0 || !a.output.empty()) {
    throw UsageError{"explain: writes no image: --hairline, --depth, --bench and -o do not apply"};
  }
  const svg::ParseOptions options = parse_options(a, a.quiet ? nullptr : &std::cerr);
  const svg::Tree tree = load_tree(a.inputs[0], a, options);
  print_warnings(a.inputs[0], tree.warnings, a, std::cerr);
  const auto [w, h] = svg::tree_output_size(tree, a.width, a.height, a.zoom);
  const Scene scene = svg::record_tree(tree, w, h, draw_settings(a));
  const ScenePlan plan = plan_scene(scene);
  std::cout << (a.json ? explain_plan_json(scene, plan) : explain_plan(scene, plan));
  return 0;
}

}  // namespace vraster::cli
