// 8-bit coverage masks for small analytic fills (glyphs).
//
//   1. bounds:  one pass over the points; anything outside the mask (beyond round-off) goes to the general sweep
//   2. walk:    every segment adds its pieces, row by row, to a block of float cells (no edge structs, no table)
//   3. resolve: per row, one pass: running sum (4 cells at a time), coverage under the rule, byte, cells back to 0
#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

// SSE2 is part of x86-64; other targets take the portable scalar row pass (-DVRASTER_MASK_SCALAR forces it, to
// check it by hand on x86-64: no test build sets it).
#if (defined(__SSE2__) || defined(_M_X64)) && !defined(VRASTER_MASK_SCALAR)
#include <emmintrin.h>
#define VRASTER_MASK_SSE2 1
#endif

#include "raster/cells.hpp"
#include "geometry/point_bounds.hpp"
#include "vraster/error.hpp"
#include "raster/rasterizer_p.hpp"
#include "vraster/raster.hpp"

namespace vraster {
namespace {

// Points up to this far outside the mask are moved onto its border: the round-off of a caller's transform
// (glyph boxes are computed from the same points), far below one coverage level.
constexpr double kBorderSlack = 1e-6;

// Cells per row are padded to a multiple of this, so the row pass needs no scalar tail for the cells.
constexpr int kCellBlock = 8;

inline std::uint8_t to_byte(float coverage) {
  return static_cast<std::uint8_t>(static_cast<std::uint32_t>(coverage * 255.f + 0.5f));
}

// Adds one piece of a segment inside a row: it runs from x = xa to x = xb (either order) and covers height h of
// the row (signed by direction). The same split as the row sweep's accumulate_piece (sweep.cpp): cell i gets h
// times the share of the cell right of the piece, cell i + 1 the rest; the running sum of a row is then each
// pixel's signed area. Geometry is in double (exact cell fractions), only the cells are float.
inline void add_piece(float* cells, double xa, double xb, double h) {
  if (xa > xb) std::swap(xa, xb);
  const int i0 = static_cast<int>(xa);  // x >= 0: truncation is floor
  const int i1 = static_cast<int>(xb);
  if (i0 == i1) {
    const double right = h * (0.5 * (xa + xb) - i0);
    cells[i0] += static_cast<float>(h - right);
    cells[i0 + 1] += static_cast<float>(right);
    return;
  }
  const double per_x = h / (xb - xa);
  // First, partial cell: the piece covers f0 of its width, at mean x 1 - f0 / 2.
  const double f0 = (i0 + 1) - xa;
  const double h0 = per_x * f0;
  const double right0 = h0 * (1.0 - 0.5 * f0);
  cells[i0] += static_cast<float>(h0 - right0);
  cells[i0 + 1] += static_cast<float>(right0);
  // Whole cells: the piece crosses each at mean x 0.5.
  const auto half = static_cast<float>(0.5 * per_x);
  for (int i = i0 + 1; i < i1; ++i) {
    cells[i] += half;
    cells[i + 1] += half;
  }
  // Last, partial cell.
  const double f1 = xb - i1;
  if (f1 > 0) {
    const double h1 = per_x * f1;
    const double right1 = h1 * (0.5 * f1);
    cells[i1] += static_cast<float>(h1 - right1);
    cells[i1 + 1] += static_cast<float>(right1);
  }
}

// Adds segment p -> q (both inside [0, width] x [0, height]) to the block whose first row is `row0`.
inline void add_segment(float* block, std::ptrdiff_t stride, int row0, Point p, Point q) {
  if (p.y == q.y) return;  // horizontal: no area
  double dir = 1;
  if (p.y > q.y) {
    std::swap(p, q);
    dir = -1;
  }
  const int first = static_cast<int>(p.y);  // y >= 0: truncation is floor
  const int last_floor = static_cast<int>(q.y);
  const int end = last_floor + (last_floor < q.y ? 1 : 0);  // rows [first, end)
  float* row = block + (first - row0) * stride;
  if (end - first == 1) return add_piece(row, p.x, q.x, (q.y - p.y) * dir);
  if (p.x == q.x) {
    // Vertical (glyph stems): the same two cells in every row, in shares that do not change.
    const int i = static_cast<int>(p.x);
    const double right_share = p.x - i;
    const auto whole_left = static_cast<float>(dir * (1.0 - right_share));
    const auto whole_right = static_cast<float>(dir * right_share);
    for (int y = first; y < end; ++y, row += stride) {
      if (y == first || y + 1 == end) {
        const double h = (std::min(y + 1.0, q.y) - std::max(static_cast<double>(y), p.y)) * dir;
        row[i] += static_cast<float>(h * (1.0 - right_share));
        row[i + 1] += static_cast<float>(h * right_share);
      } else {
        row[i] += whole_left;
        row[i + 1] += whole_right;
      }
    }
    return;
  }
  const double dxdy = (q.x - p.x) / (q.y - p.y);
  const double lo = std::min(p.x, q.x), hi = std::max(p.x, q.x);
  double ya = p.y, xa = p.x;
  for (int y = first; y < end; ++y, row += stride) {
    const double yb = std::min(y + 1.0, q.y);
    // x at the row's bottom, kept inside the segment's x range so round-off never leaves it.
    const double xb = yb == q.y ? q.x : std::clamp(p.x + (yb - p.y) * dxdy, lo, hi);
    add_piece(row, xa, xb, (yb - ya) * dir);
    ya = yb;
    xa = xb;
  }
}

// Coverage from the signed area s, per rule (the values of coverage_of in sweep.cpp, without its snapping, which
// 8-bit rounding makes moot).
template <FillRule R>
inline float coverage_scalar(float s) {
  if constexpr (R == FillRule::EvenOdd) {
    float a = std::abs(s);
    a -= 2.0f * static_cast<float>(static_cast<int>(a * 0.5f));
    return 1.0f - std::abs(a - 1.0f);
  } else if constexpr (R == FillRule::Positive) {
    return std::clamp(s, 0.0f, 1.0f);
  } else if constexpr (R == FillRule::Negative) {
    return std::clamp(-s, 0.0f, 1.0f);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return std::clamp(std::abs(s) - 1.0f, 0.0f, 1.0f);
  } else {
    return std::min(std::abs(s), 1.0f);
  }
}

#if VRASTER_MASK_SSE2
template <FillRule R>
inline __m128 coverage4(__m128 s) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 sign = _mm_set1_ps(-0.0f);
  if constexpr (R == FillRule::EvenOdd) {
    __m128 a = _mm_andnot_ps(sign, s);
    // a - 2 floor(a / 2): truncation is floor for a >= 0.
    const __m128 halves = _mm_cvtepi32_ps(_mm_cvttps_epi32(_mm_mul_ps(a, _mm_set1_ps(0.5f))));
    a = _mm_sub_ps(a, _mm_add_ps(halves, halves));
    return _mm_sub_ps(one, _mm_andnot_ps(sign, _mm_sub_ps(a, one)));
  } else if constexpr (R == FillRule::Positive) {
    return _mm_min_ps(_mm_max_ps(s, zero), one);
  } else if constexpr (R == FillRule::Negative) {
    return _mm_min_ps(_mm_max_ps(_mm_sub_ps(zero, s), zero), one);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return _mm_min_ps(_mm_max_ps(_mm_sub_ps(_mm_andnot_ps(sign, s), one), zero), one);
  } else {
    return _mm_min_ps(_mm_andnot_ps(sign, s), one);
  }
}

// Running sum inside four cells: (a, b, c, d) -> (a, a+b, a+b+c, a+b+c+d).
inline __m128 prefix4(__m128 v) {
  v = _mm_add_ps(v, _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(v), 4)));
  return _mm_add_ps(v, _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(v), 8)));
}

