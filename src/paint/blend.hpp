// Private: the per-pixel composite operators and the run loop shared by blend_row and Compositor.
//
// Rounding (docs/design.md, "Paint and compositing"): with M = 255 (8 bits) or 65535 (16 bits),
// Three image operations, each rounded to nearest once (the HTML canvas model: the shape is an image, at the
// target's depth, whose alpha is its coverage; it is composited with the operator; the clip then lerps):
//   1. coverage x global alpha is quantized: k = round(M * clamp(cov, 0, 1)); the clip c comes as levels in [0, M]
//      (the canvas stores its clip mask quantized so: round(M * clip coverage));
//      the source is scaled: s' = round(s k / M) per channel;
//   2. r = round(Op(s', d)): Porter-Duff operators, lighter and the polynomial blend modes (multiply, screen,
//      darken, lighten, difference, exclusion) as one integer expression, exact; the other blend modes in float
//      (8 bits) or double (16 bits), within 0.51 of a level;
//   3. out = round((d (M - c) + r c) / M).
// Division by an odd M never meets a tie, so "rounded to nearest" needs no tie rule.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "raster/cpu.hpp"
#include "vraster/composite.hpp"

namespace vraster::detail {

template <class T>
struct ChannelMath {
  static constexpr std::uint32_t M = sizeof(T) == 1 ? 255u : 65535u;
  using Wide = std::conditional_t<sizeof(T) == 1, std::uint32_t, std::uint64_t>;
  using Real = std::conditional_t<sizeof(T) == 1, float, double>;

  /// round(x / M) for x >= 0.
  static Wide div(Wide x) { return (x + M / 2) / M; }
  /// round(M * clamp(c, 0, 1)); NaN gives 0.
  static Wide quantize(float c) {
    if (!(c > 0)) return 0;
    if (c >= 1) return M;
    return static_cast<Wide>(static_cast<Real>(c) * static_cast<Real>(M) + static_cast<Real>(0.5));
  }
};

/// Porter-Duff factors (Fa, Fb) scaled to [0, M] for source alpha `as` and destination alpha `ab`.
template <CompositeOp Op, class Wide>
inline void porter_duff_factors(Wide M, Wide as, Wide ab, Wide& fa, Wide& fb) {
  switch (Op) {
    case CompositeOp::Clear: fa = 0; fb = 0; break;
    case CompositeOp::Copy: fa = M; fb = 0; break;
    case CompositeOp::SourceOver: fa = M; fb = M - as; break;
    case CompositeOp::DestinationOver: fa = M - ab; fb = M; break;
    case CompositeOp::SourceIn: fa = ab; fb = 0; break;
    case CompositeOp::DestinationIn: fa = 0; fb = as; break;
    case CompositeOp::SourceOut: fa = M - ab; fb = 0; break;
    case CompositeOp::DestinationOut: fa = 0; fb = M - as; break;
    case CompositeOp::SourceAtop: fa = ab; fb = M - as; break;
    case CompositeOp::DestinationAtop: fa = M - ab; fb = as; break;
    case CompositeOp::Xor: fa = M - ab; fb = M - as; break;
    default: fa = M; fb = M; break;  // Lighter (plus); clamped by the caller
  }
}

constexpr bool is_blend_mode(CompositeOp op) { return op >= CompositeOp::Multiply; }
constexpr bool is_separable(CompositeOp op) { return op >= CompositeOp::Multiply && op < CompositeOp::Hue; }

/// W3C separable blend function B(cb, cs) on straight colour channels in [0, 1].
template <CompositeOp Op, class R>
inline R blend_separable(R cb, R cs) {
  switch (Op) {
    case CompositeOp::Multiply: return cb * cs;
    case CompositeOp::Screen: return cb + cs - cb * cs;
    case CompositeOp::Overlay: {  // hard-light with the layers swapped
      const R c2 = cb + cb;
      return cb <= R(0.5) ? cs * c2 : cs + (c2 - 1) - cs * (c2 - 1);
    }
    case CompositeOp::Darken: return std::min(cb, cs);
    case CompositeOp::Lighten: return std::max(cb, cs);
    case CompositeOp::ColorDodge:
      if (cb <= 0) return 0;
      if (cs >= 1) return 1;
      return std::min(R(1), cb / (1 - cs));
    case CompositeOp::ColorBurn:
      if (cb >= 1) return 1;
      if (cs <= 0) return 0;
      return 1 - std::min(R(1), (1 - cb) / cs);
    case CompositeOp::HardLight: {
      const R s2 = cs + cs;
      return cs <= R(0.5) ? cb * s2 : cb + (s2 - 1) - cb * (s2 - 1);
    }
    case CompositeOp::SoftLight: {
      if (cs <= R(0.5)) return cb - (1 - 2 * cs) * cb * (1 - cb);
      const R d = cb <= R(0.25) ? ((16 * cb - 12) * cb + 4) * cb : std::sqrt(cb);
      return cb + (2 * cs - 1) * (d - cb);
    }
    case CompositeOp::Difference: return std::abs(cb - cs);
    case CompositeOp::Exclusion: return cb + cs - 2 * cb * cs;
    default: return cs;
  }
}

// The non-separable helpers of W3C Compositing Level 1 (section 10.2), on straight RGB.
template <class R>
inline R lum(const R* c) { return R(0.3) * c[0] + R(0.59) * c[1] + R(0.11) * c[2]; }

template <class R>
inline void clip_color(R* c) {
  const R l = lum(c);
  const R n = std::min({c[0], c[1], c[2]});
  const R x = std::max({c[0], c[1], c[2]});
  if (n < 0) {
    const R den = l - n;
    for (int i = 0; i < 3; ++i) c[i] = den > 0 ? l + (c[i] - l) * l / den : l;
  }
  if (x > 1) {
    const R den = x - l;
    for (int i = 0; i < 3; ++i) c[i] = den > 0 ? l + (c[i] - l) * (1 - l) / den : l;
  }
}

template <class R>
inline void set_lum(R* c, R l) {
  const R d = l - lum(c);
  for (int i = 0; i < 3; ++i) c[i] += d;
  clip_color(c);
}

template <class R>
inline R sat(const R* c) { return std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]}); }

