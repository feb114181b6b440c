// What the processor running us can do, for the hand-written SIMD kernels (rows of cells, rows of pixels).
// Each kernel has a portable version that gives the same bits, used when the processor lacks the instructions.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define VRASTER_HAVE_AVX2_KERNELS 1
#endif

namespace vraster::detail {

/// Tests set this to run the portable kernels where AVX2 is there too, and compare the two.
inline bool& portable_kernels_forced() {
  static bool forced = false;
  return forced;
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
inline bool cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has && !portable_kernels_forced();
}
/// AVX-512 F, BW and VL (the pixel loops' sixteen-pixel steps); such a processor has AVX2 too.
inline bool cpu_has_avx512bw() {
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                          __builtin_cpu_supports("avx512vl");
  return has && cpu_has_avx2();
}
#endif

}  // namespace vraster::detail
