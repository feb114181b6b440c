// vraster command-line tool: shared helpers of the subcommands.
#pragma once

#include <cstdint>
#include <iostream>
#include <string>
#include <string_view>

namespace vraster {
class Renderer;
}

namespace vraster::cli {

/// A usage mistake on the command line (reported with exit status 2).
struct UsageError {
  std::string message;
};

/// `vraster render IN.svg... -o OUT.png|-|DIR/ [...]` and `vraster explain IN.svg [...]` (src/cli/render.cpp),
/// with their usage texts.
int run_render(int argc, char** argv);
int run_explain(int argc, char** argv);
extern const char* const kRenderUsage;
extern const char* const kExplainUsage;

/// `vraster demo [-o FILE]` (src/cli/demo.cpp).
int run_demo(int argc, char** argv);

/// `vraster fill-rules IN.svg -o SHEET.png [--winding] [--aa MODE] [--panel PX]`.
int run_fill_rules(int argc, char** argv);

/// `vraster accuracy [SCENE.svg...] -o DIR [--frames N] [--max-side PX]` (src/cli/accuracy.cpp).
int run_accuracy(int argc, char** argv);

/// `vraster mesh IN -o OUT.png [...]`, `vraster shading -o SHEET.png`, `vraster depth -o SHEET.png`
/// (src/cli/mesh.cpp).
int run_mesh(int argc, char** argv);
int run_shading(int argc, char** argv);
int run_depth(int argc, char** argv);

/// Prints a warning when some exact (or non-exterior) fills of `renderer` went over the crossing budget and
/// were drawn analytic (or non-zero) instead (see Rasterizer::kMaxExactCrossings).
void warn_about_exact_fallbacks(Renderer& renderer);
void warn_about_exact_fallbacks(std::uint64_t fallbacks, std::ostream& out = std::cerr);

/// The embedded demo scene (SVG text).
std::string_view demo_svg();

}  // namespace vraster::cli

namespace vraster {
class Canvas;
}

namespace vraster::cli {

/// The demo's second part, drawn through the canvas into the band [top, top + height) (src/cli/demo.cpp).
void draw_canvas_panel(Canvas& canvas, double top, double width, double height);
inline constexpr int kDemoPanelHeight = 220;

}  // namespace vraster::cli
