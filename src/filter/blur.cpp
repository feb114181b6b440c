// Separable Gaussian blur: horizontal pass into a float image, vertical pass back into the view.
//
//   kernel: tap i = Gaussian mass over [i - 1/2, i + 1/2] (erf differences), |i| <= r, renormalised
//   -> rows: each row, zero padded by r, convolved (float RGBA)  -> columns: sum of w_i x row (y + i) -> round
#include "vraster/blur.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vraster {
namespace {

// Fills taps for offsets 0 .. r and returns r (capped at `limit`: taps farther than the image never reach a
// pixel, so they are left out without changing any result; the normalisation still counts the full kernel).
int make_kernel(double sigma, double reach, int limit, std::vector<float>& kernel) {
  const double full = std::ceil(reach * sigma);
  const int r = static_cast<int>(std::min<double>(full, limit));
  const double s2 = sigma * std::sqrt(2.0);
  const double total = std::erf((full + 0.5) / s2);  // mass over [-(full + 1/2), full + 1/2]
  kernel.resize(static_cast<std::size_t>(r) + 1);
  for (int i = 0; i <= r; ++i) {
    const double mass = 0.5 * (std::erf((i + 0.5) / s2) - std::erf((i - 0.5) / s2));
    kernel[static_cast<std::size_t>(i)] = static_cast<float>(mass / total);
  }
  return r;
}

bool usable(double sigma) { return std::isfinite(sigma) && sigma > 0; }

}  // namespace

template <class T>
void GaussianBlur::apply(const ImageView<T>& image, double sigma_x, double sigma_y) {
  const bool bx = usable(sigma_x), by = usable(sigma_y);
  const int w = image.width, h = image.height;
  if ((!bx && !by) || w <= 0 || h <= 0 || image.pixels == nullptr) return;
  constexpr float kMax = static_cast<float>(BasicImage<T>::kMax);
  constexpr float kInv = 1.f / kMax;
  const double reach = sizeof(T) == 1 ? 4.0 : 5.0;
  const std::size_t row_len = static_cast<std::size_t>(w) * 4;
  rows_.resize(row_len * static_cast<std::size_t>(h));

  // Horizontal pass (or a plain conversion) into rows_.
  const int rx = bx ? make_kernel(sigma_x, reach, w - 1, kernel_) : 0;
  line_.assign((static_cast<std::size_t>(w) + 2 * static_cast<std::size_t>(rx)) * 4, 0.f);
  for (int y = 0; y < h; ++y) {
    const T* src = image.pixels + static_cast<std::ptrdiff_t>(y) * image.stride;
    float* out = rows_.data() + row_len * static_cast<std::size_t>(y);
    if (!bx) {
      for (std::size_t j = 0; j < row_len; ++j) out[j] = static_cast<float>(src[j]) * kInv;
      continue;
    }
    float* padded = line_.data() + static_cast<std::size_t>(rx) * 4;
    for (std::size_t j = 0; j < row_len; ++j) padded[j] = static_cast<float>(src[j]) * kInv;
    const float k0 = kernel_[0];
    for (std::size_t j = 0; j < row_len; ++j) out[j] = k0 * padded[j];
    for (int i = 1; i <= rx; ++i) {
      const float k = kernel_[static_cast<std::size_t>(i)];
      const float* left = padded - 4 * i;
      const float* right = padded + 4 * i;
      for (std::size_t j = 0; j < row_len; ++j) out[j] += k * (left[j] + right[j]);
    }
  }

  // Vertical pass: each output row is the weighted sum of the rows around it.
  const int ry = by ? make_kernel(sigma_y, reach, h - 1, kernel_) : 0;
  line_.resize(row_len);
  float* acc = line_.data();
  for (int y = 0; y < h; ++y) {
    const float* centre = rows_.data() + row_len * static_cast<std::size_t>(y);
    if (!by) {
      std::copy(centre, centre + row_len, acc);
    } else {
      const float k0 = kernel_[0];
      for (std::size_t j = 0; j < row_len; ++j) acc[j] = k0 * centre[j];
      for (int i = 1; i <= ry; ++i) {
        const float k = kernel_[static_cast<std::size_t>(i)];
        if (y - i >= 0) {
          const float* up = rows_.data() + row_len * static_cast<std::size_t>(y - i);
          for (std::size_t j = 0; j < row_len; ++j) acc[j] += k * up[j];
        }
        if (y + i < h) {
          const float* down = rows_.data() + row_len * static_cast<std::size_t>(y + i);
          for (std::size_t j = 0; j < row_len; ++j) acc[j] += k * down[j];
        }
      }
    }
    T* dst = image.pixels + static_cast<std::ptrdiff_t>(y) * image.stride;
    for (std::size_t j = 0; j < row_len; j += 4) {
      const float a = std::clamp(acc[j + 3] * kMax + 0.5f, 0.f, kMax);
      const auto qa = static_cast<std::uint32_t>(a);
      for (std::size_t c = 0; c < 3; ++c) {
        const auto q = static_cast<std::uint32_t>(std::clamp(acc[j + c] * kMax + 0.5f, 0.f, kMax));
        dst[j + c] = static_cast<T>(std::min(q, qa));
      }
      dst[j + 3] = static_cast<T>(qa);
    }
  }
}

template void GaussianBlur::apply(const ImageView<std::uint8_t>&, double, double);
template void GaussianBlur::apply(const ImageView<std::uint16_t>&, double, double);

}  // namespace vraster
