// Cell accumulation shared by the analytic sweeps: pieces of edges inside one pixel row -> signed area deltas
// in cells -> a running sum per row -> coverage under a fill rule -> CoverageSink.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "raster/cpu.hpp"
#include "vraster/raster.hpp"

namespace vraster::detail {

// Coverage from the accumulated signed area s (the winding number, averaged over the pixel).
// Exact where one pixel sees a single winding transition; an approximation where edges cross inside a pixel.
// Coverage this close to 0 or 1 is 0 or 1: round-off left by edges that cancel must not become coverage (it would
// cost spans and break exact invariance under translation). Far below the area of a 1e-6 x 1e-6 px shape.
constexpr double kSnap = 0x1p-43;

inline float snapped(double c) { return static_cast<float>(c < kSnap ? 0.0 : (c > 1.0 - kSnap ? 1.0 : c)); }

// Coverage of the running sum s under rule R, without data-dependent branches (the SIMD kernel's arithmetic).
template <FillRule R>
inline double rule_coverage(double s) {
  if constexpr (R == FillRule::EvenOdd) {
    // Fold |s| into [0, 2) (windings beyond 2 inside one pixel; exact, subtracts 0 below 2), then mirror (1, 2)
    // onto (1, 0).
    double a = std::abs(s);
    a -= 2.0 * std::floor(a * 0.5);
    return std::min(a, 2.0 - a);
  } else if constexpr (R == FillRule::Positive) {
    return std::min(std::max(s, 0.0), 1.0);
  } else if constexpr (R == FillRule::Negative) {
    return std::min(std::max(-s, 0.0), 1.0);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return std::min(std::max(std::abs(s) - 1.0, 0.0), 1.0);
  } else {
    return std::min(std::abs(s), 1.0);
  }
}

template <FillRule R>
inline float coverage_of(double s) {
  return snapped(rule_coverage<R>(s));
}

// The per-row pass: accumulation cells -> running sum -> coverage.
//
// The running sum is taken in blocks of four cells, in one fixed order of additions (below), on every machine:
// with AVX2 the four sums of a block come out of one register, without it the same additions run one by one. So
// the bits never depend on the instruction set, and the only serial step is one addition per block (the sum
// carried from block to block) instead of one per cell.

// One block of up to four cells, one addition at a time, in the order the AVX2 kernel adds them:
//   p0 = a, p1 = a + b, p2 = (b + c) + a, p3 = (c + d) + (a + b); cell i gets sum + p_i; the sum moves on by p3.
template <FillRule R>
inline void sweep_block_scalar(double* cells, float* cov, int n, double& sum) {
  // Cells past n count as 0 (read one by one: a loop here would become a library call).
  const double a = cells[0], b = n > 1 ? cells[1] : 0.0, c = n > 2 ? cells[2] : 0.0, d = n > 3 ? cells[3] : 0.0;
  const double p[4] = {a, a + b, (b + c) + a, (c + d) + (a + b)};
  for (int i = 0; i < n; ++i) {
    cov[i] = coverage_of<R>(sum + p[i]);
    cells[i] = 0;
  }
  sum = sum + p[3];
}

template <FillRule R>
inline void sweep_cells_scalar(double* cells, float* cov, int n, double& sum) {
  for (int i = 0; i < n; i += 4) sweep_block_scalar<R>(cells + i, cov + i, n - i < 4 ? n - i : 4, sum);
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
// Four cells the row's pieces have just written, one double at a time: read as two halves of two doubles each, each
// double its own load. One 32-byte load of cells written by separate 8-byte stores moments before cannot take their
// data from the store queue and waits until the stores reach the cache (perf put a fifth of a thin shape's row loop
// on that wait); a load of one double takes it from its store.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256d load_fresh_cells(const double* cells) {
  __m128d lo = _mm_load_sd(cells), hi = _mm_load_sd(cells + 2);
  asm("" : "+x"(lo), "+x"(hi));  // keeps GCC from merging the loads into wider ones
  lo = _mm_loadh_pd(lo, cells + 1);
  hi = _mm_loadh_pd(hi, cells + 3);
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(lo), hi, 1);
}
// rule_coverage on four sums. std::min/std::max on doubles are (b < a ? b : a) / (a < b ? b : a); minpd/maxpd
// return their second operand when the comparison fails, so the argument order below gives the same values (sums
// here are never NaN).
template <FillRule R>
[[gnu::target("avx2")]] inline __m256d rule_coverage_avx2(__m256d s) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  const __m256d sign = _mm256_set1_pd(-0.0);
  if constexpr (R == FillRule::EvenOdd) {
    __m256d a = _mm256_andnot_pd(sign, s);
    const __m256d half_floor =
        _mm256_round_pd(_mm256_mul_pd(a, _mm256_set1_pd(0.5)), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    a = _mm256_sub_pd(a, _mm256_mul_pd(_mm256_set1_pd(2.0), half_floor));
    return _mm256_min_pd(a, _mm256_sub_pd(_mm256_set1_pd(2.0), a));
  } else if constexpr (R == FillRule::Positive) {
    return _mm256_min_pd(_mm256_max_pd(s, zero), one);
  } else if constexpr (R == FillRule::Negative) {
    return _mm256_min_pd(_mm256_max_pd(_mm256_xor_pd(s, sign), zero), one);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return _mm256_min_pd(_mm256_max_pd(_mm256_sub_pd(_mm256_andnot_pd(sign, s), one), zero), one);
  } else {
    return _mm256_min_pd(_mm256_andnot_pd(sign, s), one);
  }
}