template <class R>
inline void set_sat(R* c, R s) {
  // Indices of the largest, middle and smallest channel.
  int mx = 0, mn = 0;
  for (int i = 1; i < 3; ++i) {
    if (c[i] > c[mx]) mx = i;
    if (c[i] < c[mn]) mn = i;
  }
  if (mx == mn) {  // all equal
    c[0] = c[1] = c[2] = 0;
    return;
  }
  const int md = 3 - mx - mn;
  const R range = c[mx] - c[mn];
  c[md] = (c[md] - c[mn]) * s / range;
  c[mx] = s;
  c[mn] = 0;
}

/// W3C non-separable blend B(cb, cs) on straight RGB; writes the result into `out`.
template <CompositeOp Op, class R>
inline void blend_non_separable(const R* cb, const R* cs, R* out) {
  for (int i = 0; i < 3; ++i) out[i] = (Op == CompositeOp::Hue || Op == CompositeOp::Color) ? cs[i] : cb[i];
  switch (Op) {
    case CompositeOp::Hue:
      set_sat(out, sat(cb));
      set_lum(out, lum(cb));
      break;
    case CompositeOp::Saturation:
      set_sat(out, sat(cs));
      set_lum(out, lum(cb));
      break;
    case CompositeOp::Color: set_lum(out, lum(cb)); break;
    default: set_lum(out, lum(cs)); break;  // Luminosity
  }
}

/// Porter-Duff operators and lighter on one pixel: r = round(s Fa + d Fb), exact.
template <class T, CompositeOp Op>
inline void porter_duff_pixel(const T* s, const T* d, T* r) {
  using CM = ChannelMath<T>;
  using W = typename CM::Wide;
  constexpr W M = CM::M;
  W fa, fb;
  porter_duff_factors<Op, W>(M, s[3], d[3], fa, fb);
  for (int c = 0; c < 4; ++c) {
    const W v = CM::div(W{s[c]} * fa + W{d[c]} * fb);
    r[c] = static_cast<T>(v < M ? v : M);
  }
}

/// Blend modes whose premultiplied form is a polynomial with min / max (multiply, screen, darken, lighten,
/// difference, exclusion): the W3C formula co = cs (1 - ab) + cb (1 - as) + as ab B(cb / ab, cs / as) rewritten on
/// premultiplied integers (e.g. darken: co = cs + cb - max(cs ab, cb as) / M), rounded once: exact.
constexpr bool is_integer_blend(CompositeOp op) {
  return op == CompositeOp::Multiply || op == CompositeOp::Screen || op == CompositeOp::Darken ||
         op == CompositeOp::Lighten || op == CompositeOp::Difference || op == CompositeOp::Exclusion;
}

