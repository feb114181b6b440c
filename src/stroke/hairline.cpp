// Hairlines (1-device-pixel lines: Bresenham, DDA, Wu, analytic) and the stroke entry point, as coverage.
//
//   Renderer::stroke: width in device pixels >= 1 -> stroke_to_path (user space) -> Renderer::fill (non-zero);
//                     thinner -> dashes in user space -> Renderer::hairlines with coverage scaled by the width.
//   Either way the coverage goes to the caller's sink (a compositor): strokes are geometry, never pixels here.
#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>

#include "stroke/internal.hpp"
#include "vraster/lines.hpp"
#include "vraster/renderer.hpp"
#include "vraster/stroke.hpp"

namespace vraster {
namespace {

constexpr double kHairlineTolerance = 0.1;

// The pixel containing a device point (callers keep coordinates well inside the int range).
IPoint pixel_of(Point p) { return {static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y))}; }

// Aliased hairlines of one polyline (Bresenham, or DDA when `dda`): every segment half-open, so each joint is
// drawn once; an open polyline then draws its last pixel. plot(x, y) gets canvas pixels only.
template <class Plot>
void walk_aliased(const StrokePolyline& pl, int width, int height, bool dda, Plot&& plot) {
  const double w = width, h = height;
  // Segments are clipped (in floating point) to a rectangle with a wide margin before rounding: far endpoints
  // never overflow an int, and the margin keeps the clipped direction within 1e-6 of the original.
  const Rect safe{-1e6, -1e6, w + 1e6, h + 1e6};
  const std::size_t n = pl.points.size();
  if (n == 1) {
    const Point p = pl.points[0];
    if (p.x >= 0 && p.x < w && p.y >= 0 && p.y < h) plot(static_cast<int>(p.x), static_cast<int>(p.y));
    return;
  }
  const std::size_t segs = pl.closed ? n : n - 1;
  for (std::size_t i = 0; i < segs; ++i) {
    Point a = pl.points[i], b = pl.points[(i + 1) % n];
    const bool end_inside = safe.x0 <= b.x && b.x <= safe.x1 && safe.y0 <= b.y && b.y <= safe.y1;
    if (!clip_segment(a, b, safe)) continue;
    const IPoint pa = pixel_of(a), pb = pixel_of(b);
    if (pa == pb) continue;  // the joint pixel belongs to the next segment (or the final plot below)
    const LineEnd end = end_inside ? LineEnd::HalfOpen : LineEnd::Closed;
    if (dda) {
      dda_line(pa, pb, width, height, end, plot);
    } else {
      bresenham_line(pa, pb, width, height, end, plot);
    }
  }
  if (!pl.closed) {
    const Point p = pl.points[n - 1];
    if (p.x >= 0 && p.x < w && p.y >= 0 && p.y < h) plot(static_cast<int>(p.x), static_cast<int>(p.y));
  }
}

}  // namespace

bool parse_hairline_mode(std::string_view name, HairlineMode& out) {
  if (name == "bresenham") out = HairlineMode::Bresenham;
  else if (name == "dda") out = HairlineMode::Dda;
  else if (name == "wu") out = HairlineMode::Wu;
  else if (name == "analytic") out = HairlineMode::Analytic;
  else return false;
  return true;
}

std::string_view to_string(HairlineMode mode) {
  switch (mode) {
    case HairlineMode::Bresenham: return "bresenham";
    case HairlineMode::Dda: return "dda";
    case HairlineMode::Wu: return "wu";
    case HairlineMode::Analytic: return "analytic";
  }
  return "?";
}

