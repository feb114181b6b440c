// Point-sampled antialiasing: regular supersampling (SSAA, N x N samples) and sparse multisampling (MSAA, N
// samples in an n-rooks pattern). Both are the aliased sweep run at sub-sample rows; a pixel's coverage is the
// share of its samples inside the fill rule.
#pragma once

#include <span>
#include <vector>

#include "vraster/raster.hpp"

namespace vraster::detail {

/// The sample layout of a point-sampled mode: `grid` sub-rows (and columns) per pixel; `sparse` means one sample
/// per sub-row at column permutation()[row] (MSAA), otherwise every column (SSAA, grid x grid samples).
struct SamplePattern {
  int grid = 0;
  bool sparse = false;
  /// Sparse patterns: the column of the sample in each sub-row (a permutation of 0 .. grid-1).
  std::span<const int> permutation() const;
  int samples() const { return sparse ? grid : grid * grid; }
};

/// The pattern of `aa`, or grid == 0 when `aa` is not a point-sampled mode.
SamplePattern sample_pattern(AntiAlias aa);

/// Sweeps `edges` (clipped to [0, width] x [0, height], rows [y_min, y_max) touched) at the pattern's sample
/// positions and hands the per-pixel share of samples inside `rule` to `sink`. `rule` must be a winding rule
/// (NonExterior is turned into boundary pieces + NonZero before this).
void sweep_sampled(const std::vector<Edge>& edges, int y_min, int y_max, FillRule rule, SamplePattern pattern,
                   int width, CoverageSink& sink);

}  // namespace vraster::detail
