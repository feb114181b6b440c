// Test support: capturing the rasterizer's coverage as a float grid.
#pragma once

#include <string>
#include <vector>

#include "vraster/vraster.hpp"

namespace vraster::test {

/// A CoverageSink that records coverage per pixel (floats, before any 8-bit rounding) and checks the sink
/// contract as it goes (rows in order, x increasing and inside the grid, coverage in (0, 1]).
class CoverageGrid final : public CoverageSink {
 public:
  CoverageGrid(int width, int height);
  void span(int y, int x0, int x1, float coverage) override;
  void row(int y, int x0, int x1, const float* coverage) override;

  int width() const { return width_; }
  int height() const { return height_; }
  float at(int x, int y) const { return cells_[static_cast<std::size_t>(y) * width_ + x]; }
  double total() const;
  /// Contract violations seen so far (empty when none).
  const std::vector<std::string>& violations() const { return violations_; }
  /// The grid as text, one row per line, coverage in hundredths (for failure messages).
  std::string to_string() const;

 private:
  void check(int y, int x0, int x1);
  int width_, height_;
  std::vector<float> cells_;
  int last_y_ = -1, last_x_ = 0;
  std::vector<std::string> violations_;
};

/// Flattens `path` (identity transform, tolerance `tol`) and rasterizes it into a fresh grid.
CoverageGrid rasterize(const Path& path, FillRule rule, AntiAlias aa, int width, int height, double tol = 0.01);

/// The row sweep's coverage of `lines` in a fresh grid, whatever their box (no dense sweep); fixed_cells false: every
/// row in double cells (Rasterizer::set_fixed_cells). Expects the sink's contract kept.
CoverageGrid row_sweep_grid(const Polylines& lines, FillRule rule, int width, int height, bool fixed_cells = true);

/// Parses a grid written as text: rows separated by newlines, cells by spaces; each cell a number
/// (e.g. "1", "0.5", ".25", "0") or a fraction ("5/6"). Used for hand-made expected coverage.
std::vector<std::vector<double>> parse_grid(const std::string& text);

}  // namespace vraster::test