namespace {

// Sorts the hits into rows, merges repeated pixels (sum, clamped to 1) and emits runs of adjacent pixels.
void emit_hits(std::vector<detail::RendererScratch::PixelHit>& hits, std::vector<float>& run, float scale,
               CoverageSink& sink) {
  using Hit = detail::RendererScratch::PixelHit;
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
  std::size_t i = 0;
  while (i < hits.size()) {
    const int y = hits[i].y, x0 = hits[i].x;
    int x = x0;
    run.clear();
    while (i < hits.size() && hits[i].y == y && hits[i].x <= x + 1) {
      if (hits[i].x == x + 1 || run.empty()) {
        x = hits[i].x;
        run.push_back(0);
      }
      run.back() = std::min(1.0f, run.back() + hits[i].coverage);
      ++i;
    }
    for (float& c : run) c *= scale;
    if (run.size() == 1) {
      if (run[0] > 0) sink.span(y, x0, x0 + 1, run[0]);
    } else {
      sink.row(y, x0, x0 + static_cast<int>(run.size()), run.data());
    }
  }
}

// Scales every coverage value on its way to another sink.
class ScaledSink final : public CoverageSink {
 public:
  ScaledSink(CoverageSink& out, float scale, std::vector<float>& buf) : out_(out), scale_(scale), buf_(buf) {}
  void span(int y, int x0, int x1, float coverage) override { out_.span(y, x0, x1, coverage * scale_); }
  void row(int y, int x0, int x1, const float* coverage) override {
    buf_.assign(coverage, coverage + (x1 - x0));
    for (float& c : buf_) c *= scale_;
    out_.row(y, x0, x1, buf_.data());
  }
  void expect(int y0, int y1, int x0, int x1) override { out_.expect(y0, y1, x0, x1); }

 private:
  CoverageSink& out_;
  float scale_;
  std::vector<float>& buf_;
};

}  // namespace

void Renderer::hairlines(const Path& path, const Affine& transform, HairlineMode mode, int width, int height,
                         CoverageSink& sink, float coverage_scale) {
  flush();  // painter's order with queued fills
  if (!(coverage_scale > 0) || path.empty() || width <= 0 || height <= 0) return;
  const float scale = std::min(coverage_scale, 1.0f);
  detail::RendererScratch& s = *scratch_;
  const Path device = path.transformed(transform);
  s.pieces.clear();
  const Rect clip{-2, -2, width + 2.0, height + 2.0};
  flatten_for_stroke_clipped(device, kHairlineTolerance, clip, s.pieces);
  if (mode == HairlineMode::Analytic) {
    StrokeStyle style;
    style.width = 1;
    style.join = LineJoin::Bevel;
    s.outline.clear();
    stroke_polylines(s.pieces, style, kHairlineTolerance, s.outline);
    const Polylines& lines = flatten_for_fill(s.outline, Affine{}, kHairlineTolerance, width, height);
    if (scale == 1.0f) {
      rasterizer_.fill(lines, FillRule::NonZero, AntiAlias::Analytic, width, height, sink);
    } else {
      ScaledSink scaled(sink, scale, s.run);
      rasterizer_.fill(lines, FillRule::NonZero, AntiAlias::Analytic, width, height, scaled);
    }
    return;
  }
  // Per-pixel algorithms: the pixels are collected (memory proportional to the pixels drawn), then handed over in
  // row order.
  s.hits.clear();
  for (const StrokePolyline& pl : s.pieces) {
    if (mode == HairlineMode::Wu) {
      const std::size_t n = pl.points.size();
      const std::size_t segs = n < 2 ? 0 : (pl.closed ? n : n - 1);
      for (std::size_t i = 0; i < segs; ++i) {
        wu_line(pl.points[i], pl.points[(i + 1) % n], width, height,
                [&](int x, int y, float cov) { s.hits.push_back({y, x, cov}); });
      }
      continue;
    }
    walk_aliased(pl, width, height, mode == HairlineMode::Dda, [&](int x, int y) { s.hits.push_back({y, x, 1.0f}); });
  }
  emit_hits(s.hits, s.run, scale, sink);
}

void hairline_coverage(const Path& path, const Affine& transform, HairlineMode mode, int width, int height,
                       CoverageSink& sink, float coverage_scale) {
  Renderer renderer;
  renderer.hairlines(path, transform, mode, width, height, sink, coverage_scale);
}

void draw_hairlines(Image& image, const Path& path, const Affine& transform, Color color, HairlineMode mode,
                    float coverage_scale) {
  if (!(color.a > 0)) return;
  SolidCompositor<std::uint8_t> compositor(image, color);
  hairline_coverage(path, transform, mode, image.width, image.height, compositor, coverage_scale);
}

