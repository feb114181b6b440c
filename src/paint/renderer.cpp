// The coverage producer: path -> flatten (clipped to the device) -> rasterize -> CoverageSink; masks -> rows.
#include "vraster/renderer.hpp"

#include <algorithm>

#include "stroke/internal.hpp"

namespace vraster {

Renderer::Renderer() : scratch_(std::make_unique<detail::RendererScratch>()) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

const Polylines& Renderer::flatten_for_fill(const Path& path, const Affine& transform, double tolerance, int width,
                                            int height) {
  lines_.clear();
  const Rect clip{0, 0, static_cast<double>(width), static_cast<double>(height)};
  FlattenOptions options;
  options.tolerance = tolerance;
  options.clip = &clip;
  flatten(path, transform, options, lines_);
  flattened_points_ += lines_.points.size();
  return lines_;
}

void Renderer::fill(const Path& path, const Affine& transform, const FillOptions& options, int width, int height,
                    CoverageSink& sink) {
  if (path.empty() || width <= 0 || height <= 0) return;
  const Polylines& lines = flatten_for_fill(path, transform, options.tolerance, width, height);
  rasterizer_.fill(lines, options.rule, options.aa, width, height, sink);
}

void Renderer::fill(const Path& path, const Affine& transform, const FillOptions& options, int width, int height,
                    std::unique_ptr<CoverageSink> sink) {
  if (path.empty() || width <= 0 || height <= 0) return;
  const Polylines& lines = flatten_for_fill(path, transform, options.tolerance, width, height);
  rasterizer_.fill_queued(lines, options.rule, options.aa, width, height, std::move(sink));
}

void Renderer::fill_queued(const Path& path, const Affine& transform, const FillOptions& options, int width,
                           int height, CoverageSink& sink) {
  if (path.empty() || width <= 0 || height <= 0) return;
  const Polylines& lines = flatten_for_fill(path, transform, options.tolerance, width, height);
  rasterizer_.fill_queued(lines, options.rule, options.aa, width, height, sink);
}

void Renderer::mask(const std::uint8_t* mask, int mask_width, int mask_height, std::ptrdiff_t stride, int x, int y,
                    int width, int height, CoverageSink& sink) {
  flush();  // painter's order with queued fills
  if (!mask || mask_width <= 0 || mask_height <= 0) return;
  // 64-bit bounds: a mask placed near the int limits must not wrap around.
  const std::int64_t x0 = std::max<std::int64_t>(x, 0), x1 = std::min<std::int64_t>(std::int64_t{x} + mask_width, width);
  const std::int64_t y0 = std::max<std::int64_t>(y, 0), y1 = std::min<std::int64_t>(std::int64_t{y} + mask_height, height);
  if (x1 <= x0 || y1 <= y0) return;
  sink.expect(static_cast<int>(y0), static_cast<int>(y1), static_cast<int>(x0), static_cast<int>(x1));
  std::vector<float>& row = scratch_->row;
  if (row.size() < static_cast<std::size_t>(x1 - x0)) row.resize(static_cast<std::size_t>(x1 - x0));
  for (std::int64_t py = y0; py < y1; ++py) {
    const std::uint8_t* src = mask + (py - y) * stride + (x0 - x);
    // Trim the transparent ends, so the compositor sees only the pixels the mask touches.
    int a = 0, b = static_cast<int>(x1 - x0);
    while (a < b && src[a] == 0) ++a;
    while (b > a && src[b - 1] == 0) --b;
    if (a == b) continue;
    for (int i = a; i < b; ++i) row[static_cast<std::size_t>(i)] = static_cast<float>(src[i]) * (1.0f / 255.0f);
    sink.row(static_cast<int>(py), static_cast<int>(x0) + a, static_cast<int>(x0) + b, row.data() + a);
  }
}

template <class T>
void Renderer::fill(BasicImage<T>& image, const Path& path, const Affine& transform, Color color,
                    const FillOptions& options) {
  if (!(color.a > 0) || path.empty()) return;  // invisible: no work at all
  SolidCompositor<T> compositor(image, color);
  fill_queued(path, transform, options, image.width, image.height, compositor);
}

template void Renderer::fill(Image&, const Path&, const Affine&, Color, const FillOptions&);
template void Renderer::fill(Image16&, const Path&, const Affine&, Color, const FillOptions&);

}  // namespace vraster