template <class T, CompositeOp Op>
inline void integer_blend_pixel(const T* s, const T* d, T* r) {
  using CM = ChannelMath<T>;
  using S = std::int64_t;
  constexpr S M = CM::M;
  const S as = s[3], ab = d[3];
  const S ao = as + static_cast<S>(CM::div(static_cast<typename CM::Wide>(ab * (M - as))));
  r[3] = static_cast<T>(ao);
  for (int c = 0; c < 3; ++c) {
    const S cs = s[c], cb = d[c];
    S n;  // co * M
    switch (Op) {
      case CompositeOp::Multiply: n = cs * (M - ab) + cb * (M - as) + cs * cb; break;
      case CompositeOp::Screen: n = (cs + cb) * M - cs * cb; break;
      case CompositeOp::Darken: n = (cs + cb) * M - std::max(cs * ab, cb * as); break;
      case CompositeOp::Lighten: n = (cs + cb) * M - std::min(cs * ab, cb * as); break;
      case CompositeOp::Difference: n = (cs + cb) * M - 2 * std::min(cs * ab, cb * as); break;
      default: n = (cs + cb) * M - 2 * cs * cb; break;  // exclusion
    }
    const S v = n > 0 ? (n + M / 2) / M : 0;
    r[c] = static_cast<T>(v < ao ? v : ao);
  }
}

/// The other blend modes on one pixel, in float (8 bits) or double (16 bits), rounded once.
template <class T, CompositeOp Op>
inline void blend_mode_pixel(const T* s, const T* d, T* r) {
  using CM = ChannelMath<T>;
  using W = typename CM::Wide;
  using R = typename CM::Real;
  constexpr R inv = R(1) / R(CM::M);
  R sv[4], dv[4];
  for (int ch = 0; ch < 4; ++ch) {
    sv[ch] = R(s[ch]) * inv;
    dv[ch] = R(d[ch]) * inv;
  }
  const R as = sv[3], ab = dv[3];
  R cs[3], cb[3], b[3];
  for (int ch = 0; ch < 3; ++ch) {
    cs[ch] = s[3] ? std::min(R(1), R(s[ch]) / R(s[3])) : R(0);
    cb[ch] = d[3] ? std::min(R(1), R(d[ch]) / R(d[3])) : R(0);
  }
  if constexpr (is_separable(Op)) {
    for (int ch = 0; ch < 3; ++ch) b[ch] = blend_separable<Op, R>(cb[ch], cs[ch]);
  } else {
    blend_non_separable<Op, R>(cb, cs, b);
  }
  const W ao = std::min<W>(CM::M, W{s[3]} + CM::div(W{d[3]} * (CM::M - s[3])));
  r[3] = static_cast<T>(ao);
  for (int ch = 0; ch < 3; ++ch) {
    const R v = (sv[ch] * (1 - ab) + dv[ch] * (1 - as) + as * ab * b[ch]) * R(CM::M) + R(0.5);
    const W q = v > 0 ? static_cast<W>(v) : 0;
    r[ch] = static_cast<T>(q < ao ? q : ao);
  }
}

template <class T, CompositeOp Op>
inline void operator_pixel(const T* s, const T* d, T* r) {
  if constexpr (!is_blend_mode(Op)) {
    porter_duff_pixel<T, Op>(s, d, r);
  } else if constexpr (is_integer_blend(Op)) {
    integer_blend_pixel<T, Op>(s, d, r);
  } else {
    blend_mode_pixel<T, Op>(s, d, r);
  }
}

// ---- 8-bit source-over: one uint32 per pixel (R in the low byte), two channels per multiply ----

/// round(px * f / 255) per channel, exact for every px channel and f in [0, 255] (tested exhaustively).
inline std::uint32_t scale8(std::uint32_t px, std::uint32_t f) {
  std::uint32_t rb = (px & 0x00FF00FFu) * f + 0x00800080u;
  rb = ((rb + ((rb >> 8) & 0x00FF00FFu)) >> 8) & 0x00FF00FFu;
  std::uint32_t ag = ((px >> 8) & 0x00FF00FFu) * f + 0x00800080u;
  ag = ((ag + ((ag >> 8) & 0x00FF00FFu)) >> 8) & 0x00FF00FFu;
  return rb | (ag << 8);
}

