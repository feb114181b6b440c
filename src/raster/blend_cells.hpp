// Cells to pixels in one pass: a run of accumulation cells -> coverage (the sweep's blocks of four, cells.hpp) ->
// one colour blended source-over onto 8-bit premultiplied pixels (SolidOver8), eight pixels a step, with the
// arithmetic of SolidCompositor::row (paint/over8_avx2.hpp). What it saves is the coverage row in between, the pass
// over it and the call: about a tenth of the frame of convex shapes (docs/performance.md).
#pragma once

#include <algorithm>
#include <cstdint>

#include "raster/cells.hpp"
#include "raster/cpu.hpp"
#include "raster/fixed_cells.hpp"

#ifdef VRASTER_HAVE_AVX2_KERNELS
#include "paint/over8_avx2.hpp"

namespace vraster::detail {

/// The first n (1 to 8) of the pixels at p under colour c16 (16-bit lanes) at the coverage levels k: one step of both
/// kernels below.
[[gnu::target("avx2"), gnu::always_inline]] inline void blend_step8(std::uint32_t* p, int n, __m256i c16, __m256i k) {
  namespace a2 = avx2;
  if (n == 8) {
    auto* q = reinterpret_cast<__m256i*>(p);
    _mm256_storeu_si256(q, a2::over_coverage8(_mm256_loadu_si256(q), c16, k));
  } else {
    const __m256i d = _mm256_maskload_epi32(reinterpret_cast<const int*>(p), a2::first_lanes(n));
    a2::store_first(p, a2::over_coverage8(d, c16, k), n);
  }
}

/// Where the colour is opaque (`opaque`) and all eight of a whole step's coverages are 1: the eight pixels become the
/// colour whatever they were (over8 adds scale8(d, 0) = 0 to it), so they are stored without being read (a pixel
/// load is most of a step's time where the pixels are cold). Returns whether it stored them.
[[gnu::target("avx2"), gnu::always_inline]] inline bool store_covered8(std::uint32_t* p, int n, __m256 coverage,
                                                                       bool opaque, std::uint32_t color) {
  if (!opaque || n != 8 || _mm256_movemask_ps(_mm256_cmp_ps(coverage, _mm256_set1_ps(1.f), _CMP_GE_OQ)) != 0xFF) {
    return false;
  }
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_set1_epi32(static_cast<int>(color)));
  return true;
}

/// One step of the kernels below where the row goes on past the step: a partial step of n < 8 pixels (the short
/// runs at a shape's sides) as a whole one, the pixels past the run under coverage 0, which leaves them as they are
/// (over8 of a zero source is exact: scale8(d, 255) = d). A load and a store of eight pixels instead of a masked load,
/// plain stores of 4, 2 and 1 pixels and their branches on n: thin_slivers 5-8 %, opaque_triangles 10-12 %,
/// opaque_rects 2-4 % faster (docs/performance.md, thirtieth session). Only for opaque colours (the callers decide):
/// after a translucent run comes a span that reads the pixels again, and a load partly overlapping the wider store
/// just made waits for it (for every colour, discs100 measured 1.18 in one alternation).
[[gnu::target("avx2"), gnu::always_inline]] inline void blend_whole_step8(std::uint32_t* p, int n, __m256i c16,
                                                                          __m256i k) {
  namespace a2 = avx2;
  auto* const q = reinterpret_cast<__m256i*>(p);
  _mm256_storeu_si256(q, a2::over_coverage8(_mm256_loadu_si256(q), c16, _mm256_and_si256(k, a2::first_lanes(n))));
}

/// Sweeps cells[0, count) from the running sum `sum` (left past them) in blocks of four, zeroing them, and blends the
/// coverage of the first `pixels` (at most count) onto px[0, pixels) with colour `color` (premultiplied, not fully
/// transparent). The cells up to three past count, which the last block reads, must be zero (untouched); they are
/// zeroed too. The coverage is sweep_cells' to the bit, and the pixels are what SolidCompositor::row gives it (a
/// coverage of 0 leaves a pixel as it is). `room`: how many pixels from px on the row holds (and this thread owns),
/// which a partial step may read and write back unchanged (blend_whole_step8); 0 for none.
template <FillRule R>
[[gnu::target("avx2")]] inline void blend_cells_avx2(double* cells, int count, int pixels, double& sum,
                                                     std::uint32_t* px, std::uint32_t color, int room = 0) {
  namespace a2 = avx2;
  const __m256i c16 = _mm256_unpacklo_epi8(_mm256_set1_epi32(static_cast<int>(color)), _mm256_setzero_si256());
  const bool opaque = color >> 24 == 255;
  __m256d carry = _mm256_set1_pd(sum);
  for (int i = 0; i < count; i += 8) {
    // Coverage in registers: a load of floats stored as two halves moments before would wait for the stores.
    __m128 low, high = _mm_setzero_ps();
    sweep_block_avx2<R>(load_fresh_cells(cells + i), low, carry);
    _mm256_storeu_pd(cells + i, _mm256_setzero_pd());
    if (i + 4 < count) {
      sweep_block_avx2<R>(load_fresh_cells(cells + i + 4), high, carry);
      _mm256_storeu_pd(cells + i + 4, _mm256_setzero_pd());
    }
    const int n = std::min(8, pixels - i);
    if (n <= 0) continue;  // cells right of the image: swept for the sum only
    const __m256 coverage = _mm256_set_m128(high, low);
    if (store_covered8(px + i, n, coverage, opaque, color)) continue;
    const __m256i k = a2::quantize8x8(coverage, _mm256_set1_ps(1.f));
    if (n < 8 && i + 8 <= room) {
      blend_whole_step8(px + i, n, c16, k);
    } else {
      blend_step8(px + i, n, c16, k);
    }
  }
  sum = _mm_cvtsd_f64(_mm256_castpd256_pd128(carry));
}

/// blend_cells_avx2 for fixed-point cells (fixed_cells.hpp), eight a step: the same pixels as
/// sweep_fixed_cells_avx2's coverage handed to SolidCompositor::row. Reads and zeroes cells up to seven past count
/// (which must be zero). `room` as for blend_cells_avx2.
template <FillRule R>
[[gnu::target("avx2")]] inline void blend_fixed_cells_avx2(std::int32_t* cells, int count, int pixels,
                                                           std::int32_t& sum, std::uint32_t* px, std::uint32_t color,
                                                           int room = 0) {
  namespace a2 = avx2;
  const __m256i c16 = _mm256_unpacklo_epi8(_mm256_set1_epi32(static_cast<int>(color)), _mm256_setzero_si256());
  const bool opaque = color >> 24 == 255;
  __m256i carry = _mm256_set1_epi32(sum);
  for (int i = 0; i < count; i += kFixedBlock) {
    const __m256 coverage = sweep_fixed_block_avx2<R, false>(cells + i, carry);  // (the snap moves no level)
    const int n = std::min(kFixedBlock, pixels - i);
    if (n <= 0) continue;  // cells right of the image: swept for the sum only
    if (store_covered8(px + i, n, coverage, opaque, color)) continue;
    const __m256i k = a2::quantize8x8(coverage, _mm256_set1_ps(1.f));
    if (n < 8 && i + 8 <= room) {
      blend_whole_step8(px + i, n, c16, k);
    } else {
      blend_step8(px + i, n, c16, k);
    }
  }
  sum = _mm256_cvtsi256_si32(carry);
}

}  // namespace vraster::detail

#endif