// Eight cells -> eight bytes (coverage under R, rounded as to_byte rounds); the cells are set back to 0.
template <FillRule R>
inline __m128i resolve8(float* cells, __m128& carry) {
  const __m128 scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f);
  __m128 lo = prefix4(_mm_loadu_ps(cells));
  __m128 hi = prefix4(_mm_loadu_ps(cells + 4));
  hi = _mm_add_ps(hi, _mm_shuffle_ps(lo, lo, _MM_SHUFFLE(3, 3, 3, 3)));
  lo = _mm_add_ps(lo, carry);
  hi = _mm_add_ps(hi, carry);
  carry = _mm_shuffle_ps(hi, hi, _MM_SHUFFLE(3, 3, 3, 3));
  _mm_storeu_ps(cells, _mm_setzero_ps());
  _mm_storeu_ps(cells + 4, _mm_setzero_ps());
  const __m128i a = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(coverage4<R>(lo), scale), half));
  const __m128i b = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(coverage4<R>(hi), scale), half));
  const __m128i words = _mm_packs_epi32(a, b);
  return _mm_packus_epi16(words, words);
}
#endif

// Copies n < 8 bytes in fixed-size pieces (a memcpy of variable length is a library call per row).
inline void copy_short(std::uint8_t* out, const std::uint8_t* in, int n) {
  if (n & 4) {
    std::memcpy(out, in, 4);
    out += 4;
    in += 4;
  }
  if (n & 2) {
    std::memcpy(out, in, 2);
    out += 2;
    in += 2;
  }
  if (n & 1) *out = *in;
}

