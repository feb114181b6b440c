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

template <class T>
class Shader {
 public:
  /// Prepares `paint` for a target whose device pixels are reached from user space by `user_to_device`.
  /// Returns false when the paint paints nothing (invisible, degenerate, singular transform); the shader is then a
  /// transparent constant.
  bool prepare(const Paint& paint, const Affine& user_to_device);

  /// A single colour everywhere (solid paint, or a gradient whose stops are all one colour): color() is all.
  bool is_constant() const { return constant_; }
  /// The constant premultiplied colour (is_constant() only).
  const T* color() const { return color_; }
  /// Every shaded pixel has full alpha.
  bool is_opaque() const { return opaque_; }

  /// Shades device pixels [x0, x0 + n) of row y (sampled at their centres) into out[0 .. 4n).
  void shade(int y, int x0, int n, T* out);

  /// Gradients: the parameter t (before the extend mode) at paint-space point p; false where the paint is
  /// transparent (a radial gradient's cone does not reach p).
  bool gradient_t(Point p, double& t) const;

 private:
  bool prepare_gradient(const Paint& paint);
  void build_lut();
  double extend_t(double t) const;
  /// Straight-interpolated, premultiplied colour at t in [0, 1], channels in [0, 1].
  void color_at(double t, float* rgba) const;
  void shade_gradient(int y, int x0, int n, T* out);
  void shade_pattern(int y, int x0, int n, T* out);

  Paint::Kind kind_ = Paint::Kind::Solid;
  bool constant_ = true, opaque_ = false, dither_ = false;
  T color_[4] = {0, 0, 0, 0};
  Affine to_paint_{};  // device -> paint space
  // Gradient geometry in paint space.
  Point p0_{}, p1_{};
  double r0_ = 0, dr_ = 0, angle_ = 0;
  Point d_{};            // linear: (p1 - p0) / |p1 - p0|^2; radial: c1 - c0
  double a_ = 0;         // radial: |c1 - c0|^2 - (r1 - r0)^2
  Extend extend_ = Extend::Pad;
  std::vector<double> offsets_;
  std::vector<float> colors_;  // straight RGBA per stop, opacity applied
  // 8-bit gradients without dithering: premultiplied colours at t = i / (kLutSize - 1), packed RGBA.
  static constexpr int kLutSize = 1024;
  std::vector<std::uint32_t> lut_;
  std::vector<double> ts_;   // one row of gradient parameters (NaN: transparent), kept across calls
  // Patterns.
  const Paint* pattern_ = nullptr;
};

/// The 8-bit bilinear sampler's arithmetic on one pixel: texels a b (top row) and c d (bottom row) as packed RGBA,
/// weights fx, fy of the right and bottom texels in [0, 4096), opacity in 16.16 fixed point (65536: opaque).
/// Per channel: round((a gx + b fx) gy + (c gx + d fx) fy) / 2^24) with g = 4096 - f, then round(q opacity / 2^16)
/// (q opacity < 2^24: 32 bits suffice).
inline std::uint32_t bilinear8_pixel(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                                     std::uint32_t fx, std::uint32_t fy, std::uint32_t opacity) {
  const std::uint32_t gx = 4096 - fx, gy = 4096 - fy;
  std::uint32_t out = 0;
  for (int sh = 0; sh < 32; sh += 8) {
    const std::uint32_t top = (a >> sh & 255u) * gx + (b >> sh & 255u) * fx;
    const std::uint32_t bottom = (c >> sh & 255u) * gx + (d >> sh & 255u) * fx;
    const std::uint32_t q = (top * gy + bottom * fy + (1u << 23)) >> 24;
    out |= ((q * opacity + 32768u) >> 16) << sh;
  }
  return out;
}

/// bilinear8_pixel over n pixels of gathered texels and weights, vectorised (AVX2 clone picked at run time); the
/// same integers, so the same results (tests/pattern_test.cpp compares it with bilinear8_pixel).
void bilinear8_run(const std::uint32_t* a, const std::uint32_t* b, const std::uint32_t* c, const std::uint32_t* d,
                   const std::uint32_t* fx, const std::uint32_t* fy, std::uint32_t opacity, int n, std::uint32_t* dst);

extern template class Shader<std::uint8_t>;
extern template class Shader<std::uint16_t>;

}  // namespace vraster::detail