// One block of four cells v: their prefix sums in a register ([a, b, c, d] + [0, a, b, c] = [a, a+b, b+c, c+d];
// plus [0, 0, a, a+b] = the prefix sums, added in sweep_block_scalar's order), coverage under the rule, snapped, as
// four floats; the carried sum moved past the block. Returns which of the four are nonzero (bit i: cov[i] != 0; a
// double this far from 0 stays nonzero as a float). Only the snap to 0 is done in doubles: a coverage within kSnap
// of 1 rounds to 1.0f when it becomes a float (the floats below 1 are 2^-24 apart), which is what snapping it to 1
// gives, so the four floats are snapped()'s.
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline int sweep_block_avx2(__m256d v, __m128& cov, __m256d& carry) {
  static_assert(kSnap < 0x1p-25, "coverage within kSnap of 1 rounds to 1.0f");
  const __m256d zero = _mm256_setzero_pd();
  const __m256d lo = _mm256_set1_pd(kSnap);
  const __m256d t1 = _mm256_add_pd(v, _mm256_blend_pd(_mm256_permute4x64_pd(v, 0x90), zero, 0x1));
  const __m256d t2 = _mm256_add_pd(t1, _mm256_permute2f128_pd(t1, t1, 0x08));
  const __m256d s = _mm256_add_pd(carry, t2);
  carry = _mm256_add_pd(carry, _mm256_permute4x64_pd(t2, 0xFF));
  const __m256d c = rule_coverage_avx2<R>(s);  // >= 0 and never NaN: below kSnap is exactly where it snaps to 0
  const __m256d below = _mm256_cmp_pd(c, lo, _CMP_LT_OQ);
  cov = _mm256_cvtpd_ps(_mm256_andnot_pd(below, c));
  return _mm256_movemask_pd(below) ^ 0xF;
}
// The same, the four floats stored at cov.
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline int sweep_block_avx2(__m256d v, float* cov, __m256d& carry) {
  __m128 c;
  const int nonzero = sweep_block_avx2<R>(v, c, carry);
  _mm_storeu_ps(cov, c);
  return nonzero;
}

template <FillRule R>
[[gnu::target("avx2")]] void sweep_cells_avx2(double* cells, float* cov, int n, double& sum) {
  __m256d carry = _mm256_set1_pd(sum);
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    sweep_block_avx2<R>(_mm256_loadu_pd(cells + i), cov + i, carry);
    _mm256_storeu_pd(cells + i, _mm256_setzero_pd());
  }
  sum = _mm_cvtsd_f64(_mm256_castpd256_pd128(carry));
  if (i < n) sweep_block_scalar<R>(cells + i, cov + i, n - i, sum);
}

// A run of n <= 4 cells in a padded row (the row sweep's) as one AVX2 block: the cells past the run (untouched
// zeros or the next run's, left as they are) count as zero, as in sweep_block_scalar; the coverage written past the
// run is overwritten before it is read.
template <FillRule R>
[[gnu::target("avx2")]] inline void sweep_short_run_avx2(double* cells, float* cov, int n, double& sum) {
  const __m256i lanes = _mm256_setr_epi64x(0, 1, 2, 3);
  const __m256d in_run = _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(n), lanes));
  const __m256d v = load_fresh_cells(cells);
  _mm256_storeu_pd(cells, _mm256_andnot_pd(in_run, v));  // the run's cells zeroed, the others kept
  __m256d carry = _mm256_set1_pd(sum);
  sweep_block_avx2<R>(_mm256_and_pd(in_run, v), cov, carry);
  sum = _mm_cvtsd_f64(_mm256_castpd256_pd128(carry));
}

