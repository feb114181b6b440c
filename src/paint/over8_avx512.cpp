// The two source-over loops of over8_avx2.cpp in AVX-512 (BW, VL): sixteen pixels a step, and the ends of a run
// with mask registers, which cost no more than a full step (AVX2's masked stores are slow on some processors); a run
// of up to eight pixels (most of them) is one eight-pixel step, so that it reads no more memory than it needs.
// Picked at run time where the processor has AVX-512 BW and VL (composite.cpp). The arithmetic is blend.hpp's lane by lane, as in
// the AVX2 loops, so the bits are those of the portable loops.
#include "blend.hpp"
#include "paint/over8_avx2.hpp"

#ifdef VRASTER_HAVE_AVX2_KERNELS

// GCC 12's AVX-512 headers fill the unused operand of maxps, minps, cvttps2dq and broadcasti32x4 with a deliberately
// undefined register and then warn that it may be used uninitialized; it is not used.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace vraster::detail {
namespace {

#define VRASTER_AVX512 [[gnu::target("avx512f,avx512bw,avx512vl"), gnu::always_inline]] inline

// round(a * f / 255) per 16-bit lane for a, f in [0, 255] (scale8's form, as the high half of t * 257: see
// over8_avx2.hpp's scale16).
VRASTER_AVX512 __m512i scale32(__m512i a, __m512i f) {
  const __m512i t = _mm512_add_epi16(_mm512_mullo_epi16(a, f), _mm512_set1_epi16(128));
  return _mm512_mulhi_epu16(t, _mm512_set1_epi16(257));
}

// 255 - alpha of every pixel, spread over its four lanes (alpha is lane 3 of each pixel).
VRASTER_AVX512 __m512i inverse_alpha32(__m512i s) {
  const __m512i a = _mm512_shufflehi_epi16(_mm512_shufflelo_epi16(s, 0xFF), 0xFF);
  return _mm512_sub_epi16(_mm512_set1_epi16(255), a);
}

// Lanes i < n set (n in [0, 16]).
VRASTER_AVX512 __mmask16 first_lanes16(int n) { return static_cast<__mmask16>((1u << n) - 1u); }

// Sixteen pixels d under the constant source s whose inverse alpha is inv: s + scale8(d, inv).
VRASTER_AVX512 __m512i over_constant16(__m512i d, __m512i s, __m512i inv) {
  const __m512i zero = _mm512_setzero_si512();
  const __m512i lo = scale32(_mm512_unpacklo_epi8(d, zero), inv);
  const __m512i hi = scale32(_mm512_unpackhi_epi8(d, zero), inv);
  return _mm512_add_epi32(s, _mm512_packus_epi16(lo, hi));
}

// Sixteen pixels d under colour c16 (16-bit lanes) scaled by the levels k (sixteen 32-bit lanes in [0, 255]). The
// unpacks work within 128-bit lanes, as in AVX2: each lane holds pixels {0, 1} and {2, 3} of its four.
VRASTER_AVX512 __m512i over_coverage16(__m512i d, __m512i c16, __m512i k) {
  const __m512i zero = _mm512_setzero_si512();
  const __m512i spread_lo = _mm512_broadcast_i32x4(_mm_setr_epi8(0, -1, 0, -1, 0, -1, 0, -1, 4, -1, 4, -1, 4, -1, 4, -1));
  const __m512i spread_hi =
      _mm512_broadcast_i32x4(_mm_setr_epi8(8, -1, 8, -1, 8, -1, 8, -1, 12, -1, 12, -1, 12, -1, 12, -1));
  const __m512i s_lo = scale32(c16, _mm512_shuffle_epi8(k, spread_lo));
  const __m512i s_hi = scale32(c16, _mm512_shuffle_epi8(k, spread_hi));
  const __m512i d_lo = scale32(_mm512_unpacklo_epi8(d, zero), inverse_alpha32(s_lo));
  const __m512i d_hi = scale32(_mm512_unpackhi_epi8(d, zero), inverse_alpha32(s_hi));
  return _mm512_add_epi32(_mm512_packus_epi16(s_lo, s_hi), _mm512_packus_epi16(d_lo, d_hi));
}

// quantize8(coverage * scale) for sixteen values, as quantize8x8 (maxps gives 0 for NaN, no fused multiply-add).
VRASTER_AVX512 __m512i quantize8x16(__m512 v, __m512 scale) {
  v = _mm512_max_ps(_mm512_mul_ps(v, scale), _mm512_setzero_ps());
  v = _mm512_min_ps(v, _mm512_set1_ps(1.f));
  return _mm512_cvttps_epi32(_mm512_add_ps(_mm512_mul_ps(v, _mm512_set1_ps(255.f)), _mm512_set1_ps(0.5f)));
}

#undef VRASTER_AVX512

}  // namespace

