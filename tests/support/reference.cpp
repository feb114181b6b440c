#include "support/reference.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vraster::test {
namespace {

// One Sutherland–Hodgman pass: keeps the part of `poly` on the side coord(p) >= value (keep_greater) or
// coord(p) <= value of the line {coord = value}, where coord is x (axis 0) or y (axis 1).
Polygon clip_half_plane(const Polygon& poly, int axis, double value, bool keep_greater) {
  Polygon out;
  const std::size_t n = poly.size();
  if (n == 0) return out;
  out.reserve(n + 4);
  auto coord = [axis](Point p) { return axis == 0 ? p.x : p.y; };
  auto inside = [&](Point p) { return keep_greater ? coord(p) >= value : coord(p) <= value; };
  auto cut = [&](Point p, Point q) {
    const double t = (value - coord(p)) / (coord(q) - coord(p));
    if (axis == 0) return Point{value, p.y + (q.y - p.y) * t};
    return Point{p.x + (q.x - p.x) * t, value};
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Point cur = poly[i];
    const Point prev = poly[(i + n - 1) % n];
    const bool cur_in = inside(cur), prev_in = inside(prev);
    if (cur_in) {
      if (!prev_in) out.push_back(cut(prev, cur));
      out.push_back(cur);
    } else if (prev_in) {
      out.push_back(cut(prev, cur));
    }
  }
  return out;
}

}  // namespace

double shoelace_area(const Polygon& poly) {
  const std::size_t n = poly.size();
  double twice = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point a = poly[i], b = poly[(i + 1) % n];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * twice;
}

Polygon clip_to_box(const Polygon& poly, double x0, double y0, double x1, double y1) {
  Polygon p = clip_half_plane(poly, 0, x0, true);
  p = clip_half_plane(p, 0, x1, false);
  p = clip_half_plane(p, 1, y0, true);
  return clip_half_plane(p, 1, y1, false);
}

std::vector<double> reference_coverage(const std::vector<Polygon>& contours, int width, int height) {
  std::vector<double> signed_area(static_cast<std::size_t>(width) * height, 0.0);
  for (const Polygon& poly : contours) {
    if (poly.size() < 3) continue;
    double ymin = poly[0].y, ymax = poly[0].y, xmin = poly[0].x, xmax = poly[0].x;
    for (Point p : poly) {
      ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
      xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
    }
    const int r0 = std::max(0, static_cast<int>(std::floor(ymin)));
    const int r1 = std::min(height, static_cast<int>(std::ceil(ymax)));
    const int c0 = std::max(0, static_cast<int>(std::floor(xmin)));
    const int c1 = std::min(width, static_cast<int>(std::ceil(xmax)));
    for (int y = r0; y < r1; ++y) {
      // Row band first, then each pixel of it: both are plain half-plane clips.
      Polygon band = clip_half_plane(clip_half_plane(poly, 1, y, true), 1, y + 1.0, false);
      if (band.size() < 3) continue;
      for (int x = c0; x < c1; ++x) {
        const Polygon cell = clip_half_plane(clip_half_plane(band, 0, x, true), 0, x + 1.0, false);
        if (cell.size() < 3) continue;
        signed_area[static_cast<std::size_t>(y) * width + x] += shoelace_area(cell);
      }
    }
  }
  for (double& a : signed_area) a = std::min(std::abs(a), 1.0);
  return signed_area;
}

std::optional<int> winding_number(const std::vector<Polygon>& contours, Point p) {
  int w = 0;
  for (const Polygon& poly : contours) {
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point a = poly[i], b = poly[(i + 1) % n];
      if (a.y == b.y) continue;
      const bool down = b.y > a.y;
      const Point top = down ? a : b, bottom = down ? b : a;
      if (!(top.y <= p.y && p.y < bottom.y)) continue;
      // y grows downward: with d = bottom - top (d.y > 0), p lies right of the edge when cross(d, p - top) < 0.
      const double o = cross(bottom - top, p - top);
      if (o == 0) return std::nullopt;
      if (o < 0) w += down ? 1 : -1;
    }
  }
  return w;
}

bool rule_inside(FillRule rule, int w) {
  switch (rule) {
    case FillRule::EvenOdd: return w % 2 != 0;
    case FillRule::NonZero: return w != 0;
    case FillRule::Positive: return w > 0;
    case FillRule::Negative: return w < 0;
    case FillRule::AbsGeq2: return std::abs(w) >= 2;
    case FillRule::NonExterior: break;
  }
  return false;
}

Path path_of(const std::vector<Polygon>& contours) {
  Path path;
  for (const Polygon& poly : contours) path.add_polygon(poly, true);
  return path;
}

std::vector<Polygon> reversed(const std::vector<Polygon>& contours) {
  std::vector<Polygon> out = contours;
  for (Polygon& p : out) std::reverse(p.begin(), p.end());
  return out;
}

Polygon random_star_polygon(std::mt19937& rng, Point center, int n, double r_min, double r_max,
                            bool random_orientation) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  std::uniform_real_distribution<double> angle(0, kTwoPi), radius(r_min, r_max), unit(0, 1);
  std::vector<double> angles(static_cast<std::size_t>(n));
  for (;;) {
    for (double& a : angles) a = angle(rng);
    std::sort(angles.begin(), angles.end());
    // Every gap below pi keeps each edge inside its own sector, so the polygon is simple (star-shaped from the
    // centre); distinct angles keep vertices apart.
    double max_gap = angles.front() + kTwoPi - angles.back(), min_gap = max_gap;
    for (std::size_t i = 1; i < angles.size(); ++i) {
      max_gap = std::max(max_gap, angles[i] - angles[i - 1]);
      min_gap = std::min(min_gap, angles[i] - angles[i - 1]);
    }
    if (max_gap < 0.9 * std::numbers::pi && min_gap > 1e-3) break;
  }
  Polygon poly;
  for (double a : angles) {
    const double r = radius(rng);
    poly.push_back({center.x + r * std::cos(a), center.y + r * std::sin(a)});
  }
  if (random_orientation && unit(rng) < 0.5) std::reverse(poly.begin(), poly.end());
  return poly;
}

Polygon random_dyadic_polygon(std::mt19937& rng, int n, double lo, double hi) {
  const int k0 = static_cast<int>(std::ceil(lo * 64)), k1 = static_cast<int>(std::floor(hi * 64)) - 1;
  std::uniform_int_distribution<int> k(k0, k1);
  Polygon poly;
  for (int i = 0; i < n; ++i) poly.push_back({k(rng) / 64.0 + 1 / 128.0, k(rng) / 64.0 + 1 / 128.0});
  return poly;
}

}  // namespace vraster::test