// One row of cells (padded to a multiple of kCellBlock, at least width + 2) -> width bytes; the cells end zero.
template <FillRule R>
void resolve_row(float* cells, int padded, int width, std::uint8_t* out) {
#if VRASTER_MASK_SSE2
  __m128 carry = _mm_setzero_ps();
  int c = 0;
  for (; c + kCellBlock <= width; c += kCellBlock) {
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + c), resolve8<R>(cells + c, carry));
  }
  if (c < width) {
    alignas(16) std::uint8_t tail[16];
    _mm_storel_epi64(reinterpret_cast<__m128i*>(tail), resolve8<R>(cells + c, carry));
    copy_short(out + c, tail, width - c);
    c += kCellBlock;
  }
  // The cells past the last pixel (an edge at x = width writes cell width + 1) only need clearing.
  for (; c < padded; c += 4) _mm_storeu_ps(cells + c, _mm_setzero_ps());
#else
  float sum = 0;
  for (int c = 0; c < width; ++c) {
    sum += cells[c];
    out[c] = to_byte(coverage_scalar<R>(sum));
  }
  std::fill(cells, cells + padded, 0.0f);
#endif
}

template <FillRule R>
void resolve_rows(float* block, int padded, int rows, int width, std::uint8_t* out, std::ptrdiff_t stride) {
  for (int r = 0; r < rows; ++r) {
    resolve_row<R>(block + static_cast<std::ptrdiff_t>(r) * padded, padded, width, out + r * stride);
  }
}

#if VRASTER_MASK_SSE2 && defined(VRASTER_HAVE_AVX2_KERNELS)
// The row pass eight cells a step in one AVX2 register (picked at run time), with resolve8's additions in resolve8's
// order: each half's running sum, the low half's total added to the high half, then the carry. So the same floats
// and the same bytes; about a third fewer instructions a step (a fifth of a 64 px glyph's time is this pass).
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline __m256 coverage8(__m256 s) {
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 sign = _mm256_set1_ps(-0.0f);
  if constexpr (R == FillRule::EvenOdd) {
    __m256 a = _mm256_andnot_ps(sign, s);
    const __m256 halves = _mm256_cvtepi32_ps(_mm256_cvttps_epi32(_mm256_mul_ps(a, _mm256_set1_ps(0.5f))));
    a = _mm256_sub_ps(a, _mm256_add_ps(halves, halves));
    return _mm256_sub_ps(one, _mm256_andnot_ps(sign, _mm256_sub_ps(a, one)));
  } else if constexpr (R == FillRule::Positive) {
    return _mm256_min_ps(_mm256_max_ps(s, zero), one);
  } else if constexpr (R == FillRule::Negative) {
    return _mm256_min_ps(_mm256_max_ps(_mm256_sub_ps(zero, s), zero), one);
  } else if constexpr (R == FillRule::AbsGeq2) {
    return _mm256_min_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_andnot_ps(sign, s), one), zero), one);
  } else {
    return _mm256_min_ps(_mm256_andnot_ps(sign, s), one);
  }
}

// Eight cells -> eight bytes, as resolve8; the cells are set back to 0.
template <FillRule R>
[[gnu::target("avx2"), gnu::always_inline]] inline __m128i resolve8_avx2(float* cells, __m256& carry) {
  __m256 v = _mm256_loadu_ps(cells);
  // prefix4 in each half, then the low half's last sum broadcast into the high half (zero in the low half).
  v = _mm256_add_ps(v, _mm256_castsi256_ps(_mm256_slli_si256(_mm256_castps_si256(v), 4)));
  v = _mm256_add_ps(v, _mm256_castsi256_ps(_mm256_slli_si256(_mm256_castps_si256(v), 8)));
  const __m256 low_total = _mm256_permute2f128_ps(v, v, 0x08);  // [0 | low half]
  v = _mm256_blend_ps(v, _mm256_add_ps(v, _mm256_shuffle_ps(low_total, low_total, _MM_SHUFFLE(3, 3, 3, 3))), 0xF0);
  v = _mm256_add_ps(v, carry);
  carry = _mm256_permutevar8x32_ps(v, _mm256_set1_epi32(7));
  _mm256_storeu_ps(cells, _mm256_setzero_ps());
  const __m256i levels = _mm256_cvttps_epi32(
      _mm256_add_ps(_mm256_mul_ps(coverage8<R>(v), _mm256_set1_ps(255.0f)), _mm256_set1_ps(0.5f)));
  const __m128i words = _mm_packs_epi32(_mm256_castsi256_si128(levels), _mm256_extracti128_si256(levels, 1));
  return _mm_packus_epi16(words, words);
}

