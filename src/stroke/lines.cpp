// Classic line scan conversion: clipping plans for Bresenham (exact integer restart), DDA and Wu, plus the
// convenience wrappers (pixel lists, drawing into images).
#include "vraster/lines.hpp"

#include "stroke/internal.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

namespace vraster {
namespace {

using i128 = __int128;

i128 floor_div(i128 a, i128 b) {  // b > 0
  i128 q = a / b;
  if ((a % b != 0) && (a < 0)) --q;
  return q;
}

// Minor offset after t major steps: off(t) = floor((2*adv*t + du - bias) / (2*du)), the nearest integer to
// adv*t/du with halves rounded so that the ABSOLUTE minor coordinate rounds down (bias 1 when the minor
// coordinate increases, 0 when it decreases).
struct OffsetFn {
  std::int64_t adv, du, bias;
  i128 num(std::int64_t t) const { return i128{2} * adv * t + du - bias; }
  std::int64_t operator()(std::int64_t t) const { return static_cast<std::int64_t>(floor_div(num(t), i128{2} * du)); }
};

// Liang-Barsky: clips the parameter range [t0, t1] of p + t (q - p) to the rectangle. False when empty.
bool liang_barsky(Point p, Point q, double x0, double y0, double x1, double y1, double& t0, double& t1) {
  const double dx = q.x - p.x, dy = q.y - p.y;
  const double pp[4] = {-dx, dx, -dy, dy};
  const double qq[4] = {p.x - x0, x1 - p.x, p.y - y0, y1 - p.y};
  t0 = 0;
  t1 = 1;
  for (int i = 0; i < 4; ++i) {
    if (pp[i] == 0) {
      if (qq[i] < 0) return false;
      continue;
    }
    const double r = qq[i] / pp[i];
    if (pp[i] < 0) {
      if (r > t1) return false;
      if (r > t0) t0 = r;
    } else {
      if (r < t0) return false;
      if (r < t1) t1 = r;
    }
  }
  return t0 <= t1;
}

}  // namespace

bool plan_bresenham(IPoint p, IPoint q, int width, int height, LineEnd end, BresenhamWalk& walk) {
  if (width <= 0 || height <= 0) return false;
  const std::int64_t dx = std::int64_t{q.x} - p.x, dy = std::int64_t{q.y} - p.y;
  const bool x_major = std::llabs(dx) >= std::llabs(dy);
  std::int64_t u0 = x_major ? p.x : p.y, v0 = x_major ? p.y : p.x;
  std::int64_t u1 = x_major ? q.x : q.y, v1 = x_major ? q.y : q.x;
  // Which canonical t the end point q sits at (for the half-open rule), after ordering by increasing u.
  bool q_at_start = false;
  if (u1 < u0) {
    std::swap(u0, u1);
    std::swap(v0, v1);
    q_at_start = true;
  }
  const std::int64_t du = u1 - u0, dv = v1 - v0;
  const int sv = dv > 0 ? 1 : (dv < 0 ? -1 : 0);
  const std::int64_t umax = x_major ? width : height, vmax = x_major ? height : width;
  walk.x_major = x_major;
  walk.sv = sv;
  if (du == 0) {  // a single pixel
    if (end == LineEnd::HalfOpen) return false;
    if (u0 < 0 || u0 >= umax || v0 < 0 || v0 >= vmax) return false;
    walk.u = u0;
    walk.v = v0;
    walk.count = 1;
    walk.rem = 0;
    walk.two_dv = 0;
    walk.two_du = 1;
    return true;
  }
  std::int64_t ta = 0, tb = du;
  if (end == LineEnd::HalfOpen) {
    if (q_at_start) ta = 1; else tb = du - 1;
  }
  // Clip on the major axis.
  ta = std::max(ta, -u0);
  tb = std::min(tb, umax - 1 - u0);
  if (ta > tb) return false;
  // Clip on the minor axis: off(t) must lie in [lo, hi]; off is non-decreasing, so binary search.
  const OffsetFn off{std::llabs(dv), du, sv > 0 ? 1 : 0};
  std::int64_t lo, hi;
  if (sv >= 0) {
    lo = -v0;
    hi = vmax - 1 - v0;
  } else {
    lo = v0 - (vmax - 1);
    hi = v0;
  }
  if (off(tb) < lo || off(ta) > hi) return false;
  if (off(ta) < lo) {  // first t with off(t) >= lo
    std::int64_t a = ta, b = tb;  // off(a) < lo <= off(b)
    while (b - a > 1) {
      const std::int64_t m = a + (b - a) / 2;
      (off(m) >= lo ? b : a) = m;
    }
    ta = b;
  }
  if (off(tb) > hi) {  // last t with off(t) <= hi
    std::int64_t a = ta, b = tb;  // off(a) <= hi < off(b)
    while (b - a > 1) {
      const std::int64_t m = a + (b - a) / 2;
      (off(m) <= hi ? a : b) = m;
    }
    tb = a;
  }
  if (ta > tb) return false;
  // Restart the integer error term exactly at t = ta.
  const i128 n = off.num(ta), two_du = i128{2} * du;
  const i128 o = floor_div(n, two_du);
  walk.u = u0 + ta;
  walk.v = v0 + sv * static_cast<std::int64_t>(o);
  walk.rem = static_cast<std::int64_t>(n - o * two_du);
  walk.two_dv = 2 * std::llabs(dv);
  walk.two_du = 2 * du;
  walk.count = tb - ta + 1;
  return true;
}

bool plan_dda(IPoint p, IPoint q, int width, int height, MajorRange& range) {
  if (width <= 0 || height <= 0) return false;
  const double dx = static_cast<double>(q.x) - p.x, dy = static_cast<double>(q.y) - p.y;
  range.x_major = std::fabs(dx) >= std::fabs(dy);
  // Restrict to the part of the segment near the canvas (one pixel of margin covers rounding), then to the
  // canvas on the major axis.
  double t0, t1;
  const Point pp{static_cast<double>(p.x), static_cast<double>(p.y)}, qq{static_cast<double>(q.x), static_cast<double>(q.y)};
  if (!liang_barsky(pp, qq, -1.0, -1.0, width + 1.0, height + 1.0, t0, t1)) return false;
  const double ua = range.x_major ? pp.x + t0 * dx : pp.y + t0 * dy;
  const double ub = range.x_major ? pp.x + t1 * dx : pp.y + t1 * dy;
  const double lo = std::min(ua, ub), hi = std::max(ua, ub);
  const std::int64_t umax = range.x_major ? width : height;
  range.first = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(lo)) - 1);
  range.last = std::min<std::int64_t>(umax - 1, static_cast<std::int64_t>(std::ceil(hi)) + 1);
  // Never step outside the segment itself.
  const std::int64_t pu = range.x_major ? p.x : p.y, qu = range.x_major ? q.x : q.y;
  range.first = std::max(range.first, std::min(pu, qu));
  range.last = std::min(range.last, std::max(pu, qu));
  return range.first <= range.last;
}

