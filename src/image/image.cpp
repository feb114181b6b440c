// Images: allocation with size limits, clearing.
#include "vraster/image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "vraster/error.hpp"

namespace vraster {

namespace {
// A side for a message: whole pixels while they fit an integer, else in exponent form (casting 1e50 to an
// integer type is undefined).
std::string side_text(double v) {
  if (v < 1e15) return std::to_string(static_cast<long long>(v));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
}  // namespace

void check_image_size(double width, double height) {
  if (!std::isfinite(width) || !std::isfinite(height) || width < 1 || height < 1) {
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is not a positive size");
  }
  if (width > kMaxImageSide || height > kMaxImageSide || width * height > static_cast<double>(kMaxImagePixels)) {
    throw Error("image size " + side_text(width) + "x" + side_text(height) + " is too large (at most " +
                std::to_string(kMaxImageSide) + " pixels a side and " + std::to_string(kMaxImagePixels) +
                " pixels)");
  }
}

template <class T>
BasicImage<T>::BasicImage(int w, int h) : width(w), height(h) {
  check_image_size(w, h);
  data.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0);
}

template <class T>
void BasicImage<T>::clear(Color c) {
  const double a = std::clamp(static_cast<double>(c.a), 0.0, 1.0);
  const double scale = kMax;
  const T px[4] = {static_cast<T>(std::lround(std::clamp(static_cast<double>(c.r), 0.0, 1.0) * a * scale)),
                   static_cast<T>(std::lround(std::clamp(static_cast<double>(c.g), 0.0, 1.0) * a * scale)),
                   static_cast<T>(std::lround(std::clamp(static_cast<double>(c.b), 0.0, 1.0) * a * scale)),
                   static_cast<T>(std::lround(a * scale))};
  if (px[0] == px[1] && px[1] == px[2] && px[2] == px[3] && sizeof(T) == 1) {
    std::memset(data.data(), px[0], data.size());
    return;
  }
  // Fill the first row, then copy it: whole-row copies are memcpy speed.
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (std::size_t i = 0; i < row; i += 4) std::copy(px, px + 4, data.begin() + static_cast<std::ptrdiff_t>(i));
  for (std::size_t y = 1; y < static_cast<std::size_t>(height); ++y) {
    std::copy(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(row), data.begin() + static_cast<std::ptrdiff_t>(y * row));
  }
}

template struct BasicImage<std::uint8_t>;
template struct BasicImage<std::uint16_t>;

}  // namespace vraster