// A block of four cells of a narrow row (sweep_narrow_row), where every cell outside the row's touched range is
// zero: the block is swept whole and zeroed by a store of constants (no mask). The store's data then does not wait
// for the cells, so the next row's pieces, which add to the same cells, need not wait for this row's sweep.
template <FillRule R>
[[gnu::target("avx2")]] inline int sweep_zeroed_block_avx2(double* cells, float* cov, double& sum) {
  const __m256d v = load_fresh_cells(cells);
  _mm256_storeu_pd(cells, _mm256_setzero_pd());
  __m256d carry = _mm256_set1_pd(sum);
  const int nonzero = sweep_block_avx2<R>(v, cov, carry);
  sum = _mm_cvtsd_f64(_mm256_castpd256_pd128(carry));
  return nonzero;
}

#endif

/// cells[0, n) -> cov[0, n): cov[i] is the coverage of sum + cells[0] + ... + cells[i] (summed in blocks, above);
/// zeroes the cells and leaves the sum past the last cell in `sum`.
template <FillRule R>
inline void sweep_cells(double* cells, float* cov, int n, double& sum) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (cpu_has_avx2()) return sweep_cells_avx2<R>(cells, cov, n, sum);
#endif
  sweep_cells_scalar<R>(cells, cov, n, sum);
}


/// sweep_cells with the kernel chosen at compile time: kAvx2 where the caller is compiled for AVX2 and was chosen
/// per fill already (no test per run).
template <FillRule R, bool kAvx2>
[[gnu::always_inline]] inline void sweep_cells_for(double* cells, float* cov, int n, double& sum) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if constexpr (kAvx2) return sweep_cells_avx2<R>(cells, cov, n, sum);
#endif
  sweep_cells<R>(cells, cov, n, sum);
}

// Adds one straight piece of an edge inside a row to the accumulation cells. The piece runs between x = xa and
// x = xb (either order) and covers height h of the row (signed by winding). Cell i receives the part of h
// times the share of the cell right of the piece, cell i + 1 the rest; the running sum along the row is then the
// signed area of each pixel that lies right of the edge (the winding number averaged over the pixel).
//
// The split without branches (split4 and accumulate_split, below) writes cells i .. i + 3 for a piece that starts
// in cell i (the cells past the piece get + 0): its rows need kPieceSlack cells past the last cell a piece can start
// in. With or without that split, the same numbers are added to each cell in the same order.
constexpr int kPieceSlack = 3;

#ifdef VRASTER_HAVE_AVX2_KERNELS
// The whole cells of a long piece, four at a time: cells [from, from + count) each get + half twice (once as the
// cell after one whole cell, once as a whole cell itself), which is what the loop of accumulate_long_piece adds to
// them, in its order. Without a loop whose length changes from row to row for most pieces (a sliver's piece covers
// four cells in one row and five in the next), so without its mispredicted exit. Needs 3 cells of row padding.
[[gnu::target("avx2")]] inline void add_whole_cells_avx2(double* acc, int from, int count, double half) {
  const __m256d lanes = _mm256_setr_pd(0, 1, 2, 3), hv = _mm256_set1_pd(half);
  for (int j = 0; j < count; j += 4) {
    const __m256d in = _mm256_cmp_pd(lanes, _mm256_set1_pd(count - j), _CMP_LT_OQ);
    const __m256d v = _mm256_loadu_pd(acc + from + j);
    _mm256_storeu_pd(acc + from + j, _mm256_blendv_pd(v, _mm256_add_pd(_mm256_add_pd(v, hv), hv), in));
  }
}
#endif

// The general split, for a piece from cell i0 to cell i1 > i0: the first and last cells take their part of the
// piece, every whole cell in between half its height for itself and half for the next cell. kAvx2: the whole cells
// by add_whole_cells_avx2 (the same additions in the same order per cell).
template <bool kAvx2 = false>
[[gnu::always_inline]] inline void accumulate_long_piece(double* acc, double xa, double xb, double h, int i0, int i1) {
  const double per_x = h / (xb - xa);
  // First, partial cell.
  const double f0 = (i0 + 1) - xa;
  const double h0 = per_x * f0;
  const double m0 = 1.0 - 0.5 * f0;  // mean x of the piece inside cell i0, relative to i0
  acc[i0] += h0 * (1.0 - m0);
  acc[i0 + 1] += h0 * m0;
  // Whole cells: the piece crosses each at mean x 0.5.
  const double half = 0.5 * per_x;
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if constexpr (kAvx2) {
    // Cell i0 + 1 takes + half as a whole cell after its share of the first cell; cells i0 + 2 .. i1 - 1 take
    // + half twice; cell i1 takes + half as the cell after the last whole one (before its share of the last cell).
    if (i1 > i0 + 1) {
      acc[i0 + 1] += half;
      add_whole_cells_avx2(acc, i0 + 2, i1 - i0 - 2, half);
      acc[i1] += half;
    }
  } else
#endif
  {
    for (int i = i0 + 1; i < i1; ++i) {
      acc[i] += half;
      acc[i + 1] += half;
    }
  }
  // Last, partial cell.
  const double f1 = xb - i1;
  if (f1 > 0) {
    const double h1 = per_x * f1;
    const double m1 = 0.5 * f1;
    acc[i1] += h1 * (1.0 - m1);
    acc[i1 + 1] += h1 * m1;
  }
}

