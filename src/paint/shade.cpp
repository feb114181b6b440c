// Shading: a Paint prepared for one draw call -> rows of premultiplied device colours.
#include "shade.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "blend.hpp"

namespace vraster::detail {

template <class T>
bool Shader<T>::prepare(const Paint& paint, const Affine& user_to_device) {
  using CM = ChannelMath<T>;
  paint_ = &paint;
  kind_ = paint.kind();
  constant_ = true;
  opaque_ = false;
  std::memset(color_, 0, sizeof color_);
  if (paint.is_invisible()) return false;
  opacity_ = paint.opacity();
  if (kind_ == Paint::Kind::Solid) {
    const Color c = paint.color();
    const double a = std::clamp(static_cast<double>(c.a) * opacity_, 0.0, 1.0);
    const double m = CM::M;
    color_[0] = static_cast<T>(std::lround(std::clamp(static_cast<double>(c.r), 0.0, 1.0) * a * m));
    color_[1] = static_cast<T>(std::lround(std::clamp(static_cast<double>(c.g), 0.0, 1.0) * a * m));
    color_[2] = static_cast<T>(std::lround(std::clamp(static_cast<double>(c.b), 0.0, 1.0) * a * m));
    color_[3] = static_cast<T>(std::lround(a * m));
    opaque_ = color_[3] == CM::M;
    return color_[3] != 0;
  }
  const Affine paint_to_device = user_to_device * paint.transform();
  if (!paint_to_device.is_finite() || !paint_to_device.invertible()) return false;  // transparent constant
  to_paint_ = paint_to_device.inverse();
  constant_ = false;
  return true;
}

template <class T>
void Shader<T>::shade(int y, int x0, int n, T* out) const {
  if (constant_) {
    for (int i = 0; i < n; ++i) std::memcpy(out + 4 * i, color_, sizeof color_);
    return;
  }
  // Filled in by the gradient and pattern work; transparent until then.
  (void)y;
  (void)x0;
  std::memset(out, 0, sizeof(T) * 4 * static_cast<std::size_t>(n));
}

template class Shader<std::uint8_t>;
template class Shader<std::uint16_t>;

}  // namespace vraster::detail
