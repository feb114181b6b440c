// libFuzzer target: the stroker and dasher (stroke_to_path) with random widths, caps, joins, miter limits, dash
// patterns and offsets, on random paths of lines, quadratics, cubics and closes; the result filled non-zero.
// stroke_to_path throws nothing for a valid path but its documented size limit (an outline of more than
// kMaxStrokeOutlinePoints points, named in the message); the result has finite points; its fill keeps the
// rasterizer's sink contract and coverage in [0, 1].
//
// Input: 16 header bytes (style), then 9-byte records (verb, four 16-bit signed coordinates), at most 300.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "vraster/stroke.hpp"
#include "vraster/vraster.hpp"

namespace {

constexpr int kSize = 48;

class CheckingSink final : public vraster::CoverageSink {
 public:
  void span(int y, int x0, int x1, float c) override {
    check(y, x0, x1);
    if (!(c > 0.f && c <= 1.f)) std::abort();
  }
  void row(int y, int x0, int x1, const float* c) override {
    check(y, x0, x1);
    for (int i = 0; i < x1 - x0; ++i) {
      if (!(c[i] >= 0.f && c[i] <= 1.f)) std::abort();
    }
  }

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

// A length from one byte: mostly powers of two from 2^-10 to 2^12 with a fraction, sometimes 0, negative or not
// finite (which the stroker must treat as invisible or invalid, never crash on).
double length(std::uint8_t b, std::uint8_t frac) {
  switch (b) {
    case 0: return 0;
    case 1: return -1;
    case 2: return std::numeric_limits<double>::quiet_NaN();
    case 3: return std::numeric_limits<double>::infinity();
    default: return std::ldexp(1.0 + frac / 256.0, static_cast<int>(b % 23) - 10);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kHeader = 16;
  if (size < kHeader || size > kHeader + 9 * 300) return 0;  // size cap: a few hundred segments reach everything
  vraster::StrokeStyle style;
  style.width = length(data[0], data[1]);
  style.cap = static_cast<vraster::LineCap>(data[2] % 3);
  style.join = static_cast<vraster::LineJoin>(data[3] % 3);
  style.miter_limit = data[4] / 16.0;  // 0 .. 16 (values below 1 act as 1)
  const int dash_count = data[5] % 7;  // 0 .. 6 entries, odd counts included
  for (int k = 0; k < dash_count; ++k) style.dashes.push_back(length(data[6 + k], data[12]));
  style.dash_offset = (static_cast<int>(data[13]) - 128) * length(data[14], 0) / 16;
  // Tolerance from 1/64 to 1 user unit; the scale keeps the stroke's width against its tolerance bounded (a very
  // wide stroke at a tiny tolerance is a size limit of the stroker, not what this target looks for).
  const double tolerance = std::ldexp(1.0, -static_cast<int>(data[15] % 7));
  const double scale = std::ldexp(1.0, static_cast<int>(data[15] / 7 % 16) - 10);
  vraster::Path path;
  for (std::size_t i = kHeader; i + 9 <= size; i += 9) {
    const std::uint8_t* r = data + i;
    const vraster::Point a{coord(r + 1, scale), coord(r + 3, scale)};
    const vraster::Point b{coord(r + 5, scale), coord(r + 7, scale)};
    switch (r[0] % 6) {
      case 0: path.move_to(a); break;
      case 1: path.line_to(a); break;
      case 2: path.quad_to(a, b); break;
      case 3: path.cubic_to(a, b, {a.x * 0.5 + b.x * 0.5, b.y}); break;
      case 4: path.close(); break;
      default: path.line_to(b); break;
    }
  }
  vraster::Path stroke;
  try {
    stroke = vraster::stroke_to_path(path, style, tolerance);
  } catch (const vraster::Error& e) {
    // The one documented error: a stroke far wider than its tolerance, dashed or curved finely enough to need more
    // points than the limit (the scale above bounds width against tolerance, but dashes multiply the caps).
    if (std::string(e.what()).find(std::to_string(vraster::kMaxStrokeOutlinePoints)) == std::string::npos) std::abort();
    return 0;
  } catch (...) {
    std::abort();  // nothing else is ever thrown
  }
  for (const vraster::Point& p : stroke.points()) {
    if (!vraster::is_finite(p)) std::abort();
  }
  vraster::Polylines lines;
  try {
    vraster::flatten(stroke, vraster::Affine::translate(kSize / 2.0, kSize / 2.0), vraster::FlattenOptions{}, lines);
  } catch (const vraster::Error&) {
    return 0;  // e.g. a stroke too long to flatten within the flattener's limits
  }
  CheckingSink sink;
  vraster::Rasterizer().fill(lines, vraster::FillRule::NonZero, vraster::AntiAlias::Analytic, kSize, kSize, sink);
  return 0;
}
