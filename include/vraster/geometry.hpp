// vraster: small geometry value types (points, rectangles, affine transforms).
#pragma once

#include <cmath>

namespace vraster {

/// A point or vector in user or device space (device: x right, y down, pixel (i, j) is [i, i+1) x [j, j+1)).
struct Point {
  double x = 0;
  double y = 0;

  friend constexpr Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Point operator*(Point a, double s) { return {a.x * s, a.y * s}; }
  friend constexpr Point operator*(double s, Point a) { return {a.x * s, a.y * s}; }
  friend constexpr bool operator==(Point a, Point b) { return a.x == b.x && a.y == b.y; }
};

inline double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }
inline double cross(Point a, Point b) { return a.x * b.y - a.y * b.x; }
inline double length(Point a) { return std::hypot(a.x, a.y); }
inline Point lerp(Point a, Point b, double t) { return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t}; }
inline bool is_finite(Point p) { return std::isfinite(p.x) && std::isfinite(p.y); }

/// An axis-aligned rectangle [x0, x1) x [y0, y1). Empty when x1 <= x0 or y1 <= y0.
struct Rect {
  double x0 = 0;
  double y0 = 0;
  double x1 = 0;
  double y1 = 0;

  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  bool intersects(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  /// Grows the rectangle to include p.
  void include(Point p) {
    if (p.x < x0) x0 = p.x;
    if (p.x > x1) x1 = p.x;
    if (p.y < y0) y0 = p.y;
    if (p.y > y1) y1 = p.y;
  }
  static Rect from_point(Point p) { return {p.x, p.y, p.x, p.y}; }
};

/// An affine transform in SVG matrix order (a b c d e f):
///   x' = a*x + c*y + e,   y' = b*x + d*y + f.
/// `A * B` applies B first, then A (so SVG's "transform=A B" is A * B).
struct Affine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;

  Point apply(Point p) const { return {a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
  /// Applies only the linear part (for vectors).
  Point apply_vector(Point v) const { return {a * v.x + c * v.y, b * v.x + d * v.y}; }
  double determinant() const { return a * d - b * c; }
  bool is_identity() const { return a == 1 && b == 0 && c == 0 && d == 1 && e == 0 && f == 0; }
  bool is_finite() const {
    return std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d) &&
           std::isfinite(e) && std::isfinite(f);
  }
  /// The inverse, or nothing sensible when the determinant is 0 (check invertible() first).
  bool invertible() const { return determinant() != 0 && std::isfinite(1.0 / determinant()); }
  Affine inverse() const {
    const double inv = 1.0 / determinant();
    return {d * inv, -b * inv, -c * inv, a * inv, (c * f - d * e) * inv, (b * e - a * f) * inv};
  }

  friend Affine operator*(const Affine& m, const Affine& n) {
    return {m.a * n.a + m.c * n.b,       m.b * n.a + m.d * n.b,       m.a * n.c + m.c * n.d,
            m.b * n.c + m.d * n.d,       m.a * n.e + m.c * n.f + m.e, m.b * n.e + m.d * n.f + m.f};
  }

  static Affine translate(double tx, double ty) { return {1, 0, 0, 1, tx, ty}; }
  static Affine scale(double sx, double sy) { return {sx, 0, 0, sy, 0, 0}; }
  static Affine scale(double s) { return {s, 0, 0, s, 0, 0}; }
  /// Rotation by `degrees` (positive turns +x towards +y: clockwise on screen, as in SVG).
  static Affine rotate(double degrees) {
    const double r = degrees * 3.14159265358979323846 / 180.0;
    const double cs = std::cos(r), sn = std::sin(r);
    return {cs, sn, -sn, cs, 0, 0};
  }
  static Affine rotate(double degrees, double cx, double cy) {
    return translate(cx, cy) * rotate(degrees) * translate(-cx, -cy);
  }
  static Affine skew_x(double degrees) { return {1, 0, std::tan(degrees * 3.14159265358979323846 / 180.0), 1, 0, 0}; }
  static Affine skew_y(double degrees) { return {1, std::tan(degrees * 3.14159265358979323846 / 180.0), 0, 1, 0, 0}; }
};

}  // namespace vraster
