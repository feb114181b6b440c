// libFuzzer target: path -> flatten -> rasterizer, in every antialiasing mode and fill rule.
// Input layout: byte 0 picks the rule, byte 1 the mode (and a non-finite point, below), byte 2 a scale; then
// 9-byte records (verb, and four 16-bit signed coordinates) build the path. The sink checks the rasterizer's
// contract; in exact mode the coverage must not depend on whether the path took the unit-winding shortcut.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "vraster/vraster.hpp"

namespace {

constexpr int kSize = 48;

class CheckingSink final : public vraster::CoverageSink {
 public:
  void span(int y, int x0, int x1, float c) override {
    check(y, x0, x1);
    if (!(c > 0.f && c <= 1.f)) std::abort();
    for (int x = x0; x < x1; ++x) grid[y * kSize + x] = c;
  }
  void row(int y, int x0, int x1, const float* c) override {
    check(y, x0, x1);
    for (int i = 0; i < x1 - x0; ++i) {
      if (!(c[i] >= 0.f && c[i] <= 1.f)) std::abort();
      grid[y * kSize + x0 + i] = c[i];
    }
  }
  float grid[kSize * kSize] = {};

 private:
  void check(int y, int x0, int x1) {
    if (y < 0 || y >= kSize || x0 < 0 || x1 > kSize || x0 >= x1) std::abort();
    if (y < last_y_ || (y == last_y_ && x0 < last_x_)) std::abort();
    last_y_ = y;
    last_x_ = x1;
  }
  int last_y_ = -1, last_x_ = 0;
};

double coord(const std::uint8_t* p, double scale) {
  std::int16_t v;
  std::memcpy(&v, p, 2);
  return v * scale;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3 || size > 3 + 9 * 400) return 0;  // size cap keeps the exact sweep's O(n^2) crossings small
  const auto rule = static_cast<vraster::FillRule>(data[0] % 6);
  const auto aa = static_cast<vraster::AntiAlias>(data[1] % 3);
  // Scales from 1/4096 px per unit (tiny shapes) to 2^20 (far outside the canvas).
  const double scale = std::ldexp(1.0, static_cast<int>(data[2] % 33) - 12);
  vraster::Path path;
  for (std::size_t i = 3; i + 9 <= size; i += 9) {
    const std::uint8_t* r = data + i;
    const vraster::Point a{coord(r + 1, scale), coord(r + 3, scale)};
    const vraster::Point b{coord(r + 5, scale), coord(r + 7, scale)};
    switch (r[0] % 6) {
      case 0: path.move_to(a); break;
      case 1: path.line_to(a); break;
      case 2: path.quad_to(a, b); break;
      case 3: path.cubic_to(a, b, a + b * 0.5); break;
      case 4: path.arc_to(a.x, a.y, b.x, r[0] & 8, r[0] & 16, b); break;
      default: path.close(); break;
    }
  }
  vraster::Polylines lines;
  vraster::FlattenOptions options;
  options.tolerance = 0.25;
  const vraster::Rect clip{0, 0, kSize, kSize};
  options.clip = rule == vraster::FillRule::NonExterior ? nullptr : &clip;
  try {
    vraster::flatten(path, vraster::Affine{}, options, lines);
  } catch (const vraster::Error&) {
    return 0;  // e.g. non-finite arc results: rejected with a message, which is the contract
  }
  if (lines.points.size() > 200000) return 0;
  // Polylines built by hand may hold what flatten() refuses: bits 4-5 of byte 1 put a NaN or an infinity in place
  // of one point (picked by byte 2). The rasterizer must skip that contour, not crash.
  if (const int poison = (data[1] >> 4) & 3; poison != 0 && !lines.points.empty()) {
    const double bad = poison == 1   ? std::nan("")
                       : poison == 2 ? HUGE_VAL
                                     : -HUGE_VAL;
    vraster::Point& p = lines.points[data[2] % lines.points.size()];
    (data[2] & 1 ? p.x : p.y) = bad;
  }
  CheckingSink sink;
  vraster::Rasterizer rasterizer;
  rasterizer.fill(lines, rule, aa, kSize, kSize, sink);
  std::uint8_t mask[kSize * kSize];
  rasterizer.fill_mask(lines, rule, kSize, kSize, mask, kSize);
  if (aa == vraster::AntiAlias::Exact && rule != vraster::FillRule::NonExterior) {
    // Exact mode hands paths whose winding is only 0 and one other value to the analytic sweep: it must give what
    // the boundary sweep gives.
    CheckingSink swept;
    vraster::Rasterizer boundary_only;
    boundary_only.set_exact_shortcut(false);
    boundary_only.fill(lines, rule, aa, kSize, kSize, swept);
    for (int i = 0; i < kSize * kSize; ++i) {
      if (std::abs(sink.grid[i] - swept.grid[i]) > 1e-5f) std::abort();
    }
  }
  return 0;
}