[[gnu::target("avx512f,avx512bw,avx512vl")]] void over8_constant_avx512(std::uint32_t* px, int n, std::uint32_t s) {
  if (n <= 8) {  // a short run (most of them): one eight-pixel step under a mask register
    const __mmask8 m = static_cast<__mmask8>((1u << n) - 1u);
    const __m256i d = _mm256_maskz_loadu_epi32(m, px);
    _mm256_mask_storeu_epi32(px, m, avx2::over_constant8(d, _mm256_set1_epi32(static_cast<int>(s)),
                                                         _mm256_set1_epi16(static_cast<short>(255u - (s >> 24)))));
    return;
  }
  const __m512i src = _mm512_set1_epi32(static_cast<int>(s));
  const __m512i inv = _mm512_set1_epi16(static_cast<short>(255u - (s >> 24)));
  int i = 0;
  for (; i + 16 <= n; i += 16) {
    _mm512_storeu_si512(px + i, over_constant16(_mm512_loadu_si512(px + i), src, inv));
  }
  if (i < n) {
    const __mmask16 m = first_lanes16(n - i);
    _mm512_mask_storeu_epi32(px + i, m, over_constant16(_mm512_maskz_loadu_epi32(m, px + i), src, inv));
  }
}

[[gnu::target("avx512f,avx512bw,avx512vl")]] void over8_solid_avx512(std::uint32_t* px, int n, const float* coverage,
                                                           float scale, std::uint32_t c) {
  if (n <= 8) {  // a short run (most of them): one eight-pixel step under a mask register
    const __mmask8 m = static_cast<__mmask8>((1u << n) - 1u);
    const __m256i c16 = _mm256_unpacklo_epi8(_mm256_set1_epi32(static_cast<int>(c)), _mm256_setzero_si256());
    const __m256i k = avx2::quantize8x8(_mm256_maskz_loadu_ps(m, coverage), _mm256_set1_ps(scale));
    _mm256_mask_storeu_epi32(px, m, avx2::over_coverage8(_mm256_maskz_loadu_epi32(m, px), c16, k));
    return;
  }
  const __m512i c16 = _mm512_unpacklo_epi8(_mm512_set1_epi32(static_cast<int>(c)), _mm512_setzero_si512());
  const __m512 sc = _mm512_set1_ps(scale);
  int i = 0;
  for (; i + 16 <= n; i += 16) {
    const __m512i k = quantize8x16(_mm512_loadu_ps(coverage + i), sc);
    _mm512_storeu_si512(px + i, over_coverage16(_mm512_loadu_si512(px + i), c16, k));
  }
  if (i < n) {
    const __mmask16 m = first_lanes16(n - i);
    const __m512i k = quantize8x16(_mm512_maskz_loadu_ps(m, coverage + i), sc);
    _mm512_mask_storeu_epi32(px + i, m, over_coverage16(_mm512_maskz_loadu_epi32(m, px + i), c16, k));
  }
}

}  // namespace vraster::detail

#endif
