// vraster: stroking (Path + StrokeStyle -> Path filled with non-zero) and hairlines.
//
// Data flow of a stroke:
//   1. flatten_for_stroke: each contour -> polyline in user space (curves at tolerance/2, vertices marked
//      "corner" (user join) or "smooth" (inside a curve: round join, which keeps the offset within tolerance))
//   2. dash_polylines: cut the polylines into dashes (pattern continues across segments and curves, restarts per
//      subpath; on a closed subpath the last dash is joined to the first)
//   3. stroke_polylines: offset every piece by width/2 on both sides with joins and caps -> closed contours
//   4. the caller fills the result with FillRule::NonZero (after mapping by its transform: stroking happens in
//      user space, so a non-uniform transform scales the stroke as SVG does).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/renderer.hpp"
#include "vraster/path.hpp"
#include "vraster/raster.hpp"

namespace vraster {

/// Line cap (SVG stroke-linecap).
enum class LineCap : std::uint8_t { Butt, Round, Square };
/// Line join (SVG stroke-linejoin). Miter falls back to Bevel when the miter ratio exceeds miter_limit;
/// MiterClip (SVG 2 `miter-clip`) instead cuts the miter off square to the bisector at miter_limit * width / 2
/// from the vertex.
enum class LineJoin : std::uint8_t { Miter, Round, Bevel, MiterClip };

/// Parses "butt" / "round" / "square"; false for anything else (out unchanged).
bool parse_line_cap(std::string_view name, LineCap& out);
/// Parses "miter" / "round" / "bevel" / "miter-clip"; false for anything else (out unchanged).
bool parse_line_join(std::string_view name, LineJoin& out);

/// How a path is stroked (SVG semantics; all lengths in user space).
struct StrokeStyle {
  double width = 1;          ///< full stroke width (<= 0 or non-finite: nothing is drawn)
  LineCap cap = LineCap::Butt;
  LineJoin join = LineJoin::Miter;
  double miter_limit = 4;    ///< limit on miter length / width (values < 1 act as 1)
  /// Dash lengths, alternating on/off. An odd count is repeated once (SVG). Empty, all zero, or any negative
  /// or non-finite value: solid stroke.
  std::vector<double> dashes;
  double dash_offset = 0;    ///< distance into the pattern at the start of every subpath (may be negative)
};

/// Most pattern elements (dashes and gaps) one stroke may be cut into. The count is taken against the length
/// of the path's control polygon (an upper bound of its arc length), so it is known before any flattening.
inline constexpr double kMaxDashElements = 1 << 16;

/// What stroking does with a dash pattern on a path.
enum class DashVerdict : std::uint8_t {
  None,     ///< no pattern: solid
  Dashed,   ///< the stroke is cut into dashes
  Invalid,  ///< a negative or non-finite entry, or a sum that is zero or not finite: solid (SVG: as if "none")
  TooMany,  ///< more than kMaxDashElements elements on this path (dashes far finer than the path): solid
};
/// The verdict every stroking call applies to `dashes` on `path` (user space). Callers that can warn use it to
/// say why a stroke is drawn solid.
DashVerdict check_dashes(const Path& path, const std::vector<double>& dashes);

/// Strokes `path` (user space) into a path whose non-zero fill is the stroke area.
/// `tolerance` (> 0, user units) bounds the distance between the result's boundary and the exact stroke
/// boundary (curves flattened at tolerance/2, round joins and caps with chord error <= tolerance/2).
/// Zero-length subpaths (`M x y L x y`, `M x y Z`) give a dot with round or square caps (square aligned with
/// the x axis) and nothing with butt caps; a lone `M x y` gives nothing.
/// Returns an empty path for an invisible style. Throws vraster::Error when the outline would need more than
/// kMaxStrokeOutlinePoints points (a stroke vastly wider than the tolerance on a long curve).
Path stroke_to_path(const Path& path, const StrokeStyle& style, double tolerance);

/// Most points one stroke outline may have (2^22, 64 MiB of points); see stroke_to_path. Renderer::stroke
/// outlines only the geometry that can reach the device area, so the limit applies to what is visible.
inline constexpr std::size_t kMaxStrokeOutlinePoints = std::size_t{1} << 22;

/// The user-space tolerance that gives `device_tolerance` after `transform` (divides by the largest scale).
double user_tolerance(const Affine& transform, double device_tolerance);

/// How hairlines (1-device-pixel lines, no joins or caps) are drawn.
enum class HairlineMode : std::uint8_t {
  Bresenham,  ///< aliased, integer Bresenham from the pixel containing each vertex; joints drawn once
  Dda,        ///< aliased, DDA (for comparison; same pixels as Bresenham except at exact ties)
  Wu,         ///< antialiased, Xiaolin Wu's two-pixel intensity split (the seeds' ratio method)
  Analytic,   ///< antialiased, exact area coverage of a 1-px-wide butt-capped stroke
};
/// Parses "bresenham" / "dda" / "wu" / "analytic"; false for anything else.
bool parse_hairline_mode(std::string_view name, HairlineMode& out);
std::string_view to_string(HairlineMode mode);

/// Draws every contour of `path`, mapped by `transform` and flattened at 0.1 px, as 1-device-pixel hairlines in
/// `color` (source-over). `coverage_scale` in (0, 1] multiplies the alpha (used for strokes thinner than a pixel).
/// Geometry far outside the image costs only the visible part. Never throws for a valid path and finite transform.
void draw_hairlines(Image& image, const Path& path, const Affine& transform, Color color, HairlineMode mode,
                    float coverage_scale = 1.0f);

/// The coverage of draw_hairlines (same algorithms and pixels) for any compositor: per-pixel coverage from the
/// per-pixel algorithms is summed (clamped to 1, so a pixel hit twice counts once fully) and handed to `sink`
/// in row order; Analytic hands over the rasterizer's coverage. Coverage is multiplied by `coverage_scale`.
void hairline_coverage(const Path& path, const Affine& transform, HairlineMode mode, int width, int height,
                       CoverageSink& sink, float coverage_scale = 1.0f);

/// How Renderer::stroke (and stroke_path) turn a stroke into coverage.
struct StrokeRenderOptions {
  AntiAlias aa = AntiAlias::Analytic;
  double tolerance = 0.1;  ///< device pixels
  /// Strokes whose device width (width * sqrt|det|) is below 1 px are drawn as hairlines with coverage scaled by
  /// the width, so they never vanish; thin_stroke_mode(aa, thin_mode) picks the algorithm.
  HairlineMode thin_mode = HairlineMode::Analytic;
  /// stroke_path only: when set, this renderer (flattening buffer + rasterizer) is reused instead of a fresh one.
  Renderer* renderer = nullptr;
};

/// The hairline algorithm of a stroke thinner than a device pixel (Renderer::stroke's one decision): aliased
/// (aa == None) strokes take Bresenham (or Dda if requested); antialiased ones take Wu or Analytic (Bresenham and
/// Dda requests become Analytic). The same for every image depth and compositor.
HairlineMode thin_stroke_mode(AntiAlias aa, HairlineMode requested);

/// Convenience for tools and tests: Renderer::stroke into a SolidCompositor, i.e. strokes `path` in user space,
/// maps the outline by `transform` and fills it (non-zero) with one solid `color` source-over. For Image (8-bit)
/// and Image16. Draws nothing for an invisible style or colour or a non-finite transform. Drawing code with paints,
/// operators or clips calls Renderer::stroke with its own compositor (or uses the Canvas).
template <class T>
void stroke_path(BasicImage<T>& image, const Path& path, const Affine& transform, const StrokeStyle& style, Color color,
                 const StrokeRenderOptions& options = {});
extern template void stroke_path(Image&, const Path&, const Affine&, const StrokeStyle&, Color,
                                 const StrokeRenderOptions&);
extern template void stroke_path(Image16&, const Path&, const Affine&, const StrokeStyle&, Color,
                                 const StrokeRenderOptions&);

// ---- lower-level stages (exposed for tests and tools) ----

/// One flattened piece to be stroked: points (consecutive points distinct unless the piece is a single dot),
/// per-vertex flag "corner" (1: apply the user join; 0: smooth vertex inside a curve, joined round).
struct StrokePolyline {
  std::vector<Point> points;
  std::vector<std::uint8_t> corner;
  bool closed = false;
  /// For a zero-length piece (points.size() == 1): the direction its caps face (unit vector).
  Point dot_direction{1, 0};
};

/// Step 1: flattens each contour of `path` (identity transform) at `tolerance`, dropping repeated points.
void flatten_for_stroke(const Path& path, double tolerance, std::vector<StrokePolyline>& out);
/// Step 2: cuts the pieces by the dash pattern (normalized already: even count, finite positive sum). A pattern
/// that would make more than kMaxDashElements pieces, or a sum that is not finite and positive, is ignored: the
/// pieces are copied unchanged (a solid stroke).
void dash_polylines(const std::vector<StrokePolyline>& in, const std::vector<double>& pattern, double offset,
                    std::vector<StrokePolyline>& out);
/// Step 3: outlines every piece into `out` (appends closed contours).
void stroke_polylines(const std::vector<StrokePolyline>& pieces, const StrokeStyle& style, double tolerance,
                      Path& out);

}  // namespace vraster
