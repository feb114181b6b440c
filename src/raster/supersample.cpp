// Point-sampled antialiasing (SSAA-N, MSAA-N): the aliased scanline sweep, run at N sub-rows per pixel row.
//
//   per pixel row y:
//     add the edges starting in the row to the active list
//     per sub-row j (sample line ys = y + (j + 0.5) / N):
//       crossings of the active edges with y0 <= ys < y1 (half-open: a vertex on a sample line counts once,
//       horizontal edges never), sorted by x; walk them summing the winding; every stretch [xa, xb) where the rule
//       holds adds the samples of the sub-row with xa <= sample x < xb to the pixels' counts
//         SSAA: samples at x = p + (i + 0.5) / N for i = 0 .. N-1
//         MSAA: one sample at x = p + (perm[j] + 0.5) / N
//     coverage = count / samples per pixel, emitted as spans (long constant runs) and rows (the rest)
//
// Counts go into a difference array (one add at each end of a stretch), so a stretch costs O(1) however wide;
// the prefix sum at the end of the row turns them into counts. Everything per row is O(edges + touched pixels).
//
// Scratch buffers are per thread (thread_local) and reused: no allocation in steady state (the Rasterizer's own
// buffers are in raster/rasterizer_p.hpp).
#include "raster/supersample.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace vraster::detail {
namespace {

// n-rooks patterns: the sample of sub-row j is in column perm[j]. These are the Direct3D 10.1 standard
// multisample patterns for 4, 8 and 16 samples (the 16x pattern, defined on a 1/16 grid of corners, is moved to
// cell centres here, i.e. by 1/32 px).
constexpr std::array<int, 4> kPerm4{1, 3, 0, 2};
constexpr std::array<int, 8> kPerm8{7, 2, 4, 0, 6, 3, 1, 5};
constexpr std::array<int, 16> kPerm16{1, 8, 4, 11, 15, 7, 3, 12, 0, 9, 5, 13, 2, 10, 6, 14};


struct Crossing {
  double x;
  std::uint32_t edge;
};

struct Scratch {
  std::vector<std::uint32_t> bucket_start, order, active, pending;
  std::vector<Crossing> crossings;
  std::vector<std::int32_t> diff;  // width + 2 cells, zero between rows
  std::vector<float> coverage;     // width cells
};

// Runs of one coverage at least this long become a span of their own; shorter ones go into a row() call.
constexpr int kSpanMin = 8;

void emit_row(int y, int x0, int n, const float* cov, CoverageSink& sink) {
  int i = 0;
  while (i < n) {
    if (cov[i] == 0) {
      ++i;
      continue;
    }
    int j = i + 1;
    while (j < n && cov[j] == cov[i]) ++j;
    if (j - i >= kSpanMin) {
      sink.span(y, x0 + i, x0 + j, cov[i]);
      i = j;
      continue;
    }
    // A mixed stretch: up to the next long constant run (or long zero run).
    const int start = i;
    int k = j;
    while (k < n) {
      int r = k + 1;
      while (r < n && cov[r] == cov[k]) ++r;
      if (r - k >= kSpanMin) break;
      k = r;
    }
    int end = k;
    while (end > start && cov[end - 1] == 0) --end;
    if (end - start == 1) {
      sink.span(y, x0 + start, x0 + end, cov[start]);
    } else {
      sink.row(y, x0 + start, x0 + end, cov + start);
    }
    i = k;
  }
}

template <bool Sparse>
void sweep(const std::vector<Edge>& edges, int y_min, int y_max, FillRule rule, int n, const int* perm, int width,
           CoverageSink& sink, Scratch& s) {
  // Edge table: counting sort by the pixel row of the edge's top.
  const int rows = y_max - y_min;
  s.bucket_start.assign(static_cast<std::size_t>(rows) + 1, 0);
  auto first_row = [&](const Edge& e) {
    return std::clamp(static_cast<int>(std::floor(e.y0)), y_min, y_max - 1) - y_min;
  };
  for (const Edge& e : edges) ++s.bucket_start[first_row(e) + 1];
  for (int r = 0; r < rows; ++r) s.bucket_start[r + 1] += s.bucket_start[r];
  s.order.resize(edges.size());
  {
    // Fill by a running cursor per bucket (reuse `active` as the cursors).
    s.active.assign(s.bucket_start.begin(), s.bucket_start.end() - 1);
    for (std::uint32_t i = 0; i < edges.size(); ++i) s.order[s.active[first_row(edges[i])]++] = i;
  }
  s.active.clear();
  if (s.diff.size() < static_cast<std::size_t>(width) + 2) s.diff.assign(static_cast<std::size_t>(width) + 2, 0);
  if (s.coverage.size() < static_cast<std::size_t>(width)) s.coverage.resize(static_cast<std::size_t>(width));
  std::int32_t* diff = s.diff.data();
  const double inv_n = 1.0 / n;
  const std::int64_t sample_limit = static_cast<std::int64_t>(width) * n;  // SSAA: sample columns [0, width * n)
  const float per_sample = 1.0f / static_cast<float>(Sparse ? n : n * n);  // n is a power of 2: exact

  for (int y = y_min; y < y_max; ++y) {
    const int r = y - y_min;
    for (std::uint32_t k = s.bucket_start[r]; k < s.bucket_start[r + 1]; ++k) s.active.push_back(s.order[k]);
    if (s.active.empty()) continue;
    int x_lo = width + 1, x_hi = -1;  // diff cells touched in this row, inclusive
    for (int j = 0; j < n; ++j) {
      const double ys = y + (j + 0.5) * inv_n;
      // Crossings of this sub-row; edges that end above it are retired, edges that start below it wait.
      s.crossings.clear();
      s.pending.clear();
      bool reorder = false;  // does the active list need rebuilding (retired edges, waiting ones out of place, sort)?
      for (const std::uint32_t id : s.active) {
        const Edge& e = edges[id];
        if (e.y1 <= ys) {
          reorder = true;
          continue;
        }
        if (e.y0 <= ys) {
          reorder = reorder || !s.pending.empty();
          s.crossings.push_back({e.x_at(ys), id});
        } else {
          s.pending.push_back(id);
        }
      }
      for (std::size_t i = 1; i < s.crossings.size(); ++i) {  // nearly sorted from the previous sub-row
        const Crossing c = s.crossings[i];
        std::size_t k = i;
        while (k > 0 && s.crossings[k - 1].x > c.x) {
          s.crossings[k] = s.crossings[k - 1];
          --k;
        }
        if (k != i) {
          s.crossings[k] = c;
          reorder = true;
        }
      }
      // Keep the active list in x order (the waiting edges after it): the next sub-row's sort is nearly free.
      if (reorder) {
        s.active.resize(s.crossings.size());
        for (std::size_t i = 0; i < s.crossings.size(); ++i) s.active[i] = s.crossings[i].edge;
        s.active.insert(s.active.end(), s.pending.begin(), s.pending.end());
      }
      if (s.crossings.empty()) continue;
      const double offset = Sparse ? (perm[j] + 0.5) * inv_n : 0.0;
      auto add = [&](double xa, double xb) {
        if constexpr (Sparse) {
          // Pixels p with xa <= p + offset < xb.
          const int p0 = static_cast<int>(std::clamp(std::ceil(xa - offset), 0.0, double(width)));
          const int p1 = static_cast<int>(std::clamp(std::ceil(xb - offset), 0.0, double(width)));
          if (p1 <= p0) return;
          diff[p0] += 1;
          diff[p1] -= 1;
          x_lo = std::min(x_lo, p0);
          x_hi = std::max(x_hi, p1);
        } else {
          // Sample columns c with xa <= (c + 0.5) / n < xb.
          const auto c0 = static_cast<std::int64_t>(
              std::clamp(std::ceil(xa * n - 0.5), 0.0, static_cast<double>(sample_limit)));
          const auto c1 = static_cast<std::int64_t>(
              std::clamp(std::ceil(xb * n - 0.5), 0.0, static_cast<double>(sample_limit)));
          if (c1 <= c0) return;
          const int p0 = static_cast<int>(c0 / n), p1 = static_cast<int>(c1 / n);
          const int r0 = static_cast<int>(c0 % n), r1 = static_cast<int>(c1 % n);
          // Pixel p gets clamp(c1 - p n, 0, n) - clamp(c0 - p n, 0, n).
          diff[p0] += n - r0;
          diff[p0 + 1] += r0;
          diff[p1] += r1 - n;
          diff[p1 + 1] -= r1;
          x_lo = std::min(x_lo, p0);
          x_hi = std::max(x_hi, p1 + 1);
        }
      };
      int w = 0;
      bool in = false;
      double start = 0;
      for (const Crossing& c : s.crossings) {
        w += edges[c.edge].winding;
        const bool now = winding_fills(rule, w);
        if (now == in) continue;
        if (now) {
          start = c.x;
        } else {
          add(start, c.x);
        }
        in = now;
      }
      // Still inside after the last crossing: the closing edges lie right of the image and were dropped.
      if (in) add(start, width);
    }
    // Retire the edges that no later sample line reaches.
    const double next_row = y + 1.0;
    std::size_t kept = 0;
    for (const std::uint32_t id : s.active) {
      if (edges[id].y1 > next_row) s.active[kept++] = id;
    }
    s.active.resize(kept);
    if (x_hi < x_lo) continue;
    // Prefix sum over the touched cells -> coverage; leaves the difference array zero.
    const int end = std::min(x_hi, width);  // pixels [x_lo, end); cells up to x_hi are cleared
    std::int32_t count = 0;
    float* cov = s.coverage.data();
    for (int x = x_lo; x < end; ++x) {
      count += diff[x];
      diff[x] = 0;
      cov[x - x_lo] = static_cast<float>(count) * per_sample;
    }
    for (int x = end; x <= x_hi; ++x) diff[x] = 0;
    emit_row(y, x_lo, end - x_lo, cov, sink);
  }
}

}  // namespace

