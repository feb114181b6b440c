// Hand-written AVX2 source-over for 8-bit pixels: the two loops that nearly every fill ends in (a constant colour
// under constant coverage, and a solid colour under a row of coverage). Eight pixels a step with the channels in
// 16-bit lanes; the runs the rasterizer hands over are mostly short (2 to 16 pixels), so their ends are done with
// masked loads and stores instead of the scalar loops a compiler-vectorised loop falls back to. The arithmetic is
// blend.hpp's (scale8, over8, quantize8) lane by lane, so the bits are those of the portable loops.
#include "blend.hpp"
#include "paint/over8_avx2.hpp"

#ifdef VRASTER_HAVE_AVX2_KERNELS

namespace vraster::detail {
using namespace avx2;

[[gnu::target("avx2")]] void over8_constant_avx2(std::uint32_t* px, int n, std::uint32_t s) {
  const __m256i src = _mm256_set1_epi32(static_cast<int>(s));
  const __m256i inv = _mm256_set1_epi16(static_cast<short>(255u - (s >> 24)));
  auto* p = reinterpret_cast<__m256i*>(px);
  // A partial step up to the first 32-byte boundary, whole aligned steps, a partial step at the end.
  int i = to_aligned32(px, n);
  if (i > 0) {
    const __m256i m = first_lanes(i);
    store_first(px, over_constant8(_mm256_maskload_epi32(reinterpret_cast<const int*>(px), m), src, inv), i);
  }
  for (; i + 8 <= n; i += 8) {
    p = reinterpret_cast<__m256i*>(px + i);
    _mm256_store_si256(p, over_constant8(_mm256_load_si256(p), src, inv));
  }
  if (i < n) {
    const __m256i m = first_lanes(n - i);
    store_first(px + i, over_constant8(_mm256_maskload_epi32(reinterpret_cast<const int*>(px + i), m), src, inv),
                n - i);
  }
}

[[gnu::target("avx2")]] void over8_solid_avx2(std::uint32_t* px, int n, const float* coverage, float scale,
                                              std::uint32_t c) {
  const __m256i zero = _mm256_setzero_si256();
  const __m256i c16 = _mm256_unpacklo_epi8(_mm256_set1_epi32(static_cast<int>(c)), zero);
  const __m256 sc = _mm256_set1_ps(scale);
  int i = 0;
  if (n >= 8 && c >> 24 == 255 && scale == 1.f) {
    // An opaque colour: eight fully covered pixels become the colour, whatever they were (over8 of an opaque source
    // adds scale8(d, 0) = 0), so they are stored without reading them. A loop of its own, entered only by runs of
    // eight or more: the test inside the one loop cost the short runs most calls are 1.4 % (thin_slivers).
    const __m256i colour = _mm256_set1_epi32(static_cast<int>(c));
    const __m256 full = _mm256_set1_ps(1.f);
    for (; i + 8 <= n; i += 8) {
      auto* p = reinterpret_cast<__m256i*>(px + i);
      const __m256 v = _mm256_loadu_ps(coverage + i);
      if (_mm256_movemask_ps(_mm256_cmp_ps(v, full, _CMP_GE_OQ)) == 0xFF) {
        _mm256_storeu_si256(p, colour);
      } else {
        _mm256_storeu_si256(p, over_coverage8(_mm256_loadu_si256(p), c16, quantize8x8(v, sc)));
      }
    }
  }
  for (; i + 8 <= n; i += 8) {
    auto* p = reinterpret_cast<__m256i*>(px + i);
    const __m256i k = quantize8x8(_mm256_loadu_ps(coverage + i), sc);
    _mm256_storeu_si256(p, over_coverage8(_mm256_loadu_si256(p), c16, k));
  }
  if (i < n) {
    const __m256i m = first_lanes(n - i);
    const __m256i k = quantize8x8(_mm256_maskload_ps(coverage + i, m), sc);
    store_first(px + i, over_coverage8(_mm256_maskload_epi32(reinterpret_cast<const int*>(px + i), m), c16, k), n - i);
  }
}

}  // namespace vraster::detail

#endif
