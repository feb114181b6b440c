// vraster: images (RGBA, premultiplied) and colours.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vraster {

/// A straight (not premultiplied) colour with channels in [0, 1].
struct Color {
  float r = 0, g = 0, b = 0, a = 1;

  static constexpr Color rgb8(int r, int g, int b, int a = 255) {
    return {static_cast<float>(r) / 255.f, static_cast<float>(g) / 255.f, static_cast<float>(b) / 255.f,
            static_cast<float>(a) / 255.f};
  }
  static constexpr Color transparent() { return {0, 0, 0, 0}; }
  constexpr Color with_alpha(float alpha) const { return {r, g, b, a * alpha}; }
};

/// Largest accepted image side and pixel count (bigger requests throw vraster::Error).
inline constexpr int kMaxImageSide = 1 << 15;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 26;  // 8192 x 8192: 256 MiB at 8 bits, 512 MiB at 16

/// An RGBA image with premultiplied channels of type T (uint8_t: 8 bits, uint16_t: 16 bits per channel),
/// stored row by row, 4 channels a pixel, no padding.
template <class T>
struct BasicImage {
  using Channel = T;
  static constexpr std::uint32_t kMax = (1u << (8 * sizeof(T))) - 1;

  int width = 0;
  int height = 0;
  std::vector<T> data;

  BasicImage() = default;
  /// Throws vraster::Error for sizes <= 0 or above the limits.
  BasicImage(int w, int h);

  T* pixel(int x, int y) { return data.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  const T* pixel(int x, int y) const { return data.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  /// Fills every pixel with c (premultiplied on the way in).
  void clear(Color c);
};

using Image = BasicImage<std::uint8_t>;
using Image16 = BasicImage<std::uint16_t>;

/// A view of pixels someone else owns: premultiplied RGBA with channels of type T, covering the device pixels
/// [x0, x0 + width) x [y0, y0 + height). Pixel (x, y) starts at pixels + (y - y0) * stride + (x - x0) * 4, so a
/// layer that covers only part of the canvas is addressed in canvas coordinates. `stride` counts channels (T
/// values), not bytes.
template <class T>
struct ImageView {
  T* pixels = nullptr;
  int x0 = 0, y0 = 0;
  int width = 0, height = 0;
  std::ptrdiff_t stride = 0;

  T* pixel(int x, int y) const { return pixels + (y - y0) * stride + static_cast<std::ptrdiff_t>(x - x0) * 4; }
  bool contains(int x, int y) const { return x >= x0 && y >= y0 && x < x0 + width && y < y0 + height; }
  static ImageView of(BasicImage<T>& image) {
    return {image.data.data(), 0, 0, image.width, image.height, static_cast<std::ptrdiff_t>(image.width) * 4};
  }
};

/// Checks an image size against the limits; throws vraster::Error naming the problem.
void check_image_size(double width, double height);

extern template struct BasicImage<std::uint8_t>;
extern template struct BasicImage<std::uint16_t>;

}  // namespace vraster