// The adds of a piece within three cells, from cell i0 on (accumulate_piece's split; the order of additions is
// the general split's).
[[gnu::always_inline]] inline void accumulate_split(double* acc, int i0, double add0, double add1, double then1,
                                                    double add2, double then2, double add3) {
  acc[i0] += add0;
  acc[i0 + 1] = (acc[i0 + 1] + add1) + then1;
  acc[i0 + 2] = (acc[i0 + 2] + add2) + then2;
  acc[i0 + 3] += add3;
}

template <bool kAvx2 = false>
[[gnu::always_inline]] inline void accumulate_piece(double* acc, double xa, double xb, double h) {
  const double xl = std::min(xa, xb), xr = std::max(xa, xb);
  const int i0 = static_cast<int>(xl);
  const int k = static_cast<int>(xr) - i0;  // whole cells from the first cell to the last
  if (k == 0) {
    const double m = 0.5 * (xl + xr) - i0;
    acc[i0] += h * (1.0 - m);
    acc[i0 + 1] += h * m;
    return;
  }
  accumulate_long_piece<kAvx2>(acc, xl, xr, h, i0, i0 + k);
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
// All ones in the (64-bit) lanes where v's (32-bit) lane is k.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256d lanes_where_equal(__m128i v, int k) {
  return _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm_cmpeq_epi32(v, _mm_set1_epi32(k))));
}

// accumulate_piece for four pieces at once without branches (lane i: from x = xa[i] to xb[i], height h[i]): the
// first cell, how many cells the right end lies past it, and, for pieces within three cells (nine in ten), the
// numbers accumulate_split adds to cells first .. first + 3: the general split's numbers (accumulate_long_piece), or
// for a piece inside one cell its mean x, chosen by the count with blends. A branch on the count is mispredicted on
// a good share of pieces (it is about as often 0 as 1); chosen this way, polygons of 16-64 px fill 15-25 % faster
// (docs/performance.md). The numbers and the order of additions are accumulate_piece's, so the cells get the same
// values: minpd / maxpd with the operands below give std::min / std::max's, there is no FMA, and a piece that ends on
// a cell's left side adds + 0 where the general split adds nothing (only the sign of a zero cell can differ, which no
// sum sees).
struct Split4 {
  __m128i first, past;
  __m256d add0, add1, then1, add2, then2, add3;
};
[[gnu::target("avx2"), gnu::always_inline]] inline Split4 split4(__m256d xa, __m256d xb, __m256d h) {
  const __m256d half = _mm256_set1_pd(0.5), one = _mm256_set1_pd(1.0);
  const __m256d xl = _mm256_min_pd(xb, xa), xr = _mm256_max_pd(xb, xa);  // std::min(xa, xb), std::max(xa, xb)
  Split4 p;
  p.first = _mm256_cvttpd_epi32(xl);
  const __m128i right = _mm256_cvttpd_epi32(xr);
  p.past = _mm_sub_epi32(right, p.first);
  const __m256d first = _mm256_cvtepi32_pd(p.first);
  const __m256d per_x = _mm256_div_pd(h, _mm256_max_pd(_mm256_set1_pd(0x1p-1000), _mm256_sub_pd(xr, xl)));
  const __m256d f0 = _mm256_sub_pd(_mm256_add_pd(first, one), xl);
  const __m256d h0 = _mm256_mul_pd(per_x, f0), m0 = _mm256_sub_pd(one, _mm256_mul_pd(half, f0));
  const __m256d f1 = _mm256_sub_pd(xr, _mm256_cvtepi32_pd(right));
  const __m256d h1 = _mm256_mul_pd(per_x, f1), m1 = _mm256_mul_pd(half, f1);
  const __m256d whole = _mm256_mul_pd(half, per_x);
  const __m256d m = _mm256_sub_pd(_mm256_mul_pd(half, _mm256_add_pd(xl, xr)), first);
  const __m256d last0 = _mm256_mul_pd(h1, _mm256_sub_pd(one, m1)), last1 = _mm256_mul_pd(h1, m1);
  const __m256d one_cell = lanes_where_equal(p.past, 0), two_cells = lanes_where_equal(p.past, 1);
  const __m256d three_cells = lanes_where_equal(p.past, 2);
  const __m256d middle = _mm256_and_pd(three_cells, whole);
  p.add0 = _mm256_blendv_pd(_mm256_mul_pd(h0, _mm256_sub_pd(one, m0)), _mm256_mul_pd(h, _mm256_sub_pd(one, m)),
                            one_cell);
  p.add1 = _mm256_blendv_pd(_mm256_mul_pd(h0, m0), _mm256_mul_pd(h, m), one_cell);
  p.then1 = _mm256_blendv_pd(middle, last0, two_cells);
  p.add2 = _mm256_blendv_pd(middle, last1, two_cells);
  p.then2 = _mm256_and_pd(three_cells, last0);
  p.add3 = _mm256_and_pd(three_cells, last1);
  return p;
}

