// Shading: a Paint prepared for one draw call -> rows of premultiplied device colours.
#include "shade.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "blend.hpp"
#include "vraster/image.hpp"

namespace vraster::detail {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Bayer 8 x 8 ordered-dither thresholds: (index + 0.5) / 64 is a threshold in (0, 1) whose mean is 1/2.
constexpr std::uint8_t kBayer8[8][8] = {
    {0, 32, 8, 40, 2, 34, 10, 42},  {48, 16, 56, 24, 50, 18, 58, 26}, {12, 44, 4, 36, 14, 46, 6, 38},
    {60, 28, 52, 20, 62, 30, 54, 22}, {3, 35, 11, 43, 1, 33, 9, 41},  {51, 19, 59, 27, 49, 17, 57, 25},
    {15, 47, 7, 39, 13, 45, 5, 37}, {63, 31, 55, 23, 61, 29, 53, 21},
};

float clamp01f(float v) { return v > 0 ? (v < 1 ? v : 1) : 0; }

}  // namespace

template <class T>
bool Shader<T>::prepare(const Paint& paint, const Affine& user_to_device) {
  using CM = ChannelMath<T>;
  kind_ = paint.kind();
  constant_ = true;
  opaque_ = false;
  pattern_ = nullptr;
  std::memset(color_, 0, sizeof color_);
  if (paint.is_invisible()) return false;
  if (kind_ == Paint::Kind::Solid) {
    const Color c = paint.color();
    const double a = std::clamp(static_cast<double>(c.a) * paint.opacity(), 0.0, 1.0);
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
  if (!to_paint_.is_finite()) return false;
  if (kind_ == Paint::Kind::Pattern) {
    pattern_ = &paint;
    constant_ = false;
    return true;
  }
  return prepare_gradient(paint);
}

template <class T>
bool Shader<T>::prepare_gradient(const Paint& paint) {
  using CM = ChannelMath<T>;
  extend_ = paint.extend_x();
  dither_ = sizeof(T) == 1 && paint.dither();
  p0_ = paint.p0();
  p1_ = paint.p1();
  r0_ = paint.r0();
  dr_ = paint.r1() - paint.r0();
  angle_ = paint.angle();
  bool covers_plane = true;  // every point gets a colour (false for radial gradients whose cone leaves gaps)
  if (kind_ == Paint::Kind::Linear) {
    const Point d = p1_ - p0_;
    d_ = d * (1.0 / dot(d, d));
  } else if (kind_ == Paint::Kind::Radial) {
    d_ = p1_ - p0_;
    a_ = dot(d_, d_) - dr_ * dr_;
    covers_plane = length(d_) + std::min(paint.r0(), paint.r1()) < std::max(paint.r0(), paint.r1());
  }
  // Stops: straight RGBA with the paint's opacity, clamped.
  const auto& stops = paint.stops();
  offsets_.clear();
  colors_.clear();
  bool same = true, opaque = true;
  for (const ColorStop& st : stops) {
    offsets_.push_back(st.offset);
    const float rgba[4] = {clamp01f(st.color.r), clamp01f(st.color.g), clamp01f(st.color.b),
                           clamp01f(st.color.a) * paint.opacity()};
    if (!colors_.empty() && !std::equal(rgba, rgba + 4, colors_.end() - 4)) same = false;
    if (rgba[3] < 1) opaque = false;
    colors_.insert(colors_.end(), rgba, rgba + 4);
  }
  opaque_ = opaque && covers_plane;
  if (same && covers_plane) {
    float c[4];
    color_at(0, c);
    for (int i = 0; i < 4; ++i) color_[i] = static_cast<T>(c[i] * static_cast<float>(CM::M) + 0.5f);
    return true;
  }
  constant_ = false;
  if (sizeof(T) == 1 && !dither_) build_lut();
  return true;
}

template <class T>
void Shader<T>::color_at(double t, float* rgba) const {
  const std::size_t n = offsets_.size();
  // The last stop with offset <= t: equal offsets make a step, the later stop wins from its offset on.
  const std::size_t hi = static_cast<std::size_t>(std::upper_bound(offsets_.begin(), offsets_.end(), t) - offsets_.begin());
  float straight[4];
  if (hi == 0) {
    std::copy(colors_.begin(), colors_.begin() + 4, straight);
  } else if (hi == n) {
    std::copy(colors_.end() - 4, colors_.end(), straight);
  } else {
    const std::size_t lo = hi - 1;
    const float u = static_cast<float>((t - offsets_[lo]) / (offsets_[hi] - offsets_[lo]));
    const float* a = &colors_[lo * 4];
    const float* b = &colors_[hi * 4];
    for (int c = 0; c < 4; ++c) straight[c] = a[c] + (b[c] - a[c]) * u;
  }
  // The HTML canvas interpolates straight (not premultiplied) RGBA; premultiply afterwards.
  const float alpha = clamp01f(straight[3]);
  for (int c = 0; c < 3; ++c) rgba[c] = clamp01f(straight[c]) * alpha;
  rgba[3] = alpha;
}

template <class T>
void Shader<T>::build_lut() {
  lut_.resize(kLutSize);
  for (int i = 0; i < kLutSize; ++i) {
    float c[4];
    color_at(static_cast<double>(i) / (kLutSize - 1), c);
    std::uint32_t packed = 0;
    for (int ch = 0; ch < 4; ++ch) packed |= static_cast<std::uint32_t>(c[ch] * 255.f + 0.5f) << (8 * ch);
    lut_[static_cast<std::size_t>(i)] = packed;
  }
}

template <class T>
double Shader<T>::extend_t(double t) const {
  double r;
  switch (extend_) {
    case Extend::Repeat: r = t - std::floor(t); break;
    case Extend::Reflect: {
      const double m = t - 2 * std::floor(t * 0.5);  // [0, 2)
      r = m <= 1 ? m : 2 - m;
      break;
    }
    default: return t > 0 ? (t < 1 ? t : 1) : 0;  // pad (NaN -> 0)
  }
  return r >= 0 && r <= 1 ? r : 0;  // infinite t: any value in range will do
}

template <class T>
bool Shader<T>::gradient_t(Point p, double& t) const {
  switch (kind_) {
    case Paint::Kind::Linear: t = dot(p - p0_, d_); return true;
    case Paint::Kind::Conic: {
      const Point d = p - p0_;
      const double turn = (std::atan2(d.y, d.x) - angle_) * (1 / kTwoPi);
      t = turn - std::floor(turn);
      return true;
    }
    case Paint::Kind::Radial: {
      // The HTML canvas cone of circles c(w) = c0 + w (c1 - c0), r(w) = r0 + w (r1 - r0): the largest w with
      // |p - c(w)| = r(w) and r(w) >= 0, from a w^2 - 2 b w + c = 0.
      const Point pd = p - p0_;
      const double b = dot(pd, d_) + r0_ * dr_;
      const double c = dot(pd, pd) - r0_ * r0_;
      if (a_ == 0) {
        if (b == 0) return false;
        t = c / (2 * b);
        return r0_ + t * dr_ >= 0;
      }
      const double disc = b * b - a_ * c;
      if (disc < 0) return false;
      const double sq = std::sqrt(disc);
      const double big = (a_ > 0 ? b + sq : b - sq) / a_, small = (a_ > 0 ? b - sq : b + sq) / a_;
      if (r0_ + big * dr_ >= 0) {
        t = big;
        return true;
      }
      t = small;
      return r0_ + small * dr_ >= 0;
    }
    default: return false;
  }
}

template <class T>
void Shader<T>::shade(int y, int x0, int n, T* out) {
  if (constant_) {
    for (int i = 0; i < n; ++i) std::memcpy(out + 4 * i, color_, sizeof color_);
    return;
  }
  if (kind_ == Paint::Kind::Pattern) {
    shade_pattern(y, x0, n, out);
  } else {
    shade_gradient(y, x0, n, out);
  }
}

template <class T>
void Shader<T>::shade_gradient(int y, int x0, int n, T* out) {
  using CM = ChannelMath<T>;
  // Paint-space point of the first pixel centre and its step along the row.
  const Point start = to_paint_.apply({x0 + 0.5, y + 0.5});
  const Point step{to_paint_.a, to_paint_.b};
  if (ts_.size() < static_cast<std::size_t>(n)) ts_.resize(static_cast<std::size_t>(n));
  double* ts = ts_.data();
  if (kind_ == Paint::Kind::Linear) {
    const double t0 = dot(start - p0_, d_), dt = dot(step, d_);
    for (int i = 0; i < n; ++i) ts[i] = t0 + dt * i;
  } else {
    for (int i = 0; i < n; ++i) {
      double t;
      ts[i] = gradient_t(start + step * i, t) ? t : NAN;
    }
  }
  if (sizeof(T) == 1 && !dither_) {
    auto* px = reinterpret_cast<std::uint32_t*>(static_cast<void*>(out));
    const double scale = kLutSize - 1;
    for (int i = 0; i < n; ++i) {
      const double t = ts[i];
      if (t != t) {  // NaN: outside a radial gradient's cone
        px[i] = 0;
        continue;
      }
      px[i] = lut_[static_cast<std::size_t>(extend_t(t) * scale + 0.5)];
    }
    return;
  }
  const float m = static_cast<float>(CM::M);
  for (int i = 0; i < n; ++i, out += 4) {
    const double t = ts[i];
    if (t != t) {
      std::memset(out, 0, 4 * sizeof(T));
      continue;
    }
    float c[4];
    color_at(extend_t(t), c);
    const float bias = dither_ ? (kBayer8[y & 7][(x0 + i) & 7] + 0.5f) / 64.f : 0.5f;
    std::uint32_t q[4];
    for (int ch = 0; ch < 4; ++ch) q[ch] = std::min<std::uint32_t>(CM::M, static_cast<std::uint32_t>(c[ch] * m + bias));
    for (int ch = 0; ch < 3; ++ch) out[ch] = static_cast<T>(std::min(q[ch], q[3]));
    out[3] = static_cast<T>(q[3]);
  }
}

namespace {

// Texel index along one axis of `size` texels under an extend mode; -1: transparent (None outside the tile).
inline int texel_index(int i, int size, Extend extend) {
  switch (extend) {
    case Extend::None: return i >= 0 && i < size ? i : -1;
    case Extend::Pad: return i < 0 ? 0 : (i >= size ? size - 1 : i);
    case Extend::Repeat: {
      const int m = i % size;
      return m < 0 ? m + size : m;
    }
    case Extend::Reflect: {
      const int period = 2 * size;
      int m = i % period;
      if (m < 0) m += period;
      return m < size ? m : period - 1 - m;
    }
  }
  return -1;
}

// floor(v) as an int, v clamped far outside any image first (huge coordinates wrap or pad somewhere sensible).
inline int floor_index(double v) {
  constexpr double kFar = 1 << 30;
  v = v > -kFar ? (v < kFar ? v : kFar) : -kFar;
  return static_cast<int>(std::floor(v));
}

// Catmull-Rom weights (B = 0, C = 1/2) of the four texels around a sample at fraction f in [0, 1).
inline void catmull_rom_weights(float f, float* w) {
  const float f2 = f * f, f3 = f2 * f;
  w[0] = -0.5f * f3 + f2 - 0.5f * f;
  w[1] = 1.5f * f3 - 2.5f * f2 + 1;
  w[2] = -1.5f * f3 + 2 * f2 + 0.5f * f;
  w[3] = 0.5f * f3 - 0.5f * f2;
}

// Samples a tile of S channels into premultiplied T pixels.
template <class T, class S>
void sample_pattern(const BasicImage<S>& tile, Extend ex, Extend ey, ImageFilter filter, float opacity, Point start,
                    Point step, int n, T* out) {
  constexpr float kIn = 1.f / static_cast<float>(BasicImage<S>::kMax);
  constexpr float kOut = static_cast<float>(BasicImage<T>::kMax);
  const int w = tile.width, h = tile.height;
  auto texel = [&](int i, int j, float weight, float* acc) {
    const int x = texel_index(i, w, ex), y = texel_index(j, h, ey);
    if (x < 0 || y < 0) return;
    const S* p = tile.pixel(x, y);
    for (int c = 0; c < 4; ++c) acc[c] += weight * static_cast<float>(p[c]);
  };
  for (int k = 0; k < n; ++k, out += 4) {
    const Point p = start + step * k;
    float acc[4] = {0, 0, 0, 0};
    if (filter == ImageFilter::Nearest) {
      texel(floor_index(p.x), floor_index(p.y), 1.f, acc);
    } else {
      // Texel centres are at i + 0.5.
      const double u = p.x - 0.5, v = p.y - 0.5;
      const int i0 = floor_index(u), j0 = floor_index(v);
      const float fx = static_cast<float>(u - i0), fy = static_cast<float>(v - j0);
      if (filter == ImageFilter::Bilinear) {
        texel(i0, j0, (1 - fx) * (1 - fy), acc);
        texel(i0 + 1, j0, fx * (1 - fy), acc);
        texel(i0, j0 + 1, (1 - fx) * fy, acc);
        texel(i0 + 1, j0 + 1, fx * fy, acc);
      } else {
        float wx[4], wy[4];
        catmull_rom_weights(fx, wx);
        catmull_rom_weights(fy, wy);
        for (int j = 0; j < 4; ++j) {
          for (int i = 0; i < 4; ++i) texel(i0 - 1 + i, j0 - 1 + j, wx[i] * wy[j], acc);
        }
      }
    }
    // Clamped to a valid premultiplied colour (cubic overshoots), then opacity, then the target's range.
    const float one = static_cast<float>(BasicImage<S>::kMax);
    const float a = acc[3] > 0 ? (acc[3] < one ? acc[3] : one) : 0;
    const float scale = kIn * kOut * opacity;
    const auto qa = static_cast<std::uint32_t>(a * scale + 0.5f);
    out[3] = static_cast<T>(qa);
    for (int c = 0; c < 3; ++c) {
      const float v = (acc[c] > 0 ? (acc[c] < a ? acc[c] : a) : 0) * scale;
      const auto q = static_cast<std::uint32_t>(v + 0.5f);
      out[c] = static_cast<T>(q < qa ? q : qa);
    }
  }
}

// One axis of a fixed-point sample position (16 fractional bits) that walks along a row. Under repeat and reflect
// the position is kept wrapped into one period, by a subtraction per step rather than a division per texel.
struct FixedAxis {
  std::int64_t pos = 0, step = 0, period = 0;  // period 0: pad or none (no wrapping)
  int size = 0;
  Extend extend = Extend::Pad;

  void wrap() {
    if (period == 0) return;
    if (pos >= period || pos < 0) {
      pos %= period;
      if (pos < 0) pos += period;
    }
  }
  void advance() {
    pos += step;
    if (period != 0) {
      if (pos >= period) pos -= period;
      if (pos < 0) pos += period;
      if (pos >= period || pos < 0) wrap();  // steps longer than a period (strong minification)
    }
  }
  /// Texel indices of the two samples around the position (-1: transparent), and the weight of the second.
  template <Extend E>
  void texels(int& i0, int& i1, std::uint32_t& f) const {
    const int i = static_cast<int>(pos >> 16);
    f = static_cast<std::uint32_t>((pos & 0xFFFF) >> 4);
    if constexpr (E == Extend::Repeat) {
      i0 = i;
      i1 = i + 1 == size ? 0 : i + 1;
    } else if constexpr (E == Extend::Reflect) {
      const int j = i + 1 == 2 * size ? 0 : i + 1;
      i0 = i < size ? i : 2 * size - 1 - i;
      i1 = j < size ? j : 2 * size - 1 - j;
    } else if constexpr (E == Extend::Pad) {
      i0 = i < 0 ? 0 : (i >= size ? size - 1 : i);
      i1 = i + 1 < 0 ? 0 : (i + 1 >= size ? size - 1 : i + 1);
    } else {
      i0 = i >= 0 && i < size ? i : -1;
      i1 = i + 1 >= 0 && i + 1 < size ? i + 1 : -1;
    }
  }
};

// The common case in fixed point: an 8-bit tile onto an 8-bit target, bilinear. Positions with 16 fractional bits,
// recomputed exactly from doubles every 64 pixels (so the rounded step never drifts); weights with 12 bits: the
// horizontal lerp of two texels is at most 255 x 4096, the vertical one at most 255 x 4096^2 + 2^23 < 2^32, rounded
// once. The weights' rounding moves a sample by at most 1/8192 of a texel (a 16th of a level on the sharpest edge).
// Two passes per 64 pixels: the position walk gathers the four texels and the weights of each pixel (scalar: wrapping
// and the loads depend on the position), then bilinear8_run does the arithmetic for all of them (vectorised).
template <Extend EX, Extend EY>
void sample_bilinear8(const Image& tile, FixedAxis ax, FixedAxis ay, std::uint32_t opacity, Point start, Point step,
                      int n, std::uint32_t* dst) {
  constexpr double kOne = 65536.0, kFar = 1 << 30;
  auto fixed = [&](double v) {
    v = v > -kFar ? (v < kFar ? v : kFar) : -kFar;
    return static_cast<std::int64_t>(std::floor(v * kOne + 0.5));
  };
  constexpr int kChunk = 64;
  std::uint32_t ta[kChunk], tb[kChunk], tc[kChunk], td[kChunk], wx[kChunk], wy[kChunk];
  const std::size_t stride = static_cast<std::size_t>(tile.width) * 4;
  const std::uint8_t* pixels = tile.data.data();
  auto texel = [&](int x, int y) {
    std::uint32_t v = 0;
    // Only extend None marks texels outside the tile (-1): the other modes always land inside.
    const bool inside = (EX != Extend::None || x >= 0) && (EY != Extend::None || y >= 0);
    if (inside) std::memcpy(&v, pixels + stride * static_cast<std::size_t>(y) + 4 * static_cast<std::size_t>(x), 4);
    return v;
  };
  for (int k0 = 0; k0 < n; k0 += kChunk) {
    const int m = std::min(kChunk, n - k0);
    ax.pos = fixed(start.x - 0.5 + step.x * k0);
    ay.pos = fixed(start.y - 0.5 + step.y * k0);
    ax.wrap();
    ay.wrap();
    for (int i = 0; i < m; ++i) {
      int x0 = -1, x1 = -1, y0 = -1, y1 = -1;
      ax.texels<EX>(x0, x1, wx[i]);
      ay.texels<EY>(y0, y1, wy[i]);
      ta[i] = texel(x0, y0);
      tb[i] = texel(x1, y0);
      tc[i] = texel(x0, y1);
      td[i] = texel(x1, y1);
      ax.advance();
      ay.advance();
    }
    bilinear8_run(ta, tb, tc, td, wx, wy, opacity, m, dst + k0);
  }
}

template <Extend EX>
void sample_bilinear8_y(Extend ey, const Image& tile, const FixedAxis& ax, const FixedAxis& ay, std::uint32_t o,
                        Point start, Point step, int n, std::uint32_t* dst) {
  switch (ey) {
    case Extend::Repeat: sample_bilinear8<EX, Extend::Repeat>(tile, ax, ay, o, start, step, n, dst); return;
    case Extend::Reflect: sample_bilinear8<EX, Extend::Reflect>(tile, ax, ay, o, start, step, n, dst); return;
    case Extend::Pad: sample_bilinear8<EX, Extend::Pad>(tile, ax, ay, o, start, step, n, dst); return;
    case Extend::None: sample_bilinear8<EX, Extend::None>(tile, ax, ay, o, start, step, n, dst); return;
  }
}

void sample_bilinear8(const Image& tile, Extend ex, Extend ey, float opacity, Point start, Point step, int n,
                      std::uint8_t* out) {
  constexpr double kOne = 65536.0, kFar = 1 << 30;
  auto fixed = [&](double v) {
    v = v > -kFar ? (v < kFar ? v : kFar) : -kFar;
    return static_cast<std::int64_t>(std::floor(v * kOne + 0.5));
  };
  FixedAxis ax, ay;
  ax.size = tile.width, ay.size = tile.height;
  ax.extend = ex, ay.extend = ey;
  auto period = [](Extend e, int size) -> std::int64_t {
    return e == Extend::Repeat ? std::int64_t{size} << 16 : e == Extend::Reflect ? std::int64_t{size} << 17 : 0;
  };
  ax.period = period(ex, tile.width), ay.period = period(ey, tile.height);
  ax.step = fixed(step.x), ay.step = fixed(step.y);
  const auto o = static_cast<std::uint32_t>(opacity * 65536.f + 0.5f);  // 16.16 fixed opacity
  auto* dst = reinterpret_cast<std::uint32_t*>(static_cast<void*>(out));
  switch (ex) {
    case Extend::Repeat: sample_bilinear8_y<Extend::Repeat>(ey, tile, ax, ay, o, start, step, n, dst); return;
    case Extend::Reflect: sample_bilinear8_y<Extend::Reflect>(ey, tile, ax, ay, o, start, step, n, dst); return;
    case Extend::Pad: sample_bilinear8_y<Extend::Pad>(ey, tile, ax, ay, o, start, step, n, dst); return;
    case Extend::None: sample_bilinear8_y<Extend::None>(ey, tile, ax, ay, o, start, step, n, dst); return;
  }
}

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void bilinear8_run(const std::uint32_t* a, const std::uint32_t* b, const std::uint32_t* c, const std::uint32_t* d,
                   const std::uint32_t* fx, const std::uint32_t* fy, std::uint32_t opacity, int n, std::uint32_t* dst) {
  for (int i = 0; i < n; ++i) dst[i] = bilinear8_pixel(a[i], b[i], c[i], d[i], fx[i], fy[i], opacity);
}

template <class T>
void Shader<T>::shade_pattern(int y, int x0, int n, T* out) {
  const Point start = to_paint_.apply({x0 + 0.5, y + 0.5});
  const Point step{to_paint_.a, to_paint_.b};
  const Paint& p = *pattern_;
  if constexpr (sizeof(T) == 1) {
    if (p.image8() && p.filter() == ImageFilter::Bilinear) {
      sample_bilinear8(*p.image8(), p.extend_x(), p.extend_y(), p.opacity(), start, step, n, out);
      return;
    }
  }
  if (p.image8()) {
    sample_pattern(*p.image8(), p.extend_x(), p.extend_y(), p.filter(), p.opacity(), start, step, n, out);
  } else {
    sample_pattern(*p.image16(), p.extend_x(), p.extend_y(), p.filter(), p.opacity(), start, step, n, out);
  }
}

template class Shader<std::uint8_t>;
template class Shader<std::uint16_t>;

}  // namespace vraster::detail
