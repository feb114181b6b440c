// vraster: Gaussian blur of premultiplied images (canvas shadows, SVG feGaussianBlur).
#pragma once

#include <vector>

#include "vraster/image.hpp"

namespace vraster {

/// A separable Gaussian blur that keeps its buffers between calls (steady state allocates nothing).
///
/// What it computes: the image seen as a piecewise-constant function (each pixel a unit square), convolved with
/// the 2-D Gaussian of standard deviations (sigma_x, sigma_y), sampled at pixel centres; pixels outside the view
/// are transparent. The kernel tap for offset i is the Gaussian's mass over [i - 1/2, i + 1/2], truncated at
/// |i| <= ceil(4 sigma) (8 bits) or ceil(5 sigma) (16 bits) and renormalised: the truncation moves a result by at
/// most 6.4e-5 (8 bits: 1/60 of a level) or 5.8e-7 (16 bits: 1/26 of a level) of full scale, so with float
/// accumulation each channel is within 0.6 of a level of the exact blur (tests/blur_test.cpp: against a slow 2-D
/// convolution). Cost: O(width x height x (taps_x + taps_y)).
class GaussianBlur {
 public:
  /// Blurs `image` in place. A sigma <= 0 or non-finite leaves that axis alone.
  template <class T>
  void apply(const ImageView<T>& image, double sigma_x, double sigma_y);

 private:
  std::vector<float> kernel_;  // taps for offsets 0 .. r (symmetric)
  std::vector<float> line_;    // one padded row
  std::vector<float> rows_;    // the horizontally blurred image, float RGBA
};

/// One-off convenience over GaussianBlur::apply.
template <class T>
void gaussian_blur(const ImageView<T>& image, double sigma_x, double sigma_y) {
  GaussianBlur blur;
  blur.apply(image, sigma_x, sigma_y);
}

}  // namespace vraster