// Four shares in fixed-point cells' units (fixed_cells.hpp's kFixedUnit), rounded to nearest as to_fixed rounds.
[[gnu::target("avx2"), gnu::always_inline]] inline __m128i fixed_units(__m256d v) {
  return _mm256_cvtpd_epi32(_mm256_mul_pd(v, _mm256_set1_pd(0x1p26)));
}

// Four shares in wide cells' units (fixed_cells.hpp's kWideUnit, 2^36), rounded to nearest even as to_wide rounds:
// the scaled share plus 1.5 * 2^52 is rounded to a whole number by the addition (|share| < 2^51), whose low bits
// are then that number.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i wide_units(__m256d v) {
  const __m256d magic = _mm256_set1_pd(0x1.8p52);
  const __m256d shifted = _mm256_add_pd(_mm256_mul_pd(v, _mm256_set1_pd(0x1p36)), magic);
  return _mm256_sub_epi64(_mm256_castpd_si256(shifted), _mm256_castpd_si256(magic));
}

// A split's four lanes in memory, with the pieces' ends and heights, to add the pieces one at a time. Cell
// std::int32_t or std::int64_t: the shares in fixed-point or wide cells' units (fixed_cells.hpp: each cell gets the
// difference of the rounded running totals) instead of kept as doubles.
template <class Cell = double>
struct SplitLanes {
  static constexpr bool kFixed = !std::is_same_v<Cell, double>;
  alignas(32) double xa[4], xb[4], h[4], add0[4], add1[4], then1[4], add2[4], then2[4], add3[4];
  alignas(16) std::int32_t first[4], past[4];
  // kFixed: lane i's four shares, cells first .. first + 3 (one 16- or 32-byte addition a piece).
  alignas(32) Cell fixed[4][4];
  [[gnu::target("avx2"), gnu::always_inline]] SplitLanes(__m256d from_x, __m256d to_x, __m256d height) {
    const Split4 p = split4(from_x, to_x, height);
    _mm256_store_pd(xa, from_x);
    _mm256_store_pd(xb, to_x);
    _mm256_store_pd(h, height);
    if constexpr (kFixed) {
      // The shares' running totals (accumulate_split_fixed's sums, in its order), rounded to the cells' units; each
      // cell gets the difference of two, transposed from share c of the four lanes in row c to lane i's in row i.
      const __m256d c0 = p.add0, c1 = _mm256_add_pd(_mm256_add_pd(c0, p.add1), p.then1);
      const __m256d c2 = _mm256_add_pd(_mm256_add_pd(c1, p.add2), p.then2), c3 = _mm256_add_pd(c2, p.add3);
      if constexpr (std::is_same_v<Cell, std::int64_t>) {
        const __m256i q0 = wide_units(c0), q1 = wide_units(c1), q2 = wide_units(c2), q3 = wide_units(c3);
        const __m256i s0 = q0, s1 = _mm256_sub_epi64(q1, q0), s2 = _mm256_sub_epi64(q2, q1);
        const __m256i s3 = _mm256_sub_epi64(q3, q2);
        const __m256i t0 = _mm256_unpacklo_epi64(s0, s1), t1 = _mm256_unpacklo_epi64(s2, s3);  // lanes 0, 2
        const __m256i t2 = _mm256_unpackhi_epi64(s0, s1), t3 = _mm256_unpackhi_epi64(s2, s3);  // lanes 1, 3
        _mm256_store_si256(reinterpret_cast<__m256i*>(fixed[0]), _mm256_permute2x128_si256(t0, t1, 0x20));
        _mm256_store_si256(reinterpret_cast<__m256i*>(fixed[1]), _mm256_permute2x128_si256(t2, t3, 0x20));
        _mm256_store_si256(reinterpret_cast<__m256i*>(fixed[2]), _mm256_permute2x128_si256(t0, t1, 0x31));
        _mm256_store_si256(reinterpret_cast<__m256i*>(fixed[3]), _mm256_permute2x128_si256(t2, t3, 0x31));
      } else {
        const __m128i q0 = fixed_units(c0), q1 = fixed_units(c1), q2 = fixed_units(c2), q3 = fixed_units(c3);
        const __m128i s0 = q0, s1 = _mm_sub_epi32(q1, q0), s2 = _mm_sub_epi32(q2, q1), s3 = _mm_sub_epi32(q3, q2);
        const __m128i t0 = _mm_unpacklo_epi32(s0, s1), t1 = _mm_unpacklo_epi32(s2, s3);
        const __m128i t2 = _mm_unpackhi_epi32(s0, s1), t3 = _mm_unpackhi_epi32(s2, s3);
        _mm_store_si128(reinterpret_cast<__m128i*>(fixed[0]), _mm_unpacklo_epi64(t0, t1));
        _mm_store_si128(reinterpret_cast<__m128i*>(fixed[1]), _mm_unpackhi_epi64(t0, t1));
        _mm_store_si128(reinterpret_cast<__m128i*>(fixed[2]), _mm_unpacklo_epi64(t2, t3));
        _mm_store_si128(reinterpret_cast<__m128i*>(fixed[3]), _mm_unpackhi_epi64(t2, t3));
      }
    } else {
      _mm256_store_pd(add0, p.add0);
      _mm256_store_pd(add1, p.add1);
      _mm256_store_pd(then1, p.then1);
      _mm256_store_pd(add2, p.add2);
      _mm256_store_pd(then2, p.then2);
      _mm256_store_pd(add3, p.add3);
    }
    _mm_store_si128(reinterpret_cast<__m128i*>(first), p.first);
    _mm_store_si128(reinterpret_cast<__m128i*>(past), p.past);
  }
  /// kFixed: lane i's piece within three cells added to the cells at acc (its four shares at once).
  [[gnu::target("avx2"), gnu::always_inline]] void add_fixed(int i, Cell* acc) const {
    if constexpr (std::is_same_v<Cell, std::int64_t>) {
      auto* const cells = reinterpret_cast<__m256i*>(acc + first[i]);
      const __m256i shares = _mm256_load_si256(reinterpret_cast<const __m256i*>(fixed[i]));
      _mm256_storeu_si256(cells, _mm256_add_epi64(_mm256_loadu_si256(cells), shares));
    } else {
      auto* const cells = reinterpret_cast<__m128i*>(acc + first[i]);
      const __m128i shares = _mm_load_si128(reinterpret_cast<const __m128i*>(fixed[i]));
      _mm_storeu_si128(cells, _mm_add_epi32(_mm_loadu_si128(cells), shares));
    }
  }
  /// Lane i's piece added to the cells at acc (accumulate_piece's numbers, in its order).
  [[gnu::target("avx2"), gnu::always_inline]] void add(int i, double* acc) const {
    if (past[i] > 2) {
      accumulate_long_piece<true>(acc, std::min(xa[i], xb[i]), std::max(xa[i], xb[i]), h[i], first[i],
                                  first[i] + past[i]);
    } else {
      accumulate_split(acc, first[i], add0[i], add1[i], then1[i], add2[i], then2[i], add3[i]);
    }
  }
};
#endif

