#include "support/capture.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

namespace vraster::test {

CoverageGrid::CoverageGrid(int width, int height)
    : width_(width), height_(height), cells_(static_cast<std::size_t>(width) * height, 0.f) {}

void CoverageGrid::check(int y, int x0, int x1) {
  char buf[160];
  if (y < 0 || y >= height_ || x0 < 0 || x1 > width_ || x0 >= x1) {
    std::snprintf(buf, sizeof buf, "span out of range: y=%d x=[%d,%d)", y, x0, x1);
    violations_.push_back(buf);
    return;
  }
  if (y < last_y_ || (y == last_y_ && x0 < last_x_)) {
    std::snprintf(buf, sizeof buf, "span out of order: y=%d x0=%d after y=%d x=%d", y, x0, last_y_, last_x_);
    violations_.push_back(buf);
  }
  last_y_ = y;
  last_x_ = x1;
}

void CoverageGrid::span(int y, int x0, int x1, float coverage) {
  check(y, x0, x1);
  if (!(coverage > 0.f && coverage <= 1.f)) violations_.push_back("span coverage outside (0, 1]");
  if (y < 0 || y >= height_) return;
  for (int x = std::max(x0, 0); x < std::min(x1, width_); ++x) cells_[static_cast<std::size_t>(y) * width_ + x] += coverage;
}

void CoverageGrid::row(int y, int x0, int x1, const float* coverage) {
  check(y, x0, x1);
  if (y < 0 || y >= height_) return;
  for (int x = std::max(x0, 0); x < std::min(x1, width_); ++x) {
    const float c = coverage[x - x0];
    if (!(c >= 0.f && c <= 1.f)) violations_.push_back("row coverage outside [0, 1]");
    cells_[static_cast<std::size_t>(y) * width_ + x] += c;
  }
}

double CoverageGrid::total() const {
  double t = 0;
  for (float c : cells_) t += c;
  return t;
}

std::string CoverageGrid::to_string() const {
  std::ostringstream out;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "%4.0f", at(x, y) * 100.0);
      out << buf;
    }
    out << "\n";
  }
  return out.str();
}

CoverageGrid rasterize(const Path& path, FillRule rule, AntiAlias aa, int width, int height, double tol) {
  Polylines lines;
  FlattenOptions options;
  options.tolerance = tol;
  flatten(path, Affine{}, options, lines);
  CoverageGrid grid(width, height);
  Rasterizer r;
  r.fill(lines, rule, aa, width, height, grid);
  return grid;
}

CoverageGrid row_sweep_grid(const Polylines& lines, FillRule rule, int width, int height, bool fixed_cells) {
  CoverageGrid grid(width, height);
  Rasterizer r;
  r.set_dense_limit(0);
  r.set_fixed_cells(fixed_cells);
  r.fill(lines, rule, AntiAlias::Analytic, width, height, grid);
  EXPECT_TRUE(grid.violations().empty()) << grid.violations().front();
  return grid;
}

std::vector<std::vector<double>> parse_grid(const std::string& text) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::vector<double> row;
    std::string cell;
    while (cells >> cell) {
      const auto slash = cell.find('/');
      row.push_back(slash == std::string::npos ? std::stod(cell)
                                               : std::stod(cell.substr(0, slash)) / std::stod(cell.substr(slash + 1)));
    }
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

}  // namespace vraster::test
