// Separable Gaussian blur for shadows.
#include "canvas/shadow_blur.hpp"

#include <cmath>

namespace vraster::canvas_detail {

int blur_reach(double sigma) { return sigma > 0 ? static_cast<int>(std::ceil(3 * sigma)) : 0; }

void gaussian_blur(std::vector<float>& plane, std::vector<float>& scratch, int width, int height, double sigma) {
  const int reach = blur_reach(sigma);
  if (reach == 0 || width <= 0 || height <= 0) return;
  std::vector<float> kernel(2 * static_cast<std::size_t>(reach) + 1);
  double sum = 0;
  for (int i = -reach; i <= reach; ++i) {
    const double w = std::exp(-0.5 * i * i / (sigma * sigma));
    kernel[i + reach] = static_cast<float>(w);
    sum += w;
  }
  for (float& k : kernel) k = static_cast<float>(k / sum);
  scratch.assign(plane.size(), 0.f);
  // Rows: plane -> scratch.
  for (int y = 0; y < height; ++y) {
    const float* src = plane.data() + static_cast<std::size_t>(y) * width;
    float* dst = scratch.data() + static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x) {
      double acc = 0;
      const int lo = x - reach < 0 ? -x : -reach, hi = x + reach >= width ? width - 1 - x : reach;
      for (int i = lo; i <= hi; ++i) acc += kernel[i + reach] * src[x + i];
      dst[x] = static_cast<float>(acc);
    }
  }
  // Columns: scratch -> plane.
  for (int y = 0; y < height; ++y) {
    const int lo = y - reach < 0 ? -y : -reach, hi = y + reach >= height ? height - 1 - y : reach;
    float* dst = plane.data() + static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x) dst[x] = 0;
    for (int i = lo; i <= hi; ++i) {
      const float k = kernel[i + reach];
      const float* src = scratch.data() + static_cast<std::size_t>(y + i) * width;
      for (int x = 0; x < width; ++x) dst[x] += k * src[x];
    }
  }
}

}  // namespace vraster::canvas_detail