/// round((d * (255 - c) + r * c) / 255) per channel: the clip lerp, exact (each lane sum is at most 255 * 255).
inline std::uint32_t lerp8(std::uint32_t d, std::uint32_t r, std::uint32_t c) {
  const std::uint32_t ic = 255u - c;
  std::uint32_t rb = (d & 0x00FF00FFu) * ic + (r & 0x00FF00FFu) * c + 0x00800080u;
  rb = ((rb + ((rb >> 8) & 0x00FF00FFu)) >> 8) & 0x00FF00FFu;
  std::uint32_t ag = ((d >> 8) & 0x00FF00FFu) * ic + ((r >> 8) & 0x00FF00FFu) * c + 0x00800080u;
  ag = ((ag + ((ag >> 8) & 0x00FF00FFu)) >> 8) & 0x00FF00FFu;
  return rb | (ag << 8);
}

/// s + round(d (255 - as) / 255): source-over, exact.
inline std::uint32_t over8(std::uint32_t s, std::uint32_t d) { return s + scale8(d, 255u - (s >> 24)); }

/// round(255 * clamp(v, 0, 1)), NaN -> 0, written so that it vectorises.
inline std::uint32_t quantize8(float v) {
  // Branch-free clamp (NaN fails v > 0 and becomes 0); the conversion of v * 255 + 0.5 in [0.5, 255.5] truncates.
  const float lo = __builtin_isgreater(v, 0.f) ? v : 0.f;
  const float hi = lo < 1.f ? lo : 1.f;
  return static_cast<std::uint32_t>(static_cast<std::int32_t>(hi * 255.f + 0.5f));
}

/// How many of n pixels from px come before the first 32-byte aligned one. A 32-byte access that straddles two
/// cache lines costs two, and rows from malloc start 16 bytes into a page: the vector loops below do these pixels
/// apart and then run aligned, which made full-frame stores and blends 1.3-1.5x faster.
inline int to_aligned32(const void* px, int n) {
  return std::min(n, static_cast<int>((32 - (reinterpret_cast<std::uintptr_t>(px) & 31)) & 31) / 4);
}

// The source-over loops (composite.cpp: compiled for AVX2 and for any x86-64, picked at load time).
/// n pixels set to one colour.
void store8(std::uint32_t* px, int n, std::uint32_t c);
/// One colour, one coverage for the whole run (portable loop; over8_constant picks).
void over8_constant_portable(std::uint32_t* px, int n, std::uint32_t s);
/// One colour c under per-pixel coverage: px[i] = over8(scale8(c, quantize8(coverage[i] * scale)), px[i]).
void over8_solid_portable(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c);
#ifdef VRASTER_HAVE_AVX2_KERNELS
// over8_avx2.cpp: the same two loops by hand in AVX2, the same bits.
void over8_constant_avx2(std::uint32_t* px, int n, std::uint32_t s);
void over8_solid_avx2(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c);
// over8_avx512.cpp: the same two loops sixteen pixels a step in AVX-512 BW, the same bits.
void over8_constant_avx512(std::uint32_t* px, int n, std::uint32_t s);
void over8_solid_avx512(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c);
#endif
/// The two loops every fill ends in: the AVX2 kernel where the processor has it, else the portable loop.
void over8_constant(std::uint32_t* px, int n, std::uint32_t s);
void over8_solid(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c);
/// The same choice made once, for callers that keep it (the solid compositor).
using Over8ConstantFn = void (*)(std::uint32_t* px, int n, std::uint32_t s);
using Over8SolidFn = void (*)(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c);
Over8ConstantFn over8_constant_for_cpu();
Over8SolidFn over8_solid_for_cpu();
/// A row of colours scaled by one coverage k.
void over8_row(std::uint32_t* px, const std::uint32_t* src, int n, std::uint32_t k);
/// Colours (src_step 0: one colour) scaled by per-pixel coverage x scale, optionally lerped by a clip.
void over8_masked(std::uint32_t* px, const std::uint32_t* src, int src_step, const float* coverage, float scale,
                  const std::uint8_t* clip, int n);