bool plan_wu(Point p, Point q, int width, int height, MajorRange& range) {
  if (width <= 0 || height <= 0 || p == q || !is_finite(p) || !is_finite(q)) return false;
  const double dx = q.x - p.x, dy = q.y - p.y;
  range.x_major = std::fabs(dx) >= std::fabs(dy);
  double t0, t1;
  if (!liang_barsky(p, q, -1.0, -1.0, width + 1.0, height + 1.0, t0, t1)) return false;
  const double ua = range.x_major ? p.x + t0 * dx : p.y + t0 * dy;
  const double ub = range.x_major ? p.x + t1 * dx : p.y + t1 * dy;
  const double lo = std::min(ua, ub), hi = std::max(ua, ub);
  const std::int64_t umax = range.x_major ? width : height;
  range.first = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(lo)));
  range.last = std::min<std::int64_t>(umax - 1, static_cast<std::int64_t>(std::ceil(hi)));
  return range.first <= range.last;
}

bool clip_segment(Point& p, Point& q, const Rect& r) {
  double t0, t1;
  if (!liang_barsky(p, q, r.x0, r.y0, r.x1, r.y1, t0, t1)) return false;
  const Point a = lerp(p, q, t0), b = lerp(p, q, t1);
  p = a;
  q = b;
  return true;
}

std::vector<IPoint> bresenham_pixels(IPoint p, IPoint q, LineEnd end) {
  std::vector<IPoint> out;
  // A canvas covering every int coordinate: shift into [0, 2^32) is not representable in int, so draw on a
  // canvas translated to contain both endpoints.
  const int ox = std::min(p.x, q.x), oy = std::min(p.y, q.y);
  const std::int64_t w = std::int64_t{std::max(p.x, q.x)} - ox + 1, h = std::int64_t{std::max(p.y, q.y)} - oy + 1;
  if (w > INT_MAX || h > INT_MAX) return out;  // beyond what a list can hold anyway
  bresenham_line(IPoint{p.x - ox, p.y - oy}, IPoint{q.x - ox, q.y - oy}, static_cast<int>(w), static_cast<int>(h), end,
                 [&](int x, int y) { out.push_back({x + ox, y + oy}); });
  return out;
}