[[gnu::always_inline]] inline void mark_cells(std::uint64_t* bits, int from, int to) {  // inclusive range
  int w0 = from >> 6, w1 = to >> 6;
  const std::uint64_t first = ~std::uint64_t{0} << (from & 63);
  const std::uint64_t last = ~std::uint64_t{0} >> (63 - (to & 63));
  if (w0 == w1) {
    bits[w0] |= first & last;
    return;
  }
  bits[w0] |= first;
  for (int w = w0 + 1; w < w1; ++w) bits[w] = ~std::uint64_t{0};
  bits[w1] |= last;
}

// First set bit at or after `from`, or `limit` when there is none before it.
inline int next_set(const std::uint64_t* bits, int from, int limit) {
  int w = from >> 6;
  std::uint64_t word = bits[w] & (~std::uint64_t{0} << (from & 63));
  const int last_word = (limit - 1) >> 6;
  while (word == 0) {
    if (++w > last_word) return limit;
    word = bits[w];
  }
  return std::min((w << 6) + std::countr_zero(word), limit);
}

inline int next_clear(const std::uint64_t* bits, int from, int limit) {
  int w = from >> 6;
  std::uint64_t word = ~bits[w] & (~std::uint64_t{0} << (from & 63));
  const int last_word = (limit - 1) >> 6;
  while (word == 0) {
    if (++w > last_word) return limit;
    word = ~bits[w];
  }
  return std::min((w << 6) + std::countr_zero(word), limit);
}