/// Composites n pixels. The source advances by `src_step` channels a pixel (0: one colour for the whole run).
/// coverage == nullptr: every pixel has coverage `scale`; else coverage[i] * scale. clip: levels in [0, M], may be
/// null (all M).
template <class T, CompositeOp Op>
void composite_run(T* dst, const T* src, int src_step, const float* coverage, float scale, const T* clip, int n) {
  using CM = ChannelMath<T>;
  using W = typename CM::Wide;
  constexpr W M = CM::M;
  if constexpr (sizeof(T) == 1 && Op == CompositeOp::SourceOver) {
    auto* px = reinterpret_cast<std::uint32_t*>(static_cast<void*>(dst));
    const auto* s = reinterpret_cast<const std::uint32_t*>(static_cast<const void*>(src));
    if (coverage == nullptr && clip == nullptr) {
      const std::uint32_t k = quantize8(scale);
      if (k == 0) return;
      if (src_step == 0) {
        const std::uint32_t c = k == 255 ? s[0] : scale8(s[0], k);
        if (c >> 24 == 255) {
          store8(px, n, c);  // opaque: a store
        } else if (c != 0) {
          over8_constant(px, n, c);
        }
      } else {
        const int h = to_aligned32(px, n);
        over8_row(px, s, h, k);
        over8_row(px + h, s + h, n - h, k);
      }
    } else if (src_step == 0 && clip == nullptr) {
      over8_solid(px, n, coverage, scale, s[0]);
    } else {
      const int h = to_aligned32(px, n), step = src_step / 4;
      over8_masked(px, s, step, coverage, scale, clip, h);
      over8_masked(px + h, s + step * h, step, coverage ? coverage + h : nullptr, scale, clip ? clip + h : nullptr,
                   n - h);
    }
    return;
  }
  constexpr bool bounded = Op != CompositeOp::Copy && Op != CompositeOp::Clear && Op != CompositeOp::SourceIn &&
                           Op != CompositeOp::SourceOut && Op != CompositeOp::DestinationIn &&
                           Op != CompositeOp::DestinationAtop;
  const W k_const = CM::quantize(scale);
  for (int i = 0; i < n; ++i, dst += 4, src += src_step) {
    const W k = coverage ? CM::quantize(coverage[i] * scale) : k_const;
    const W c = clip ? W{clip[i]} : M;
    if (c == 0) continue;
    if (bounded && (k == 0 || src[3] == 0)) continue;
    T s[4], r[4];
    if (k == M) {
      for (int ch = 0; ch < 4; ++ch) s[ch] = src[ch];
    } else {
      for (int ch = 0; ch < 4; ++ch) s[ch] = static_cast<T>(CM::div(W{src[ch]} * k));
    }
    operator_pixel<T, Op>(s, dst, r);
    if (c == M) {
      for (int ch = 0; ch < 4; ++ch) dst[ch] = r[ch];
    } else {
      for (int ch = 0; ch < 4; ++ch) dst[ch] = static_cast<T>(CM::div(W{dst[ch]} * (M - c) + W{r[ch]} * c));
    }
  }
}

template <class T>
using CompositeRunFn = void (*)(T*, const T*, int, const float*, float, const T*, int);

/// The run loop for `op`.
template <class T>
CompositeRunFn<T> composite_run_for(CompositeOp op);

// CoverageSink::expect for sinks that write `view`: small fills land anywhere on a large image, whose rows are
// mostly out of the nearer caches, so the fill's pixels are requested while the rasterizer works out the coverage
// instead of being waited for row by row as they are blended. Up to kExpectRows rows of kExpectLines cache lines
// (a small fill's box; a large fill's rows come in as it goes). The box is clipped to the view.
template <class T>
void prefetch_pixels(const ImageView<T>& view, int y0, int y1, int x0, int x1) {
  constexpr int kExpectRows = 64, kExpectLines = 4;
  constexpr int kPixelsPerLine = 64 / (4 * static_cast<int>(sizeof(T)));
  y0 = std::max(y0, view.y0);
  y1 = std::min(y1, view.y0 + view.height);
  x0 = std::max(x0, view.x0);
  x1 = std::min(x1, view.x0 + view.width);
  if (y1 <= y0 || x1 <= x0) return;
  y1 = std::min(y1, y0 + kExpectRows);  // y0 < y1 inside the view: no overflow
  const int last = std::min(x1 - 1, x0 + kExpectLines * kPixelsPerLine - 1);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x <= last; x += kPixelsPerLine) __builtin_prefetch(view.pixel(x, y), 1);
    __builtin_prefetch(view.pixel(last, y), 1);  // the line of the last pixel, which the steps may skip
  }
}

}  // namespace vraster::detail
