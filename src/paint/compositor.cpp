// Compositing: coverage spans + a solid colour -> premultiplied pixels, source-over.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "blend.hpp"
#include "vraster/renderer.hpp"

namespace vraster {
namespace {

using detail::scale8;

inline std::uint64_t mul_div16(std::uint64_t a, std::uint64_t b) { return (a * b + 32767) / 65535; }

// std::lround's value for v in [0, 2^52], inline (a fill of a few pixels builds its compositor, and the library calls
// were a third of that): the fraction left by truncation is exact, so comparing it with 0.5 rounds half up as lround.
inline std::uint64_t round_channel(double v) {
  const auto whole = static_cast<std::uint64_t>(v);
  return whole + (v - static_cast<double>(whole) >= 0.5 ? 1 : 0);
}

// A colour channel or alpha in [0, 1]; NaN counts as 0.
inline double unit_channel(double v) { return v > 0 ? std::min(v, 1.0) : 0.0; }

}  // namespace

template <class T>
SolidCompositor<T>::SolidCompositor(BasicImage<T>& image, Color color) : image_(image) {
  alpha_ = static_cast<float>(unit_channel(color.a));
  const double scale = BasicImage<T>::kMax;
  const double ch[3] = {color.r, color.g, color.b};
  for (int i = 0; i < 3; ++i) premul_[i] = round_channel(unit_channel(ch[i]) * alpha_ * scale);
  premul_[3] = round_channel(alpha_ * scale);
  if constexpr (sizeof(T) == 1) {
    packed8_ = static_cast<std::uint32_t>(premul_[0] | premul_[1] << 8 | premul_[2] << 16 | premul_[3] << 24);
    over_constant_ = detail::over8_constant_for_cpu();
    over_solid_ = detail::over8_solid_for_cpu();
  }
}

template <class T>
bool SolidCompositor<T>::solid_over8(SolidOver8& target) const {
  if constexpr (sizeof(T) == 1) {
    if (premul_[3] == 0 || image_.width <= 0 || image_.height <= 0) return false;  // nothing to draw: row() returns
    target = {image_.data.data(), static_cast<std::ptrdiff_t>(image_.width) * 4, packed8_, 0, 0, image_.width,
              image_.height};
    return true;
  } else {
    return false;
  }
}

template <class T>
void SolidCompositor<T>::expect(int y0, int y1, int x0, int x1) {
  detail::prefetch_pixels(ImageView<T>::of(image_), y0, y1, x0, x1);
}

template <class T>
void SolidCompositor<T>::span(int y, int x0, int x1, float coverage) {
  if constexpr (sizeof(T) == 1) {
    span8(y, x0, x1, coverage);
  } else {
    span16(y, x0, x1, coverage);
  }
}

template <class T>
void SolidCompositor<T>::row(int y, int x0, int x1, const float* coverage) {
  if constexpr (sizeof(T) == 1) {
    row8(y, x0, x1, coverage);
  } else {
    for (int x = x0; x < x1; ++x) {
      if (coverage[x - x0] > 0) span16(y, x, x + 1, coverage[x - x0]);
    }
  }
}

template <class T>
void SolidCompositor<T>::rows(const CoverageRow* rows, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) row(rows[i].y, rows[i].x0, rows[i].x1, rows[i].coverage);  // no virtual call
}

template <class T>
void SolidCompositor<T>::span8(int y, int x0, int x1, float coverage) {
  const auto cov = static_cast<std::uint32_t>(coverage * 255.f + 0.5f);
  if (cov == 0 || premul_[3] == 0) return;
  const std::uint32_t color = packed8_;
  auto* px = reinterpret_cast<std::uint32_t*>(static_cast<void*>(image_.pixel(x0, y)));
  const int n = x1 - x0;
  if (cov == 255 && premul_[3] == 255) {  // opaque: store, no blending
    detail::store8(px, n, color);
    return;
  }
  const std::uint32_t source = cov == 255 ? color : scale8(color, cov);
  if (n == 1) {  // a lone edge pixel (thin shapes have many): over8_constant's arithmetic without its call
    *px = detail::over8(source, *px);
    return;
  }
  over_constant_(px, n, source);
}

template <class T>
void SolidCompositor<T>::row8(int y, int x0, int x1, const float* coverage) {
  if (premul_[3] == 0) return;
  const std::uint32_t color = packed8_;
  auto* px = reinterpret_cast<std::uint32_t*>(static_cast<void*>(image_.pixel(x0, y)));
  if (x1 - x0 == 1) {  // a lone pixel (a third of a thin shape's rows): the kernel's arithmetic without its call
    *px = detail::over8(scale8(color, detail::quantize8(coverage[0])), *px);
    return;
  }
  over_solid_(px, x1 - x0, coverage, 1.f, color);  // coverage in [0, 1]: quantize8 is round(255 c)
}

template <class T>
void SolidCompositor<T>::span16(int y, int x0, int x1, float coverage) {
  const auto cov = static_cast<std::uint64_t>(std::lround(static_cast<double>(coverage) * 65535.0));
  if (cov == 0 || premul_[3] == 0) return;
  std::uint64_t src[4];
  for (int c = 0; c < 4; ++c) src[c] = mul_div16(premul_[c], cov);
  const std::uint64_t inv = 65535 - src[3];
  T* px = image_.pixel(x0, y);
  for (int i = 0; i < x1 - x0; ++i, px += 4) {
    for (int c = 0; c < 4; ++c) px[c] = static_cast<T>(src[c] + mul_div16(px[c], inv));
  }
}

template class SolidCompositor<std::uint8_t>;
template class SolidCompositor<std::uint16_t>;

}  // namespace vraster
