// Fixed-point cells for the row sweep's rows of few edges: each piece's area shares (cells.hpp's split, computed in
// doubles as before) rounded to 32-bit integers of 2^-26 of a pixel, and the running sum taken in integers.
//
// Why: the running sum is the sweep's per-pixel cost, and integers take eight cells a step where doubles take four,
// with no rounding in the sum at all (so any order of additions gives the same bits). What it costs in accuracy: a
// piece's shares are the differences of its running total rounded at every cell, so up to any cell a piece adds
// what it should within half a unit (2^-27), and a pixel's running sum is within kFixedRowEdges half units of the
// double cells': with the snap of residues (kFixedSnapUnits) and the coverage's rounding to float, kFixedCellsError
// (5.4e-7; docs/design.md, "Fixed-point cells"). Rows of more edges take the wide cells below (64-bit, finer
// units): in 32 bits their sums could pass 2^31, and the rounding would add up.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "raster/cells.hpp"
#include "raster/cpu.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

namespace vraster::detail {

constexpr int kFixedShift = 26;
constexpr std::int32_t kFixedOne = std::int32_t{1} << kFixedShift;  // a whole pixel of area
constexpr double kFixedUnit = 0x1p26;
// Rows of at most this many active edges take fixed-point cells: a running sum is at most one unit per edge
// (|winding| times kFixedOne), and 31 units fit 31 bits.
constexpr std::size_t kFixedRowEdges = 31;
// A row whose winding returns to 0 (or to a whole number) may keep a residue of up to half a unit per edge, where the
// pieces' rounded totals do not cancel: coverage within this many units of 0 or of 1 snaps to it, as the double
// cells' coverage within 2^-43 does. Where nothing is drawn, the coverage is exactly 0.
constexpr std::int32_t kFixedSnapUnits = (kFixedRowEdges + 1) / 2;
// The most a fixed-point row's coverage differs from the double cells' (and so from the exact area, beyond the double
// cells' own 1e-9): half a unit per edge, the snap, and the float's rounding of a coverage up to 1 (5.4e-7).
constexpr double kFixedCellsError =
    static_cast<double>(kFixedRowEdges + 1) * 0x1p-27 + kFixedSnapUnits * 0x1p-26 + 0x1p-24;
// The integer sweep reads cells in blocks of eight from a run's first cell: a row's cells need this much padding.
constexpr int kFixedBlock = 8;
static_assert(kMergeGap >= kFixedBlock - 1, "a cluster's last block must not reach the next cluster's cells");

/// v (a share of a pixel's area, |v| <= 2) in units of 2^-26, rounded to nearest (even on ties): the same integer
/// with SSE2 and without.
inline std::int32_t to_fixed(double v) {
#if defined(__SSE2__) || defined(_M_X64)
  return _mm_cvtsd_si32(_mm_set_sd(v * kFixedUnit));
#else
  return static_cast<std::int32_t>(std::lrint(v * kFixedUnit));
#endif
}

// Wide cells: rows of more than kFixedRowEdges active edges (a star's, a line of text set as one path) in 64-bit
// integers of 2^-36 of a pixel. The shares are rounded as the 32-bit cells' are (half a unit per piece, then the
// snap), in units small enough that a row of kWideRowEdges edges stays well inside kFixedCellsError, and a running
// sum of that many whole units is far inside 63 bits. Rows of more edges keep the double cells.
constexpr int kWideShift = 36;
constexpr std::int64_t kWideOne = std::int64_t{1} << kWideShift;
constexpr double kWideUnit = 0x1p36;
constexpr std::size_t kWideRowEdges = 16384;
constexpr std::int64_t kWideSnapUnits = (kWideRowEdges + 1) / 2;
// The coverage is the unit count shifted to 24 bits (exact in a float): truncation below 2^-24.
constexpr int kWideFloatShift = kWideShift - 24;
constexpr double kWideCellsError =
    static_cast<double>(kWideRowEdges + 1) * 0x1p-37 + static_cast<double>(kWideSnapUnits) * 0x1p-36 + 0x1p-24;
static_assert(kWideCellsError <= kFixedCellsError, "wide rows keep the fixed-point rows' bound");
// A running sum of kWideRowEdges pieces of up to two whole units each fits 63 bits; the AVX2 conversion (wide_units)
// needs the scaled shares below 2^51.
static_assert(static_cast<double>(kWideRowEdges) * 2 * kWideUnit < 0x1p62 && 2 * kWideUnit < 0x1p51);

/// v (a share of a pixel's area, |v| <= 2) in units of 2^-36, rounded to nearest (even on ties), as wide_units rounds
/// four at a time.
inline std::int64_t to_wide(double v) {
#if defined(__SSE2__) || defined(_M_X64)
  return _mm_cvtsd_si64(_mm_set_sd(v * kWideUnit));
#else
  return static_cast<std::int64_t>(std::llrint(v * kWideUnit));
#endif
}

/// A share in the units of the cell type: fixed-point (32-bit) or wide (64-bit) cells.
template <class Cell>
inline Cell to_units(double v) {
  if constexpr (std::is_same_v<Cell, std::int64_t>) {
    return to_wide(v);
  } else {
    static_assert(std::is_same_v<Cell, std::int32_t>);
    return to_fixed(v);
  }
}

/// Coverage of the running sum s under R, in units (0 .. kFixedOne): rule_coverage's values, in integers, before the
/// snap.
template <FillRule R, class Int>
inline Int rule_coverage_units(Int s, Int one) {
  if constexpr (R == FillRule::EvenOdd) {
    const Int w = s & (2 * one - 1);  // s modulo two units (two's complement: also for s < 0)
    return std::min(w, 2 * one - w);
  } else if constexpr (R == FillRule::Positive) {
    return std::clamp(s, Int{0}, one);
  } else if constexpr (R == FillRule::Negative) {
    return std::clamp(-s, Int{0}, one);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return std::clamp((s < 0 ? -s : s) - one, Int{0}, one);
  } else {
    return std::min(s < 0 ? -s : s, one);
  }
}

template <FillRule R>
inline std::int32_t unsnapped_coverage_units(std::int32_t s) {
  return rule_coverage_units<R>(s, kFixedOne);
}

/// The same, within kFixedSnapUnits of 0 or of a whole unit snapped to it.
template <FillRule R>
inline std::int32_t fixed_coverage_units(std::int32_t s) {
  const std::int32_t c = unsnapped_coverage_units<R>(s);
  return c <= kFixedSnapUnits ? 0 : c >= kFixedOne - kFixedSnapUnits ? kFixedOne : c;
}

template <FillRule R>
inline float fixed_coverage(std::int32_t s) {
  return static_cast<float>(fixed_coverage_units<R>(s)) * (1.0f / static_cast<float>(kFixedOne));
}

/// accumulate_long_piece in fixed point, for a piece over more than three cells: the shares' running total is rounded
/// at every cell instead of each share on its own, so the row's sum past the piece is off by one rounding, not one
/// per cell it crosses. Both sweeps (AVX2 and portable) add a long piece this way.
template <class Cell>
inline void accumulate_long_piece_fixed(Cell* acc, double xa, double xb, double h, int i0, int i1) {
  const double per_x = h / (xb - xa);
  const double f0 = (i0 + 1) - xa;
  const double h0 = per_x * f0, m0 = 1.0 - 0.5 * f0;
  const double half = 0.5 * per_x;
  const double f1 = xb - i1;
  const double h1 = per_x * f1;
  // Totals of the shares up to each cell (accumulate_long_piece's shares, in its order).
  double total = h0 * (1.0 - m0);
  Cell done = to_units<Cell>(total);
  acc[i0] += done;
  total = h0 + half;
  for (int i = i0 + 1; i < i1; ++i) {
    const Cell now = to_units<Cell>(total);
    acc[i] += now - done;
    done = now;
    total += i + 1 < i1 ? 2.0 * half : half;
  }
  total += h1 * (1.0 - 0.5 * f1);
  Cell now = to_units<Cell>(total);
  acc[i1] += now - done;
  done = now;
  total += h1 * (0.5 * f1);
  now = to_units<Cell>(total);
  acc[i1 + 1] += now - done;
}

/// The shares of a piece within three cells (split4's add0 .. add3), from cell i0 on: the running totals rounded and
/// their differences added, so that the piece's sum up to any cell is off by one rounding.
template <class Cell>
inline void accumulate_split_fixed(Cell* acc, int i0, double add0, double add1, double then1, double add2,
                                   double then2, double add3) {
  const double c0 = add0, c1 = (c0 + add1) + then1, c2 = (c1 + add2) + then2, c3 = c2 + add3;
  const Cell q0 = to_units<Cell>(c0), q1 = to_units<Cell>(c1), q2 = to_units<Cell>(c2), q3 = to_units<Cell>(c3);
  acc[i0] += q0;
  acc[i0 + 1] += q1 - q0;
  acc[i0 + 2] += q2 - q1;
  acc[i0 + 3] += q3 - q2;
}

/// accumulate_piece in fixed point (Cell std::int32_t) or wide cells (std::int64_t): the same shares as split4 gives
/// the AVX2 sweep (accumulate_long_piece's numbers, or a piece inside one cell by its mean x), so both sweeps add the
/// same integers.
template <class Cell>
inline void accumulate_piece_fixed(Cell* acc, double xa, double xb, double h) {
  const double xl = std::min(xa, xb), xr = std::max(xa, xb);
  const int i0 = static_cast<int>(xl);
  const int k = static_cast<int>(xr) - i0;
  if (k == 0) {
    const double m = 0.5 * (xl + xr) - i0;
    return accumulate_split_fixed(acc, i0, h * (1.0 - m), h * m, 0.0, 0.0, 0.0, 0.0);
  }
  if (k > 2) return accumulate_long_piece_fixed(acc, xl, xr, h, i0, i0 + k);
  const double per_x = h / (xr - xl);
  const double f0 = (i0 + 1) - xl;
  const double h0 = per_x * f0, m0 = 1.0 - 0.5 * f0;
  const double f1 = xr - (i0 + k);
  const double h1 = per_x * f1, m1 = 0.5 * f1;
  const double last0 = h1 * (1.0 - m1), last1 = h1 * m1;
  if (k == 1) return accumulate_split_fixed(acc, i0, h0 * (1.0 - m0), h0 * m0, last0, last1, 0.0, 0.0);
  const double whole = 0.5 * per_x;
  accumulate_split_fixed(acc, i0, h0 * (1.0 - m0), h0 * m0, whole, whole, last0, last1);
}

#ifdef VRASTER_HAVE_AVX2_KERNELS
/// Lane i of a fixed-point split added to the cells at acc: a long piece by accumulate_long_piece_fixed, one within
/// three cells by its four rounded shares at once (accumulate_piece_fixed's integers either way). Both AVX2 sweeps
/// (the row sweep's pieces, the dense walk) add a lane this way.
template <class Cell>
[[gnu::target("avx2"), gnu::always_inline]] inline void add_split_lane(const SplitLanes<Cell>& split, int i,
                                                                       Cell* acc) {
  if (split.past[i] > 2) {
    accumulate_long_piece_fixed(acc, std::min(split.xa[i], split.xb[i]), std::max(split.xa[i], split.xb[i]),
                                split.h[i], split.first[i], split.first[i] + split.past[i]);
  } else {
    split.add_fixed(i, acc);
  }
}
#endif

/// Coverage of a wide cells' running sum under R: fixed_coverage_units' rules in 2^-36 units, the snap at
/// kWideSnapUnits, then the units shifted to 24 bits (exact in a float).
template <FillRule R>
inline float wide_coverage(std::int64_t s) {
  constexpr std::int64_t one = kWideOne;
  std::int64_t c = rule_coverage_units<R>(s, one);
  c = c <= kWideSnapUnits ? 0 : c >= one - kWideSnapUnits ? one : c;
  return static_cast<float>(static_cast<std::int32_t>(c >> kWideFloatShift)) * 0x1p-24f;
}

/// A fixed-point or wide cell's running sum as coverage under R.
template <FillRule R, class Cell>
inline float integer_cell_coverage(Cell s) {
  if constexpr (std::is_same_v<Cell, std::int64_t>) {
    return wide_coverage<R>(s);
  } else {
    return fixed_coverage<R>(s);
  }
}

/// cells[0, n) -> cov[0, n) under R from the running sum `sum` (left past them); zeroes the cells (fixed-point or
/// wide cells).
template <FillRule R, class Cell>
inline void sweep_fixed_cells_scalar(Cell* cells, float* cov, int n, Cell& sum) {
  for (int i = 0; i < n; ++i) {
    sum += cells[i];
    cells[i] = 0;
    cov[i] = integer_cell_coverage<R>(sum);
  }
}


#ifdef VRASTER_HAVE_AVX2_KERNELS
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i unsnapped_coverage_units_avx2(__m256i s) {
  const __m256i one = _mm256_set1_epi32(kFixedOne), zero = _mm256_setzero_si256();
  if constexpr (R == FillRule::EvenOdd) {
    const __m256i w = _mm256_and_si256(s, _mm256_set1_epi32(2 * kFixedOne - 1));
    return _mm256_min_epi32(w, _mm256_sub_epi32(_mm256_set1_epi32(2 * kFixedOne), w));
  } else if constexpr (R == FillRule::Positive) {
    return _mm256_min_epi32(_mm256_max_epi32(s, zero), one);
  } else if constexpr (R == FillRule::Negative) {
    return _mm256_min_epi32(_mm256_max_epi32(_mm256_sub_epi32(zero, s), zero), one);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return _mm256_min_epi32(_mm256_max_epi32(_mm256_sub_epi32(_mm256_abs_epi32(s), one), zero), one);
  } else {
    return _mm256_min_epi32(_mm256_abs_epi32(s), one);
  }
}

// fixed_coverage_units eight lanes at a time.
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i fixed_coverage_units_avx2(__m256i s) {
  const __m256i c = unsnapped_coverage_units_avx2<R>(s);
  const __m256i above = _mm256_and_si256(c, _mm256_cmpgt_epi32(c, _mm256_set1_epi32(kFixedSnapUnits)));
  const __m256i near_one = _mm256_cmpgt_epi32(c, _mm256_set1_epi32(kFixedOne - kFixedSnapUnits - 1));
  return _mm256_blendv_epi8(above, _mm256_set1_epi32(kFixedOne), near_one);
}

/// Eight cells from the running sum in `carry` (all lanes) -> their eight coverages; the cells are zeroed. The sums
/// are exact, so this gives sweep_fixed_cells_scalar's floats. kSnap false: without the snap, for 8-bit pixels,
/// which round what it snaps to the same level (0 and 255).
template <FillRule R, bool kSnap = true>
[[gnu::target("avx2"), gnu::always_inline]] inline __m256 sweep_fixed_block_avx2(std::int32_t* cells, __m256i& carry) {
  auto* const p = reinterpret_cast<__m256i*>(cells);
  __m256i v = _mm256_loadu_si256(p);
  _mm256_storeu_si256(p, _mm256_setzero_si256());
  v = _mm256_add_epi32(v, _mm256_slli_si256(v, 4));  // running sums inside each half
  v = _mm256_add_epi32(v, _mm256_slli_si256(v, 8));
  const __m256i low = _mm256_permute2x128_si256(v, v, 0x08);  // [0 | low half]
  v = _mm256_add_epi32(v, _mm256_shuffle_epi32(low, 0xFF));   // the low half's total added to the high half
  const __m256i total = _mm256_permutevar8x32_epi32(v, _mm256_set1_epi32(7));
  const __m256i s = _mm256_add_epi32(v, carry);
  carry = _mm256_add_epi32(carry, total);  // one addition a block on the carried chain
  const __m256i units = kSnap ? fixed_coverage_units_avx2<R>(s) : unsnapped_coverage_units_avx2<R>(s);
  return _mm256_mul_ps(_mm256_cvtepi32_ps(units), _mm256_set1_ps(1.0f / static_cast<float>(kFixedOne)));
}

/// sweep_fixed_cells_scalar eight cells a step: reads and zeroes cells up to seven past n (which must be zero: a
/// row's untouched cells) and writes coverage up to seven past n.
template <FillRule R>
[[gnu::target("avx2")]] inline void sweep_fixed_cells_avx2(std::int32_t* cells, float* cov, int n, std::int32_t& sum) {
  __m256i carry = _mm256_set1_epi32(sum);
  for (int i = 0; i < n; i += kFixedBlock) _mm256_storeu_ps(cov + i, sweep_fixed_block_avx2<R>(cells + i, carry));
  sum = _mm256_cvtsi256_si32(carry);
}
#endif

#ifdef VRASTER_HAVE_AVX2_KERNELS
// Signed 64-bit minimum and maximum (AVX2 has only the comparison).
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i min_epi64(__m256i a, __m256i b) {
  return _mm256_blendv_epi8(a, b, _mm256_cmpgt_epi64(a, b));
}
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i max_epi64(__m256i a, __m256i b) {
  return _mm256_blendv_epi8(a, b, _mm256_cmpgt_epi64(b, a));
}
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i abs_epi64(__m256i s) {
  const __m256i negative = _mm256_cmpgt_epi64(_mm256_setzero_si256(), s);
  return _mm256_sub_epi64(_mm256_xor_si256(s, negative), negative);
}

// wide_coverage four lanes at a time, up to the shift: the snapped units (0 .. kWideOne).
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i wide_coverage_units_avx2(__m256i s) {
  const __m256i one = _mm256_set1_epi64x(kWideOne), zero = _mm256_setzero_si256();
  __m256i c;
  if constexpr (R == FillRule::EvenOdd) {
    const __m256i w = _mm256_and_si256(s, _mm256_set1_epi64x(2 * kWideOne - 1));
    c = min_epi64(w, _mm256_sub_epi64(_mm256_set1_epi64x(2 * kWideOne), w));
  } else if constexpr (R == FillRule::Positive) {
    c = min_epi64(max_epi64(s, zero), one);
  } else if constexpr (R == FillRule::Negative) {
    c = min_epi64(max_epi64(_mm256_sub_epi64(zero, s), zero), one);
  } else if constexpr (R == FillRule::AbsGeq2) {
    c = min_epi64(max_epi64(_mm256_sub_epi64(abs_epi64(s), one), zero), one);
  } else {
    c = min_epi64(abs_epi64(s), one);
  }
  const __m256i above = _mm256_and_si256(c, _mm256_cmpgt_epi64(c, _mm256_set1_epi64x(kWideSnapUnits)));
  const __m256i near_one = _mm256_cmpgt_epi64(above, _mm256_set1_epi64x(kWideOne - kWideSnapUnits - 1));
  return _mm256_blendv_epi8(above, one, near_one);
}

/// sweep_fixed_cells_scalar on wide cells, four a step (the same floats: integer sums are exact in any order):
/// reads and zeroes cells up to three past n (which must be zero: a row's untouched cells) and writes coverage up to
/// three past n.
template <FillRule R>
[[gnu::target("avx2")]] inline void sweep_wide_cells_avx2(std::int64_t* cells, float* cov, int n, std::int64_t& sum) {
  __m256i carry = _mm256_set1_epi64x(sum);
  const __m256i low_dwords = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
  for (int i = 0; i < n; i += 4) {
    auto* const p = reinterpret_cast<__m256i*>(cells + i);
    __m256i v = _mm256_loadu_si256(p);
    _mm256_storeu_si256(p, _mm256_setzero_si256());
    v = _mm256_add_epi64(v, _mm256_slli_si256(v, 8));            // running sums inside each half
    const __m256i low = _mm256_permute2x128_si256(v, v, 0x08);  // [0 | low half]
    v = _mm256_add_epi64(v, _mm256_shuffle_epi32(low, 0xEE));   // the low half's total added to the high half
    const __m256i total = _mm256_permute4x64_epi64(v, 0xFF);
    const __m256i units = wide_coverage_units_avx2<R>(_mm256_add_epi64(v, carry));
    carry = _mm256_add_epi64(carry, total);
    const __m256i levels = _mm256_permutevar8x32_epi32(_mm256_srli_epi64(units, kWideFloatShift), low_dwords);
    _mm_storeu_ps(cov + i, _mm_mul_ps(_mm_cvtepi32_ps(_mm256_castsi256_si128(levels)), _mm_set1_ps(0x1p-24f)));
  }
  sum = _mm256_extract_epi64(carry, 0);
}
#endif

/// The sweep of a run of fixed-point or wide cells picked at compile time (kAvx2: the caller was chosen per fill
/// already).
template <FillRule R, bool kAvx2, class Cell>
[[gnu::always_inline]] inline void sweep_fixed_cells(Cell* cells, float* cov, int n, Cell& sum) {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if constexpr (kAvx2 && std::is_same_v<Cell, std::int64_t>) return sweep_wide_cells_avx2<R>(cells, cov, n, sum);
  if constexpr (kAvx2 && std::is_same_v<Cell, std::int32_t>) return sweep_fixed_cells_avx2<R>(cells, cov, n, sum);
#endif
  sweep_fixed_cells_scalar<R>(cells, cov, n, sum);
}

}  // namespace vraster::detail
