// vraster: the coverage producer of every draw call (Renderer) and the solid source-over compositor.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

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
  void rows(const CoverageRow* rows, std::size_t count) override;
  /// Rows are independent pixels and nothing changes between calls.
  bool takes_concurrent_rows() const override { return true; }
  void expect(int y0, int y1, int x0, int x1) override;
  /// A copy drawing the same colour onto the same image.
  std::unique_ptr<CoverageSink> clone() const override { return std::make_unique<SolidCompositor>(*this); }
  CoverageSink* clone_into(void* storage, std::size_t bytes) const override {
    return bytes >= sizeof(SolidCompositor) ? new (storage) SolidCompositor(*this) : nullptr;
  }
  /// 8-bit images with a colour that is not fully transparent: the rasterizer may blend runs itself.
  bool solid_over8(SolidOver8& target) const override;

 private:
  void span8(int y, int x0, int x1, float coverage);
  void row8(int y, int x0, int x1, const float* coverage);
  void span16(int y, int x0, int x1, float coverage);

  BasicImage<T>& image_;
  float alpha_;              // colour alpha in [0, 1]
  std::uint64_t premul_[4];  // colour premultiplied, scaled to the channel range
  std::uint32_t packed8_ = 0;  // 8-bit targets: premul_ as one pixel (R in the low byte)
  // 8-bit targets: the source-over loops for this processor (AVX2 or portable), picked once.
  void (*over_constant_)(std::uint32_t* px, int n, std::uint32_t s) = nullptr;
  void (*over_solid_)(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c) = nullptr;
};

extern template class SolidCompositor<std::uint8_t>;
extern template class SolidCompositor<std::uint16_t>;

/// How a fill is rendered.
struct FillOptions {
  FillRule rule = FillRule::NonZero;
  AntiAlias aa = AntiAlias::Analytic;
  double tolerance = kDefaultTolerance;  ///< flattening tolerance in device pixels
};

enum class HairlineMode : std::uint8_t;  // vraster/stroke.hpp
struct StrokeStyle;
struct StrokeRenderOptions;

namespace detail {
struct RendererScratch;  // src/paint/renderer.cpp: buffers of hairlines and masks
}

/// The coverage side of the seam: turns paths, hairlines and coverage masks into CoverageSink calls on a
/// width x height device, and never touches a pixel itself. Whoever draws hands it a compositor (paint +
/// operator + target, possibly behind a clip) as the sink:
///
///   fill / stroke / hairlines / mask  ->  Renderer (flatten, rasterize)  ->  CoverageSink  ->  compositor -> pixels
///
/// Keeps the flattening buffer, the rasterizer and the hairline and mask buffers between calls: one Renderer per
/// thread, reused for every draw call, allocates nothing for fills in steady state. No global state.
class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;

  /// Coverage of `path`, mapped by `transform`, on a width x height device.
  void fill(const Path& path, const Affine& transform, const FillOptions& options, int width, int height,
            CoverageSink& sink);

  /// Coverage of the stroke of `path` (user space) under `style`, mapped by `transform` (vraster/stroke.hpp):
  /// strokes at least one device pixel wide are geometry (stroke_to_path, then fill() non-zero); thinner ones are
  /// hairlines (thin_stroke_mode) with coverage scaled by their device width. Nothing for an invisible style or a
  /// non-finite transform.
  void stroke(const Path& path, const Affine& transform, const StrokeStyle& style, const StrokeRenderOptions& options,
              int width, int height, CoverageSink& sink);

  /// Coverage of every contour of `path`, mapped by `transform` and flattened at 0.1 px, drawn as 1-device-pixel
  /// hairlines (see HairlineMode; vraster/stroke.hpp). Per-pixel algorithms hand over each pixel's summed
  /// coverage (clamped to 1: a pixel hit twice counts once fully) in row order; Analytic hands over the
  /// rasterizer's coverage of a 1-px butt-capped stroke. Coverage is multiplied by `coverage_scale` (clamped to
  /// (0, 1]). Geometry far outside the device costs only the visible part.
  void hairlines(const Path& path, const Affine& transform, HairlineMode mode, int width, int height,
                 CoverageSink& sink, float coverage_scale = 1.0f);

  /// Coverage from an 8-bit mask (255 = full) whose pixel (0, 0) lands on device pixel (x, y), clipped to the
  /// width x height device: cached glyphs and other pre-rendered coverage take the same seam as paths.
  void mask(const std::uint8_t* mask, int mask_width, int mask_height, std::ptrdiff_t stride, int x, int y, int width,
            int height, CoverageSink& sink);

  /// As fill() above, handing `sink` over: with threads (set_threads(n > 1)) the fill may wait in the rasterizer's
  /// queue until flush() (Rasterizer::fill_queued: which fills queue, and why the pixels are the same).
  void fill(const Path& path, const Affine& transform, const FillOptions& options, int width, int height,
            std::unique_ptr<CoverageSink> sink);
  /// As fill() above with a borrowed sink: a fill that waits keeps a copy of it (CoverageSink::clone_into or clone);
  /// a sink that gives none is drawn at once (Rasterizer::fill_queued).
  void fill_queued(const Path& path, const Affine& transform, const FillOptions& options, int width, int height,
                   CoverageSink& sink);

  /// Convenience for tools and tests: fills `path`, mapped by `transform`, with one solid `color` source-over onto
  /// `image` (a SolidCompositor). With threads the fill is queued (fill_queued): call flush() before reading
  /// `image`. Drawing code with paints, operators or clips uses fill() with its own compositor (or the
  /// Canvas).
  template <class T>
  void fill(BasicImage<T>& image, const Path& path, const Affine& transform, Color color, const FillOptions& options);

  /// Draws every queued fill (see above). Every other drawing call of this renderer (fill() with a borrowed sink,
  /// stroke(), hairlines(), mask()), set_threads() and the destructor flush first, so the painter's order holds
  /// across them; only reading or writing the image by other means needs an explicit flush().
  void flush() { rasterizer_.flush(); }

  /// Flattens `path` for a fill on a width x height device (clipped flattening) into an internal buffer.
  const Polylines& flatten_for_fill(const Path& path, const Affine& transform, double tolerance, int width,
                                    int height);
  Rasterizer& rasterizer() { return rasterizer_; }
  /// Threads for large fills and queued frames (Rasterizer::set_threads, fill_queued): same pixels, bit for bit,
  /// as one thread.
  void set_threads(int threads) { rasterizer_.set_threads(threads); }
  int threads() const { return rasterizer_.threads(); }
  /// Points flattened by this renderer's fills so far (for work limits across many draw calls).
  std::uint64_t flattened_points() const { return flattened_points_; }

 private:
  Polylines lines_;
  std::uint64_t flattened_points_ = 0;
  Rasterizer rasterizer_;
  std::unique_ptr<detail::RendererScratch> scratch_;
};

}  // namespace vraster