// Zeroes words [w0, w1]. Most rows touch one or two words: stores, not the library call a loop becomes.
inline void clear_words(std::uint64_t* bits, int w0, int w1) {
  if (w1 - w0 < 2) {
    bits[w0] = 0;
    bits[w1] = 0;
  } else {
    std::fill(bits + w0, bits + w1 + 1, std::uint64_t{0});
  }
}

// Untouched stretches shorter than this inside a run of touched cells are written into the run's coverage instead
// of being a span of their own (and pieces this close are one cluster of a sparse row, sweep.cpp): one compositor
// call covers several edges.
constexpr int kMergeGap = 24;

// Row padding the short-run AVX2 block needs: cells and coverage past the last cell a piece can write.
constexpr int kRowPadding = 4;

// Sweeps one accumulated row: a running sum over touched cells, constant spans over long untouched stretches.
// Leaves the accumulation cells and the touched bits zero. kAvx2: compiled into an AVX2 function whose row has
// kRowPadding cells (and coverage) of padding, so runs of up to four cells take one AVX2 block.
template <FillRule R, bool kAvx2 = false>
[[gnu::always_inline]] inline void resolve_row(int y, int width, int x_lo, int x_hi, double* acc, std::uint64_t* bits,
                                               float* cov, CoverageSink& sink) {
  double sum = 0;
  int x = x_lo;
  int run = -1;  // first pixel of the open coverage run (cov[i - run] is pixel i), -1 when none is open
  const int limit = x_hi + 1;
  auto flush = [&](int end) {
    end = std::min(end, width);
    int a = run, b = end;
    while (a < b && cov[a - run] == 0) ++a;
    while (b > a && cov[b - 1 - run] == 0) --b;
    if (b - a == 1) {
      sink.span(y, a, b, cov[a - run]);
    } else if (b > a) {
      sink.row(y, a, b, cov + (a - run));
    }
    run = -1;
  };
  for (;;) {
    const int t = x >= limit ? limit : next_set(bits, x, limit);
    // Untouched cells [x, gap_end) keep the running sum; past the last touched cell that holds to the end of the
    // row (edges right of the image were dropped, so the sum need not return to 0 there).
    const int gap_end = t >= limit ? width : std::min(t, width);
    if (gap_end > x) {
      const float c = coverage_of<R>(sum);
      if (run >= 0 && t < limit && t - x <= kMergeGap && t <= width) {
        std::fill(cov + (x - run), cov + (t - run), c);
      } else {
        if (run >= 0) flush(x);
        if (c > 0) sink.span(y, x, gap_end, c);
      }
    }
    if (t >= limit) break;
    const int e = next_clear(bits, t, limit);
    if (run < 0) run = t;
    if (e - t <= 4) {  // most runs: a cell or two, not worth a call
#ifdef VRASTER_HAVE_AVX2_KERNELS
      if constexpr (kAvx2) {
        sweep_short_run_avx2<R>(acc + t, cov + (t - run), e - t, sum);
      } else
#endif
      {
        sweep_block_scalar<R>(acc + t, cov + (t - run), e - t, sum);
      }
    } else {
      sweep_cells_for<R, kAvx2>(acc + t, cov + (t - run), e - t, sum);
    }
    x = e;
  }
  if (run >= 0) flush(x);
  clear_words(bits, x_lo >> 6, x_hi >> 6);
}

// Rows whose pieces all fall within this many cells (thin shapes, the tips of others) are swept as one run.
constexpr int kNarrowRowCells = 32;

constexpr int kNarrowRowCoverage = kNarrowRowCells;  // floats of coverage a narrow row writes, at most
static_assert(kNarrowRowCells <= 32, "sweep_narrow_row's nonzero mask has a bit per cell");

