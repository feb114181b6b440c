// The AVX2 source-over steps on eight 8-bit pixels, lane by lane blend.hpp's arithmetic (scale8, over8,
// quantize8): shared by the AVX2 loops (over8_avx2.cpp) and the AVX-512 ones (over8_avx512.cpp), whose short runs
// take one eight-pixel step. Only for files that define the kernels' functions: everything here is inline.
#pragma once

#include <cstdint>

#include "raster/cpu.hpp"

#ifdef VRASTER_HAVE_AVX2_KERNELS

namespace vraster::detail::avx2 {

#define VRASTER_AVX2 [[gnu::target("avx2"), gnu::always_inline]] inline

// round(a * f / 255) per 16-bit lane for a, f in [0, 255]: t = a f + 128, then (t + (t >> 8)) >> 8 (scale8's form),
// taken as the high half of t * 257 (the same integer for every t < 2^16: t + t / 256 and t + floor(t / 256) have
// the same floor after dividing by 256), one multiply instead of two shifts and an add.
VRASTER_AVX2 __m256i scale16(__m256i a, __m256i f) {
  const __m256i t = _mm256_add_epi16(_mm256_mullo_epi16(a, f), _mm256_set1_epi16(128));
  return _mm256_mulhi_epu16(t, _mm256_set1_epi16(257));
}

// 255 - alpha of every pixel, spread over its four lanes (alpha is lane 3 of each pixel).
VRASTER_AVX2 __m256i inverse_alpha16(__m256i s) {
  const __m256i a = _mm256_shufflehi_epi16(_mm256_shufflelo_epi16(s, 0xFF), 0xFF);
  return _mm256_sub_epi16(_mm256_set1_epi16(255), a);
}

// Lanes i < n set: the mask of a partial step.
VRASTER_AVX2 __m256i first_lanes(int n) {
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}

// Stores the first n (1 to 8) pixels of v at q with plain stores of four, two and one pixel. AVX2's masked store
// (vpmaskmovd) takes about 25 cycles on AMD Zen 3, more than the rest of an eight-pixel step, and the short runs the
// rasterizer hands over (thin shapes' rows of 1 to 4 pixels) are nearly all partial steps: 10 ns a call against
// 4 ns this way.
VRASTER_AVX2 void store_first(std::uint32_t* q, __m256i v, int n) {
  if (n == 8) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(q), v);
    return;
  }
  __m128i part = _mm256_castsi256_si128(v);
  if (n & 4) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(q), part);
    part = _mm256_extracti128_si256(v, 1);
    q += 4;
  }
  if (n & 2) {
    _mm_storel_epi64(reinterpret_cast<__m128i*>(q), part);
    part = _mm_srli_si128(part, 8);
    q += 2;
  }
  if (n & 1) _mm_storeu_si32(q, part);
}

// Eight pixels d under the constant source s (packed) whose inverse alpha is inv (16-bit lanes): s + scale8(d, inv).
// The sum is a 32-bit addition per pixel, as the scalar over8 adds (no carry ever crosses a premultiplied channel).
VRASTER_AVX2 __m256i over_constant8(__m256i d, __m256i s, __m256i inv) {
  const __m256i zero = _mm256_setzero_si256();
  const __m256i lo = scale16(_mm256_unpacklo_epi8(d, zero), inv);
  const __m256i hi = scale16(_mm256_unpackhi_epi8(d, zero), inv);
  return _mm256_add_epi32(s, _mm256_packus_epi16(lo, hi));
}

// Eight pixels d under colour c16 (16-bit lanes, premultiplied) scaled by the coverage levels k (eight 32-bit lanes
// in [0, 255]): over8(scale8(c, k), d).
VRASTER_AVX2 __m256i over_coverage8(__m256i d, __m256i c16, __m256i k) {
  const __m256i zero = _mm256_setzero_si256();
  // unpacklo/hi hold pixels {0, 1 | 4, 5} and {2, 3 | 6, 7}: spread each pixel's level over its four lanes to match.
  const __m256i spread_lo = _mm256_setr_epi8(0, -1, 0, -1, 0, -1, 0, -1, 4, -1, 4, -1, 4, -1, 4, -1,
                                             0, -1, 0, -1, 0, -1, 0, -1, 4, -1, 4, -1, 4, -1, 4, -1);
  const __m256i spread_hi = _mm256_setr_epi8(8, -1, 8, -1, 8, -1, 8, -1, 12, -1, 12, -1, 12, -1, 12, -1,
                                             8, -1, 8, -1, 8, -1, 8, -1, 12, -1, 12, -1, 12, -1, 12, -1);
  const __m256i s_lo = scale16(c16, _mm256_shuffle_epi8(k, spread_lo));
  const __m256i s_hi = scale16(c16, _mm256_shuffle_epi8(k, spread_hi));
  const __m256i d_lo = scale16(_mm256_unpacklo_epi8(d, zero), inverse_alpha16(s_lo));
  const __m256i d_hi = scale16(_mm256_unpackhi_epi8(d, zero), inverse_alpha16(s_hi));
  return _mm256_add_epi32(_mm256_packus_epi16(s_lo, s_hi), _mm256_packus_epi16(d_lo, d_hi));
}

// quantize8(coverage * scale) for eight values: clamp to [0, 1] (NaN -> 0: maxps returns its second operand when
// either is NaN), times 255, plus 0.5, truncated. Multiply then add, as the scalar code (no fused multiply-add).
VRASTER_AVX2 __m256i quantize8x8(__m256 v, __m256 scale) {
  v = _mm256_max_ps(_mm256_mul_ps(v, scale), _mm256_setzero_ps());
  v = _mm256_min_ps(v, _mm256_set1_ps(1.f));
  return _mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(v, _mm256_set1_ps(255.f)), _mm256_set1_ps(0.5f)));
}

#undef VRASTER_AVX2

}  // namespace vraster::detail::avx2

#endif
