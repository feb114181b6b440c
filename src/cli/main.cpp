// vraster: command-line front end. Each subcommand lives in its own file (render.cpp: render and explain); this
// one picks the subcommand and answers --help.
//
// Errors: a message naming the problem on stderr, exit status 2, and no output file.
#include <algorithm>
#include <iostream>
#include <string>
#include <string_view>

#include "cli/cli.hpp"
#include "cli/image_compare.hpp"
#include "vraster/error.hpp"
#include "vraster/files.hpp"
#if VRASTER_WITH_TEXT
#include "vraster_text/cli.hpp"
#endif

namespace vraster::cli {
namespace {

constexpr const char* kFillRulesUsage =
    "usage: vraster fill-rules IN.svg -o SHEET.png [--winding] [--aa MODE] [--panel PX]\n"
    "A contact sheet of the document under every fill rule (evenodd, nonzero, nonexterior, positive, negative,\n"
    "abs-geq-2); --winding adds the winding numbers. MODE: as render's --aa. PX: panel size, 32 to 2048.\n";

constexpr const char* kAccuracyUsage =
    "usage: vraster accuracy [SCENE.svg...] -o DIR [--frames N] [--max-side PX]\n"
    "Every antialiasing method on each scene (default: the benchmark scenes of $VRASTER_BENCH_SCENES): time per\n"
    "frame against the error from the exact coverage; writes DIR/accuracy.png and DIR/accuracy.md.\n";

constexpr const char* kCompareUsage =
    "usage: vraster compare REFERENCE.png OURS.png [--diff DIFF.png]\n"
    "Passes (exit 0) when at most 0.1% of the pixels are off by more than 16/255 in some premultiplied\n"
    "channel after excusing a pixel whose value lies within the range of the other image's 3x3\n"
    "neighbourhood (both ways), and at most 0.1% differ by more than 96/255; exit 1 when it fails.\n"
    "Prints: pixels, off (> 16 after the excuse), far_off (> 96), max_error (after the excuse).\n";

constexpr const char* kMeshUsage =
    "usage: vraster mesh IN.vmesh|IN.obj -o OUT.png [--shading flat|gouraud|phong] [--depth zbuffer|painter|none]\n"
    "                    [--aa] [--cull] [--camera ortho|perspective] [--yaw DEG] [--pitch DEG] [--distance D]\n"
    "                    [--width PX] [--height PX] [--bits 8|16] [--background #rrggbb|transparent]\n";

constexpr const char* kShadingUsage =
    "usage: vraster shading -o SHEET.png [--panel PX] [--aa]\n"
    "Flat, Gouraud and Phong shading side by side on a sphere and a torus.\n";

constexpr const char* kDepthUsage =
    "usage: vraster depth -o SHEET.png [--panel PX] [--aa]\n"
    "The painter's algorithm beside the z-buffer on interpenetrating shapes.\n";

constexpr const char* kDemoUsage =
    "usage: vraster demo [-o FILE]\n"
    "Renders the embedded demo scene (default FILE: vraster-demo.png).\n";

struct Command {
  std::string_view name;
  int (*run)(int argc, char** argv);
  std::string_view (*usage)();
};

#if VRASTER_WITH_TEXT
int run_text(int argc, char** argv) { return text::run_text_command(argc, argv); }
#endif

constexpr Command kCommands[] = {
    {"render", run_render, [] { return std::string_view(kRenderUsage); }},
    {"explain", run_explain, [] { return std::string_view(kExplainUsage); }},
    {"fill-rules", run_fill_rules, [] { return std::string_view(kFillRulesUsage); }},
#if VRASTER_WITH_TEXT
    {"text", run_text, text::text_command_usage},
#endif
    {"accuracy", run_accuracy, [] { return std::string_view(kAccuracyUsage); }},
    {"compare", run_compare, [] { return std::string_view(kCompareUsage); }},
    {"mesh", run_mesh, [] { return std::string_view(kMeshUsage); }},
    {"shading", run_shading, [] { return std::string_view(kShadingUsage); }},
    {"depth", run_depth, [] { return std::string_view(kDepthUsage); }},
    {"demo", run_demo, [] { return std::string_view(kDemoUsage); }},
};

/// `vraster --help`: the first line of each command's usage, and where the rest is.
std::string overview() {
  std::string text = "usage: vraster COMMAND [options]   (vraster COMMAND --help: the command's options)\n";
  for (const Command& c : kCommands) {
    std::string_view usage = c.usage();
    usage = usage.substr(0, usage.find('\n'));
    if (usage.substr(0, 7) == "usage: ") usage.remove_prefix(7);
    text.append("  ").append(usage).append("\n");
  }
  return text;
}

/// --help or -? anywhere after the command asks for its usage.
bool wants_help(int argc, char** argv) {
  return std::any_of(argv + 2, argv + argc, [](const char* arg) {
    const std::string_view a = arg;
    return a == "--help" || a == "-?";
  });
}

}  // namespace
}  // namespace vraster::cli

int main(int argc, char** argv) {
  using namespace vraster;
  install_output_cleanup_handlers();  // a signal or timeout while writing leaves no partial file
  std::string_view command_name, usage;
  try {
    if (argc < 2) throw cli::UsageError{"no command given"};
    const std::string_view name = argv[1];
    if (name == "--help" || name == "-h" || name == "-?" || name == "help") {
      std::cout << cli::overview();
      return 0;
    }
    for (const cli::Command& command : cli::kCommands) {
      if (command.name != name) continue;
      command_name = command.name;
      usage = command.usage();
      if (cli::wants_help(argc, argv)) {
        std::cout << usage;
        return 0;
      }
      return command.run(argc, argv);
    }
    throw cli::UsageError{"unknown command '" + printable(name, 256) + "'"};
  } catch (const cli::UsageError& e) {
    std::cerr << "vraster: " << printable(e.message, kMaxMessageBytes) << "\n";
    if (usage.empty()) {
      std::cerr << cli::overview();
    } else {  // the synopsis; the options are one --help away
      std::cerr << usage.substr(0, usage.find('\n') + 1) << "(vraster " << command_name << " --help: all its options)\n";
    }
    return 2;
  } catch (...) {
    // Everything else, std::filesystem errors included: a message and status 2, never std::terminate.
    std::cerr << "vraster: " << describe_current_exception() << "\n";
    return 2;
  }
}