// Cells x_lo .. x_hi (at most kNarrowRowCells) swept in whole blocks of four from x_lo, with the running sum carried
// in and out of `sum`; the cells up to three past x_hi must be zero (untouched). Writes the coverage of cells x_lo ..
// x_hi to cov[0 .. n) (and up to three floats past), zeroes the cells, and returns a mask with bit i set where
// cov[i] != 0 (i < n), so that the row can be trimmed to its nonzero pixels without a loop whose length changes from
// row to row (its exits were mispredicted on a tenth of a thin shape's rows). Same padding and kAvx2 as resolve_row.
template <FillRule R, bool kAvx2 = false>
[[gnu::always_inline]] inline std::uint32_t sweep_narrow_cells(int x_lo, int x_hi, double* acc, float* cov,
                                                               double& sum) {
  const int n = x_hi - x_lo + 1;
  std::uint32_t bits = 0;
  for (int i = 0; i < n; i += 4) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
    if constexpr (kAvx2) {
      bits |= static_cast<std::uint32_t>(sweep_zeroed_block_avx2<R>(acc + x_lo + i, cov + i, sum)) << i;
      continue;
    }
#endif
    sweep_block_scalar<R>(acc + x_lo + i, cov + i, std::min(4, n - i), sum);
    for (int j = i; j < std::min(i + 4, n); ++j) bits |= static_cast<std::uint32_t>(cov[j] != 0) << j;
  }
  return n < 32 ? bits & ((std::uint32_t{1} << n) - 1) : bits;  // the last block's lanes past n left out
}

// A row whose touched cells lie in [x_lo, x_hi], at most kNarrowRowCells of them, swept without touched bits: the
// cells in between are swept too (untouched ones are zero, and add nothing to the sum), with no search for runs.
// sweep_narrow_cells from a sum of 0 (`nonzero` gets its mask); returns the coverage right of the cells: the sum
// holds to the row's end there (edges right of the image were dropped).
template <FillRule R, bool kAvx2 = false>
[[gnu::always_inline]] inline float sweep_narrow_row(int x_lo, int x_hi, double* acc, float* cov,
                                                     std::uint32_t& nonzero) {
  double sum = 0;
  nonzero = sweep_narrow_cells<R, kAvx2>(x_lo, x_hi, acc, cov, sum);
  return coverage_of<R>(sum);
}

// A narrow row's nonzero pixels inside the image: [from, to) from the first to one past the last bit of
// sweep_narrow_row's mask below `visible` (the pixels left of the image's right edge). False when there are none.
inline bool nonzero_bounds(std::uint32_t nonzero, int visible, int& from, int& to) {
  if (visible < 32) nonzero &= visible > 0 ? (std::uint32_t{1} << visible) - 1 : 0;
  if (nonzero == 0) return false;
  from = std::countr_zero(nonzero);
  to = 32 - std::countl_zero(nonzero);
  return true;
}

// [a, b) narrowed to the part of cov[a .. b) between its first and last nonzero entries (empty when all are zero).
// The number of zeros at a row's ends changes from row to row, and a loop over them one by one was mispredicted at
// its exit: on x86-64 they are passed four at a time (SSE2, always there) in the blocks of four the sweep stored
// them in, counted from cov[0] (a must be a multiple of 4). A load that straddles two of the sweep's stores, or a
// last block it stored one float at a time, would wait for the stores to reach the cache: entries past the last
// whole block are passed one by one.
inline void trim_zeros(const float* cov, int& a, int& b) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  const __m128 zero = _mm_setzero_ps();
  while (b - a >= 4) {
    const int nonzero = _mm_movemask_ps(_mm_cmpneq_ps(_mm_loadu_ps(cov + a), zero));  // NaN counts as nonzero
    if (nonzero != 0) {
      a += std::countr_zero(static_cast<unsigned>(nonzero));
      break;
    }
    a += 4;
  }
  while (b > a && (b & 3) != 0 && cov[b - 1] == 0) --b;
  while (b - a >= 4 && (b & 3) == 0) {
    const int nonzero = _mm_movemask_ps(_mm_cmpneq_ps(_mm_loadu_ps(cov + b - 4), zero));
    if (nonzero != 0) {
      b -= std::countl_zero(static_cast<unsigned>(nonzero)) - 28;  // past the last nonzero of the four
      return;
    }
    b -= 4;
  }
#endif
  while (a < b && cov[a] == 0) ++a;
  while (b > a && cov[b - 1] == 0) --b;
}

// Calls f with the fill rule as a compile-time constant, so the per-cell coverage function (and
// any other per-rule test) is chosen once per fill.
template <class F>
void with_rule(FillRule rule, F&& f) {
  switch (rule) {
    case FillRule::EvenOdd: return f(std::integral_constant<FillRule, FillRule::EvenOdd>{});
    case FillRule::Positive: return f(std::integral_constant<FillRule, FillRule::Positive>{});
    case FillRule::Negative: return f(std::integral_constant<FillRule, FillRule::Negative>{});
    case FillRule::AbsGeq2: return f(std::integral_constant<FillRule, FillRule::AbsGeq2>{});
    case FillRule::NonZero:
    case FillRule::NonExterior: return f(std::integral_constant<FillRule, FillRule::NonZero>{});
  }
}

}  // namespace vraster::detail
