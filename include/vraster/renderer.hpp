// vraster: the fill entry point (Renderer) and the solid source-over compositor.
#pragma once

#include "vraster/flatten.hpp"
#include "vraster/image.hpp"
#include "vraster/path.hpp"
#include "vraster/raster.hpp"

namespace vraster {

/// Source-over compositing of one solid colour onto an image, driven by coverage from the rasterizer.
/// Decides once per span what it needs: zero alpha writes nothing, opaque full coverage stores the colour
/// without blending.
template <class T>
class SolidCompositor final : public CoverageSink {
 public:
  SolidCompositor(BasicImage<T>& image, Color color);
  void span(int y, int x0, int x1, float coverage) override;
  void row(int y, int x0, int x1, const float* coverage) override;

 private:
  void span8(int y, int x0, int x1, float coverage);
  void row8(int y, int x0, int x1, const float* coverage);
  void span16(int y, int x0, int x1, float coverage);

  BasicImage<T>& image_;
  float alpha_;              // colour alpha in [0, 1]
  std::uint64_t premul_[4];  // colour premultiplied, scaled to the channel range
};

extern template class SolidCompositor<std::uint8_t>;
extern template class SolidCompositor<std::uint16_t>;

/// How a fill is rendered.
struct FillOptions {
  FillRule rule = FillRule::NonZero;
  AntiAlias aa = AntiAlias::Analytic;
  double tolerance = kDefaultTolerance;  ///< flattening tolerance in device pixels
};

/// Reusable state for filling paths onto an image: the flattening buffer and the rasterizer.
/// One Renderer per thread; no global state.
class Renderer {
 public:
  /// Fills `path`, mapped by `transform`, with `color` onto `image`.
  template <class T>
  void fill(BasicImage<T>& image, const Path& path, const Affine& transform, Color color, const FillOptions& options);

  /// Flattens `path` for a fill on a width x height device (clipped flattening) into an internal buffer.
  const Polylines& flatten_for_fill(const Path& path, const Affine& transform, double tolerance, int width,
                                    int height);
  Rasterizer& rasterizer() { return rasterizer_; }

 private:
  Polylines lines_;
  Rasterizer rasterizer_;
};

}  // namespace vraster