template <FillRule R>
[[gnu::target("avx2")]] void resolve_rows_avx2(float* block, int padded, int rows, int width, std::uint8_t* out,
                                                std::ptrdiff_t stride) {
  for (int r = 0; r < rows; ++r, out += stride) {
    float* cells = block + static_cast<std::ptrdiff_t>(r) * padded;
    __m256 carry = _mm256_setzero_ps();
    int c = 0;
    for (; c + kCellBlock <= width; c += kCellBlock) {
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out + c), resolve8_avx2<R>(cells + c, carry));
    }
    if (c < width) {
      alignas(16) std::uint8_t tail[16];
      _mm_storel_epi64(reinterpret_cast<__m128i*>(tail), resolve8_avx2<R>(cells + c, carry));
      copy_short(out + c, tail, width - c);
      c += kCellBlock;
    }
    for (; c < padded; c += kCellBlock) _mm256_storeu_ps(cells + c, _mm256_setzero_ps());
  }
}
#endif

// The general sweep's coverage into bytes (paths reaching outside the mask, NonExterior, huge masks).
class ByteMaskSink final : public CoverageSink {
 public:
  ByteMaskSink(std::uint8_t* mask, std::ptrdiff_t stride) : mask_(mask), stride_(stride) {}
  void span(int y, int x0, int x1, float coverage) override {
    std::memset(mask_ + y * stride_ + x0, to_byte(coverage), static_cast<std::size_t>(x1 - x0));
  }
  void row(int y, int x0, int x1, const float* coverage) override {
    std::uint8_t* out = mask_ + y * stride_ + x0;
    for (int i = 0; i < x1 - x0; ++i) out[i] = to_byte(coverage[i]);
  }

 private:
  std::uint8_t* mask_;
  std::ptrdiff_t stride_;
};

void clear_rows(std::uint8_t* mask, std::ptrdiff_t stride, int width, int from, int to) {
  for (int y = from; y < to; ++y) std::memset(mask + y * stride, 0, static_cast<std::size_t>(width));
}

}  // namespace

void detail::RasterizerImpl::fill_mask(const Polylines& lines, FillRule rule, int width, int height,
                                       std::uint8_t* mask, std::ptrdiff_t stride) {
  if (width <= 0 || height <= 0) return;
  if (!mask) throw Error("fill_mask: the mask is null");
  if (stride < width) throw Error("fill_mask: the stride is smaller than the width");
  // Bounds of the points: rows to resolve, and whether everything lies inside the mask.
  const auto [x_lo, x_hi, y_lo, y_hi, finite] = detail::point_bounds(lines.points);
  const double w = width, h = height;
  // Not finite: the general sweep, which skips the contours with a NaN or infinite point.
  const bool inside = finite && x_lo >= -kBorderSlack && y_lo >= -kBorderSlack && x_hi <= w + kBorderSlack &&
                      y_hi <= h + kBorderSlack;
  // Cells per row: every cell a segment can write (x = width writes cell width + 1), padded to whole blocks.
  const std::int64_t padded_cells = (std::int64_t{width} + 2 + kCellBlock - 1) / kCellBlock * kCellBlock;
  const int row_lo = inside ? static_cast<int>(std::max(y_lo, 0.0)) : 0;
  const int row_hi = inside ? static_cast<int>(std::ceil(std::min(y_hi, h))) : 0;
  const std::int64_t cells = padded_cells * (row_hi - row_lo);
  if (!inside || rule == FillRule::NonExterior || cells > Rasterizer::kMaskBlockLimit) {
    clear_rows(mask, stride, width, 0, height);
    ByteMaskSink sink(mask, stride);
    fill(lines, rule, AntiAlias::Analytic, width, height, sink);
    return;
  }
  clear_rows(mask, stride, width, 0, row_lo);
  clear_rows(mask, stride, width, row_hi, height);
  if (row_hi <= row_lo) return;
  if (mask_cells_.size() < static_cast<std::size_t>(cells)) mask_cells_.assign(static_cast<std::size_t>(cells), 0.0f);
  float* block = mask_cells_.data();
  const int padded = static_cast<int>(padded_cells);  // <= kMaskBlockLimit
  const bool on_border = x_lo < 0 || y_lo < 0 || x_hi > w || y_hi > h;
  lines.for_each_segment([&](Point p, Point q) {
    if (on_border) [[unlikely]] {
      p = {std::clamp(p.x, 0.0, w), std::clamp(p.y, 0.0, h)};
      q = {std::clamp(q.x, 0.0, w), std::clamp(q.y, 0.0, h)};
    }
    add_segment(block, padded, row_lo, p, q);
  });
  std::uint8_t* out = mask + row_lo * stride;
  const int rows = row_hi - row_lo;
  detail::with_rule(rule, [&](auto r) {
#if VRASTER_MASK_SSE2 && defined(VRASTER_HAVE_AVX2_KERNELS)
    if (detail::cpu_has_avx2()) return resolve_rows_avx2<decltype(r)::value>(block, padded, rows, width, out, stride);
#endif
    resolve_rows<decltype(r)::value>(block, padded, rows, width, out, stride);
  });
}

}  // namespace vraster
