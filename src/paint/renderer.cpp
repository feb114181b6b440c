// The fill entry point: path -> flatten (clipped to the image) -> rasterize -> composite.
#include "vraster/renderer.hpp"

namespace vraster {

const Polylines& Renderer::flatten_for_fill(const Path& path, const Affine& transform, double tolerance, int width,
                                            int height) {
  lines_.clear();
  const Rect clip{0, 0, static_cast<double>(width), static_cast<double>(height)};
  FlattenOptions options;
  options.tolerance = tolerance;
  options.clip = &clip;
  flatten(path, transform, options, lines_);
  return lines_;
}

template <class T>
void Renderer::fill(BasicImage<T>& image, const Path& path, const Affine& transform, Color color,
                    const FillOptions& options) {
  if (!(color.a > 0) || path.empty()) return;  // invisible: no work at all
  const Polylines& lines = flatten_for_fill(path, transform, options.tolerance, image.width, image.height);
  SolidCompositor<T> compositor(image, color);
  rasterizer_.fill(lines, options.rule, options.aa, image.width, image.height, compositor);
}

template void Renderer::fill(Image&, const Path&, const Affine&, Color, const FillOptions&);
template void Renderer::fill(Image16&, const Path&, const Affine&, Color, const FillOptions&);

}  // namespace vraster