namespace {

// The device-space centre lines of a thin stroke: dashes applied in user space, dots dropped.
Path thin_centre_lines(const Path& path, const StrokeStyle& style, double user_tol) {
  std::vector<StrokePolyline> pieces, dashed;
  flatten_for_stroke(path, user_tol, pieces);
  const bool dashed_ok = check_dashes(path, style.dashes) == DashVerdict::Dashed;
  dash_polylines(pieces, dashed_ok ? normalize_dashes(style.dashes) : std::vector<double>{}, style.dash_offset, dashed);
  Path centre_lines;
  for (const StrokePolyline& pl : dashed) {
    if (pl.points.size() < 2) continue;
    centre_lines.move_to(pl.points[0]);
    for (std::size_t i = 1; i < pl.points.size(); ++i) centre_lines.line_to(pl.points[i]);
    if (pl.closed) centre_lines.close();
  }
  return centre_lines;
}

}  // namespace

HairlineMode thin_stroke_mode(AntiAlias aa, HairlineMode requested) {
  if (aa == AntiAlias::None) return requested == HairlineMode::Dda ? HairlineMode::Dda : HairlineMode::Bresenham;
  if (requested == HairlineMode::Bresenham || requested == HairlineMode::Dda) return HairlineMode::Analytic;
  return requested;
}

void Renderer::stroke(const Path& path, const Affine& transform, const StrokeStyle& style,
                      const StrokeRenderOptions& options, int width, int height, CoverageSink& sink) {
  if (!(style.width > 0) || !std::isfinite(style.width) || path.empty() || !transform.is_finite()) return;
  if (width <= 0 || height <= 0) return;
  const double tolerance = options.tolerance > 0 && std::isfinite(options.tolerance) ? options.tolerance : kDefaultTolerance;
  const double device_width = style.width * std::sqrt(std::fabs(transform.determinant()));
  const double user_tol = user_tolerance(transform, tolerance);
  if (device_width < 1) {
    // The one place thin strokes are decided: dashes in user space, then 1-px hairlines in device space with
    // coverage scaled by the device width, so a stroke never vanishes (and never paints more than its area).
    const Path centre_lines = thin_centre_lines(path, style, user_tol);
    hairlines(centre_lines, transform, thin_stroke_mode(options.aa, options.thin_mode), width, height, sink,
              static_cast<float>(device_width));
    return;
  }
  // Geometry only: the outline in user space, then the ordinary fill path (non-zero).
  // The user-space box of the device area (plus a pixel): only geometry within the stroke's reach of it is
  // outlined, so a huge stroke far outside costs nothing.
  std::optional<Rect> visible;
  if (transform.invertible()) {
    const Affine inverse = transform.inverse();
    const double w = width + 1.0, h = height + 1.0;
    Rect box = Rect::from_point(inverse.apply({-1, -1}));
    for (const Point corner : {Point{w, -1}, Point{-1, h}, Point{w, h}}) box.include(inverse.apply(corner));
    if (is_finite(Point{box.x0, box.y0}) && is_finite(Point{box.x1, box.y1})) visible = box;
  }
  const Path outline = stroke_to_path_visible(path, style, user_tol, visible ? &*visible : nullptr);
  fill(outline, transform, FillOptions{FillRule::NonZero, options.aa, tolerance}, width, height, sink);
}

template <class T>
void stroke_path(BasicImage<T>& image, const Path& path, const Affine& transform, const StrokeStyle& style,
                 Color color, const StrokeRenderOptions& options) {
  if (!(color.a > 0)) return;
  SolidCompositor<T> compositor(image, color);
  if (options.renderer) {
    options.renderer->stroke(path, transform, style, options, image.width, image.height, compositor);
  } else {
    Renderer().stroke(path, transform, style, options, image.width, image.height, compositor);
  }
}

template void stroke_path(Image&, const Path&, const Affine&, const StrokeStyle&, Color, const StrokeRenderOptions&);
template void stroke_path(Image16&, const Path&, const Affine&, const StrokeStyle&, Color, const StrokeRenderOptions&);

}  // namespace vraster
