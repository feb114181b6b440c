// Private: the per-pixel composite operators and the run loop shared by blend_row and Compositor.
//
// Rounding (docs/design.md, "Paint and compositing"): with M = 255 (8 bits) or 65535 (16 bits),
//   1. coverage x global alpha and the clip are quantized: k = round(M * clamp(cov, 0, 1)), c likewise;
//   2. Porter-Duff operators and lighter: the formula d + (Op(s k / M, d) - d) c / M evaluated exactly on these
//      integers (one integer expression over M^3) and rounded once to nearest;
//   3. blend modes: the same formula in float (8 bits) or double (16 bits), rounded once to nearest (within
//      0.51 of a level of the exact value).
// Division by an odd M (or its powers) never meets a tie, so "rounded to nearest" needs no tie rule.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

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

/// Porter-Duff operators and lighter on one pixel at full coverage and clip: r = round(s Fa + d Fb), exact.
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

/// Porter-Duff operators and lighter with quantized coverage k and clip c (both in [0, M]), rounded once:
/// the source scaled by k / M is s k / M, so every term of s Fa + d Fb is an integer over M^2, and the clip lerp
/// d + (r - d) c / M an integer over M^3. The sums fit: M^4 < 2^64 for M = 65535, M^3 < 2^32 for M = 255 (the
/// 8-bit clip lerp uses 64 bits).
template <class T, CompositeOp Op>
inline void porter_duff_pixel(const T* s, const T* d, T* r, std::uint64_t k, std::uint64_t c) {
  constexpr std::uint64_t M = ChannelMath<T>::M, M2 = M * M, M3 = M2 * M;
  const std::uint64_t as_k = std::uint64_t{s[3]} * k;  // source alpha after coverage, over M^2
  std::uint64_t fa, fb2;                               // fa over M, fb2 over M^2
  porter_duff_factors<Op, std::uint64_t>(M, s[3], d[3], fa, fb2);
  switch (Op) {  // factors that depend on the source alpha see it scaled by coverage
    case CompositeOp::SourceOver: case CompositeOp::DestinationOut: case CompositeOp::SourceAtop:
    case CompositeOp::Xor: fb2 = M2 - as_k; break;
    case CompositeOp::DestinationIn: case CompositeOp::DestinationAtop: fb2 = as_k; break;
    default: fb2 *= M; break;
  }
  for (int ch = 0; ch < 4; ++ch) {
    std::uint64_t n = std::uint64_t{s[ch]} * k * fa + std::uint64_t{d[ch]} * fb2;  // over M^2
    if (n > M3) n = M3;                                                           // lighter saturates
    const std::uint64_t v = c == M ? (n + M2 / 2) / M2 : (std::uint64_t{d[ch]} * (M - c) * M2 + n * c + M3 / 2) / M3;
    r[ch] = static_cast<T>(v);
  }
}

/// Blend modes on one pixel: co = cs (1 - ab) + cb (1 - as) + as ab B(Cb, Cs), ao = as + ab - as ab, with the
/// source scaled by k / M and the result lerped by c / M, in float (8 bits) or double (16 bits), rounded once.
template <class T, CompositeOp Op>
inline void blend_mode_pixel(const T* s, const T* d, T* r, std::uint64_t k, std::uint64_t c) {
  using CM = ChannelMath<T>;
  using W = typename CM::Wide;
  using R = typename CM::Real;
  constexpr R inv = R(1) / R(CM::M);
  const R ks = R(k) * inv, kc = R(c) * inv;
  R sv[4], dv[4];
  for (int ch = 0; ch < 4; ++ch) {
    sv[ch] = R(s[ch]) * inv * ks;
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
  R out[4];
  for (int ch = 0; ch < 3; ++ch) out[ch] = sv[ch] * (1 - ab) + dv[ch] * (1 - as) + as * ab * b[ch];
  out[3] = as + ab - as * ab;
  W q[4];
  for (int ch = 0; ch < 4; ++ch) {
    const R v = (dv[ch] + (out[ch] - dv[ch]) * kc) * R(CM::M) + R(0.5);
    q[ch] = v > 0 ? std::min<W>(CM::M, static_cast<W>(v)) : 0;
  }
  for (int ch = 0; ch < 3; ++ch) r[ch] = static_cast<T>(q[ch] < q[3] ? q[ch] : q[3]);
  r[3] = static_cast<T>(q[3]);
}

/// Composites n pixels. The source advances by `src_step` channels a pixel (0: one colour for the whole run).
/// coverage == nullptr: every pixel has coverage `scale`; else coverage[i] * scale. clip may be null (all 1).
template <class T, CompositeOp Op>
void composite_run(T* dst, const T* src, int src_step, const float* coverage, float scale, const float* clip, int n) {
  using CM = ChannelMath<T>;
  using W = typename CM::Wide;
  constexpr W M = CM::M;
  constexpr bool bounded = Op != CompositeOp::Copy && Op != CompositeOp::Clear && Op != CompositeOp::SourceIn &&
                           Op != CompositeOp::SourceOut && Op != CompositeOp::DestinationIn &&
                           Op != CompositeOp::DestinationAtop;
  const W k_const = CM::quantize(scale);
  for (int i = 0; i < n; ++i, dst += 4, src += src_step) {
    const W k = coverage ? CM::quantize(coverage[i] * scale) : k_const;
    const W c = clip ? CM::quantize(clip[i]) : M;
    if (c == 0) continue;
    if (bounded && (k == 0 || src[3] == 0)) continue;
    T r[4];
    if constexpr (is_blend_mode(Op)) {
      blend_mode_pixel<T, Op>(src, dst, r, k, c);
    } else if (k == M && c == M) {
      porter_duff_pixel<T, Op>(src, dst, r);
    } else {
      porter_duff_pixel<T, Op>(src, dst, r, k, c);
    }
    for (int ch = 0; ch < 4; ++ch) dst[ch] = r[ch];
  }
}

template <class T>
using CompositeRunFn = void (*)(T*, const T*, int, const float*, float, const float*, int);

/// The run loop for `op`.
template <class T>
CompositeRunFn<T> composite_run_for(CompositeOp op);

}  // namespace vraster::detail