std::vector<IPoint> dda_pixels(IPoint p, IPoint q, LineEnd end) {
  std::vector<IPoint> out;
  const int ox = std::min(p.x, q.x), oy = std::min(p.y, q.y);
  const std::int64_t w = std::int64_t{std::max(p.x, q.x)} - ox + 1, h = std::int64_t{std::max(p.y, q.y)} - oy + 1;
  if (w > INT_MAX || h > INT_MAX) return out;
  dda_line(IPoint{p.x - ox, p.y - oy}, IPoint{q.x - ox, q.y - oy}, static_cast<int>(w), static_cast<int>(h), end,
           [&](int x, int y) { out.push_back({x + ox, y + oy}); });
  return out;
}

std::vector<IPoint> circle_pixels(int r) {
  std::vector<IPoint> out;
  if (r < 0) return out;
  const int side = 2 * r + 1;
  midpoint_circle(IPoint{r, r}, r, side, side, [&](int x, int y) { out.push_back({x - r, y - r}); });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<IPoint> ellipse_pixels(int rx, int ry) {
  std::vector<IPoint> out;
  if (rx < 0 || ry < 0) return out;
  midpoint_ellipse(IPoint{rx, ry}, rx, ry, 2 * rx + 1, 2 * ry + 1,
                   [&](int x, int y) { out.push_back({x - rx, y - ry}); });
  std::sort(out.begin(), out.end());
  return out;
}

PixelBlender::PixelBlender(Image& image, Color color) : image_(image) {
  const float a = std::clamp(color.a, 0.0f, 1.0f);
  alpha_ = a;
  premul_[0] = std::clamp(color.r, 0.0f, 1.0f) * a;
  premul_[1] = std::clamp(color.g, 0.0f, 1.0f) * a;
  premul_[2] = std::clamp(color.b, 0.0f, 1.0f) * a;
  premul_[3] = a;
  for (int c = 0; c < 4; ++c) src8_[c] = static_cast<std::uint32_t>(premul_[c] * 255.0f + 0.5f);
  inv8_ = 255 - src8_[3];
}

void PixelBlender::blend_full(int x, int y) {
  std::uint8_t* px = image_.pixel(x, y);
  if (inv8_ == 0) {
    for (int c = 0; c < 4; ++c) px[c] = static_cast<std::uint8_t>(src8_[c]);
    return;
  }
  for (int c = 0; c < 4; ++c) {
    // dst * inv / 255, rounded (exact for 8-bit operands).
    std::uint32_t t = px[c] * inv8_ + 128;
    t = (t + (t >> 8)) >> 8;
    px[c] = static_cast<std::uint8_t>(std::min<std::uint32_t>(255, src8_[c] + t));
  }
}

void PixelBlender::blend(int x, int y, float coverage) {
  if (coverage >= 1.0f) return blend_full(x, y);
  if (!(coverage > 0)) return;
  std::uint8_t* px = image_.pixel(x, y);
  const float keep = 1.0f - alpha_ * coverage;
  for (int c = 0; c < 4; ++c) {
    const float v = premul_[c] * coverage * 255.0f + static_cast<float>(px[c]) * keep;
    px[c] = static_cast<std::uint8_t>(std::min(v + 0.5f, 255.0f));
  }
}

void blend_pixel(Image& image, int x, int y, Color color, float coverage) {
  PixelBlender(image, color).blend(x, y, coverage);
}

namespace {
int floor_to_int(double v) {
  const double f = std::floor(v);
  return static_cast<int>(std::clamp(f, static_cast<double>(INT_MIN), static_cast<double>(INT_MAX)));
}
}  // namespace

void draw_line(Image& image, Point p, Point q, Color color, LineAlgorithm algorithm, LineEnd end) {
  if (!is_finite(p) || !is_finite(q)) return;
  PixelBlender blender(image, color);
  auto plot = [&](int x, int y) { blender.blend_full(x, y); };
  switch (algorithm) {
    case LineAlgorithm::Bresenham:
      bresenham_line(IPoint{floor_to_int(p.x), floor_to_int(p.y)}, IPoint{floor_to_int(q.x), floor_to_int(q.y)},
                     image.width, image.height, end, plot);
      break;
    case LineAlgorithm::Dda:
      dda_line(IPoint{floor_to_int(p.x), floor_to_int(p.y)}, IPoint{floor_to_int(q.x), floor_to_int(q.y)},
               image.width, image.height, end, plot);
      break;
    case LineAlgorithm::Wu:
      wu_line(p, q, image.width, image.height, [&](int x, int y, float c) { blender.blend(x, y, c); });
      break;
  }
}

void draw_circle(Image& image, IPoint c, int r, Color color) {
  PixelBlender blender(image, color);
  midpoint_circle(c, r, image.width, image.height, [&](int x, int y) { blender.blend_full(x, y); });
}

void draw_ellipse(Image& image, IPoint c, int rx, int ry, Color color) {
  PixelBlender blender(image, color);
  midpoint_ellipse(c, rx, ry, image.width, image.height, [&](int x, int y) { blender.blend_full(x, y); });
}

}  // namespace vraster
