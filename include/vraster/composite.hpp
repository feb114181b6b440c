// vraster: composite operators and the compositor, the one place where coverage becomes pixels.
//
//   coverage (rasterizer, CoverageSink calls) -> shade (Paint -> a row of premultiplied source colours)
//     -> scale the source by coverage x global alpha -> operator (source, destination) -> lerp by clip -> target
//
// Every fill, stroke, hairline, glyph and image draw reaches pixels through Compositor (or blend_row, for callers
// that shade their own colours, such as meshes): a fix or a fast path here helps all of them.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>
#include <type_traits>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/paint.hpp"
#include "vraster/raster.hpp"

namespace vraster {

/// The HTML canvas globalCompositeOperation values: the Porter-Duff operators, `lighter` (plus), and the blend
/// modes of W3C Compositing and Blending Level 1 (composited source-over).
enum class CompositeOp : std::uint8_t {
  SourceOver, Copy, SourceIn, SourceOut, SourceAtop,
  DestinationOver, DestinationIn, DestinationOut, DestinationAtop,
  Xor, Lighter, Clear,
  Multiply, Screen, Overlay, Darken, Lighten, ColorDodge, ColorBurn, HardLight, SoftLight,
  Difference, Exclusion, Hue, Saturation, Color, Luminosity,
};
inline constexpr int kCompositeOpCount = 27;

/// Parses a CSS / canvas name ("source-over", "copy", "lighter", "plus-lighter", "multiply", "color-dodge", ...);
/// returns false for an unknown name (out unchanged).
bool parse_composite_op(std::string_view css_name, CompositeOp& out);
std::string_view to_string(CompositeOp op);
/// Whether a transparent source leaves the destination unchanged. Unbounded operators (copy, clear, source-in,
/// source-out, destination-in, destination-atop) change pixels outside the shape: as the HTML canvas says, the
/// shape is then composited over the whole clip region with a transparent source where it does not cover.
bool is_bounded(CompositeOp op);

/// Composites `count` premultiplied source pixels `src` (same channel type as the destination) onto `dst` with
/// `op`. `coverage` (may be null: all 1) scales each source pixel first; `clip` (may be null: all full) then lerps
/// between the old and the new destination. Clip values are levels of the channel type, 0 .. 255 (8 bits) or
/// 0 .. 65535 (16 bits), i.e. round(max * clip coverage): a clip mask is stored so (1 or 2 bytes a pixel, not a
/// float) and used as is. 8 bits: rounded as documented in docs/design.md; 16 bits: 16-bit arithmetic throughout.
template <class T>
void blend_row(CompositeOp op, T* dst, const T* src, const float* coverage, const std::type_identity_t<T>* clip,
               int count);

/// As blend_row with every coverage value equal to `alpha` (a layer's opacity): no coverage row needed.
template <class T>
void blend_row_alpha(CompositeOp op, T* dst, const T* src, float alpha, const std::type_identity_t<T>* clip,
                     int count);

/// A CoverageSink that paints with a Paint and an operator onto an ImageView. Coverage scales the source (the
/// HTML canvas model: the shape is an image whose alpha is its coverage); for bounded operators this equals
/// lerping by coverage. Decides once per span what it needs: an opaque solid span with source-over stores
/// without blending, an invisible paint with a bounded operator draws nothing.
///
/// Calls use device coordinates inside the view; the view's (x0, y0) is the device position of its first pixel.
/// One Compositor is meant to be reused for many draw calls (set() per call): it keeps its shading buffers, so
/// steady-state drawing allocates nothing.
template <class T>
class Compositor final : public CoverageSink {
 public:
  Compositor();
  ~Compositor() override;
  Compositor(Compositor&&) noexcept;
  Compositor& operator=(Compositor&&) noexcept;

  /// Prepares one draw call. `user_to_device` maps user space to device pixels; the paint's own transform is
  /// applied first. The paint (and its pattern image) must outlive the calls that follow.
  void set(ImageView<T> target, const Paint& paint, const Affine& user_to_device, CompositeOp op,
           float global_alpha = 1);

  void span(int y, int x0, int x1, float coverage) override;
  void row(int y, int x0, int x1, const float* coverage) override;
  void rows(const CoverageRow* rows, std::size_t count) override;
  /// As row(), then lerps by `clip` (may be null; levels as in blend_row). For unbounded operators the caller covers
  /// the whole clip region row by row, with coverage 0 where the shape is absent. `coverage` may be null here:
  /// coverage 1 everywhere.
  void row(int y, int x0, int x1, const float* coverage, const T* clip);
  /// As span(), then lerps by `clip` (may be null; levels): a run of constant coverage through a clip mask's row.
  void span(int y, int x0, int x1, float coverage, const T* clip);

  /// True when the current draw call paints one constant colour: span() and row() then change nothing but the
  /// target's pixels, so rows may come from several threads. (Gradients and patterns shade into a buffer kept in
  /// the compositor: their calls stay on one thread.)
  bool takes_concurrent_rows() const override;
  void expect(int y0, int y1, int x0, int x1) override;
  /// 8-bit pixels under a solid paint, source-over, global alpha 1: the target view's pixels and the colour, so that
  /// the rasterizer may blend runs straight from its cells (row() gives those runs the same pixels).
  bool solid_over8(SolidOver8& target) const override;

  /// True when nothing the current draw call could do changes a pixel (invisible paint or zero alpha with a
  /// bounded operator): callers skip rasterization altogether.
  bool draws_nothing() const;

 private:
  struct State;  // shading buffers and the prepared paint (src/paint/)
  std::unique_ptr<State> state_;
};

extern template class Compositor<std::uint8_t>;
extern template class Compositor<std::uint16_t>;

}  // namespace vraster
