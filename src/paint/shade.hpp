// Private: a Paint prepared for one draw call, shading rows of device pixels into premultiplied colours.
//
//   Paint (paint space) + user_to_device -> device_to_paint (inverse) -> per pixel centre: paint-space point
//   -> gradient parameter t (linear / radial / conic) -> extend -> colour from the stops
//      or pattern texel(s) -> filter -> premultiplied T
#pragma once

#include <cstdint>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/paint.hpp"

namespace vraster::detail {

/// One gradient stop, straight RGBA (opacity applied), kept for interpolation.
struct StopF {
  double offset;
  float rgba[4];
};

template <class T>
class Shader {
 public:
  /// Prepares `paint` for a target whose device pixels are reached from user space by `user_to_device`.
  /// Returns false when the paint paints nothing (invisible, degenerate, singular transform).
  bool prepare(const Paint& paint, const Affine& user_to_device);

  /// A single colour everywhere (solid paint, or a gradient with one stop): color() is all there is to shade.
  bool is_constant() const { return constant_; }
  /// The constant premultiplied colour (is_constant() only).
  const T* color() const { return color_; }
  /// Every shaded pixel has full alpha.
  bool is_opaque() const { return opaque_; }

  /// Shades device pixels [x0, x0 + n) of row y (sampled at their centres) into out[0 .. 4n).
  void shade(int y, int x0, int n, T* out) const;

 private:
  void shade_gradient(int y, int x0, int n, T* out) const;
  void shade_pattern(int y, int x0, int n, T* out) const;
  void build_lut();
  void color_at(double t, float* rgba) const;
  T* store(const float* rgba, T* out, int x, int y) const;

  const Paint* paint_ = nullptr;
  Paint::Kind kind_ = Paint::Kind::Solid;
  bool constant_ = true, opaque_ = false, dither_ = false;
  T color_[4] = {0, 0, 0, 0};
  Affine to_paint_{};  // device -> paint space
  // Gradient geometry in paint space.
  Point p0_{}, p1_{};
  double r0_ = 0, r1_ = 0, angle_ = 0;
  // Radial: precomputed terms of the quadratic (see shade.cpp).
  double cdx_ = 0, cdy_ = 0, dr_ = 0, a_ = 0;
  Extend extend_ = Extend::Pad;
  std::vector<StopF> stops_;
  // 8-bit gradients without dithering: a table of packed premultiplied colours over t in [0, 1].
  std::vector<std::uint32_t> lut_;
  float opacity_ = 1;
};

extern template class Shader<std::uint8_t>;
extern template class Shader<std::uint16_t>;

}  // namespace vraster::detail