std::span<const int> SamplePattern::permutation() const {
  switch (grid) {
    case 4: return kPerm4;
    case 8: return kPerm8;
    case 16: return kPerm16;
    default: return {};
  }
}

SamplePattern sample_pattern(AntiAlias aa) {
  switch (aa) {
    case AntiAlias::Ssaa2: return {2, false};
    case AntiAlias::Ssaa4: return {4, false};
    case AntiAlias::Ssaa8: return {8, false};
    case AntiAlias::Ssaa16: return {16, false};
    case AntiAlias::Msaa4: return {4, true};
    case AntiAlias::Msaa8: return {8, true};
    case AntiAlias::Msaa16: return {16, true};
    default: return {};
  }
}

void sweep_sampled(const std::vector<Edge>& edges, int y_min, int y_max, FillRule rule, SamplePattern pattern,
                   int width, CoverageSink& sink) {
  if (edges.empty() || y_max <= y_min || width <= 0 || pattern.grid <= 0) return;
  thread_local Scratch scratch;
  if (pattern.sparse) {
    sweep<true>(edges, y_min, y_max, rule, pattern.grid, pattern.permutation().data(), width, sink, scratch);
  } else {
    sweep<false>(edges, y_min, y_max, rule, pattern.grid, nullptr, width, sink, scratch);
  }
}

}  // namespace vraster::detail
