// svg_subset: drawing a parsed Document with vraster.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "svg_subset/svg.hpp"

namespace vraster::svg {

namespace {

/// The dash pattern as dash_polylines wants it (even count, positive sum), or empty for a solid stroke: an odd
/// count is repeated once; a negative or non-finite value or a zero sum means solid (as stroke_path does).
std::vector<double> normalized_dashes(const std::vector<double>& dashes) {
  double sum = 0;
  for (const double d : dashes) {
    if (!(d >= 0) || !std::isfinite(d)) return {};
    sum += d;
  }
  if (!(sum > 0) || !std::isfinite(sum)) return {};
  std::vector<double> pattern = dashes;
  if (pattern.size() % 2 != 0) pattern.insert(pattern.end(), dashes.begin(), dashes.end());
  return pattern;
}

/// The centre lines of a stroke for hairline drawing: the path itself, or its dashes (cut in user space).
Path hairline_centre_lines(const DrawItem& item, double device_tolerance) {
  if (check_dashes(item.path, item.stroke.dashes) != DashVerdict::Dashed) return item.path;
  const std::vector<double> pattern = normalized_dashes(item.stroke.dashes);
  std::vector<StrokePolyline> pieces, dashed;
  flatten_for_stroke(item.path, user_tolerance(item.transform, device_tolerance), pieces);
  dash_polylines(pieces, pattern, item.stroke.dash_offset, dashed);
  Path lines;
  for (const StrokePolyline& pl : dashed) {
    if (pl.points.size() < 2) continue;  // dots have no length: nothing for a hairline
    lines.move_to(pl.points[0]);
    for (std::size_t i = 1; i < pl.points.size(); ++i) lines.line_to(pl.points[i]);
    if (pl.closed) lines.close();
  }
  return lines;
}

template <class T>
void draw_hairline(BasicImage<T>& image, const DrawItem& item, HairlineMode mode, double tolerance,
                   Renderer& renderer) {
  if (!item.transform.is_finite() || !(item.color.a > 0)) return;
  const Path lines = hairline_centre_lines(item, tolerance);
  SolidCompositor<T> compositor(image, item.color);
  renderer.hairlines(lines, item.transform, mode, image.width, image.height, compositor);
}

}  // namespace

std::pair<int, int> output_size(const Document& doc, int width, int height, double zoom) {
  if (zoom > 0) {
    // Rounded up so the drawing is not cut off (1e-9: 10 x 0.3 is 3.0000000000000004, which is 3 pixels).
    const double w = std::max(1.0, std::ceil(doc.intrinsic_width * zoom - 1e-9));
    const double h = std::max(1.0, std::ceil(doc.intrinsic_height * zoom - 1e-9));
    if ((width <= 0 || w <= width) && (height <= 0 || h <= height)) {
      check_image_size(w, h);  // before the cast: a large zoom can be out of int's range
      return {static_cast<int>(w), static_cast<int>(h)};
    }
  }
  if (width > 0 && height > 0) return {width, height};
  if (width <= 0 && height <= 0) return {doc.width, doc.height};
  // Single precision, as resvg computes it (the reference images were made that way).
  const float w = std::max(1.0f, std::round(static_cast<float>(doc.intrinsic_width)));
  const float h = std::max(1.0f, std::round(static_cast<float>(doc.intrinsic_height)));
  const double other = std::max(1.0f, width > 0 ? std::ceil(static_cast<float>(width) * h / w)
                                                : std::ceil(static_cast<float>(height) * w / h));
  if (width > 0) {
    check_image_size(width, other);  // before the cast: the other side can be out of int's range
    return {width, static_cast<int>(other)};
  }
  check_image_size(other, height);
  return {static_cast<int>(other), height};
}

void scale_to(Document& doc, int width, int height) {
  check_image_size(width, height);
  const Affine scale = Affine::scale(width / doc.intrinsic_width, height / doc.intrinsic_height);
  for (DrawItem& item : doc.items) item.transform = scale * item.transform;
  doc.width = width;
  doc.height = height;
  doc.intrinsic_width = width;
  doc.intrinsic_height = height;
}

template <class T>
void render(const Document& doc, BasicImage<T>& image, const RenderSettings& settings, Renderer& renderer) {
  for (const DrawItem& item : doc.items) {
    try {
      if (item.is_fill()) {
        const FillOptions options{settings.rule_override.value_or(item.rule), settings.aa, settings.tolerance};
        renderer.fill(image, item.path, item.transform, item.color, options);
      } else if (settings.hairline) {
        draw_hairline(image, item, *settings.hairline, settings.tolerance, renderer);
      } else {
        const StrokeRenderOptions options{settings.aa, settings.tolerance, HairlineMode::Analytic, &renderer};
        stroke_path(image, item.path, item.transform, item.stroke, item.color, options);
      }
    } catch (const ParseError&) {
      throw;
    } catch (const Error& e) {
      // A limit of the core (work or memory per draw call): the message names the element.
      throw ParseError(doc.file, item.line, item.column,
                       std::string("cannot draw the ") + (item.is_fill() ? "fill" : "stroke") + " of this element: " +
                           e.what());
    }
  }
  renderer.flush();  // with threads, the fills were queued
}

template void render<std::uint8_t>(const Document&, Image&, const RenderSettings&, Renderer&);
template void render<std::uint16_t>(const Document&, Image16&, const RenderSettings&, Renderer&);

}  // namespace vraster::svg
