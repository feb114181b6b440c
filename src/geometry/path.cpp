// Path construction: every coordinate is checked once here, so later stages can trust the path.
#include "vraster/path.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/point_bounds.hpp"
#include "vraster/error.hpp"

namespace vraster {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Arcs are split into cubics of at most 30 degrees: the radial error of such a cubic is below 4e-7 of the radius.
constexpr double kMaxArcStep = kPi / 6;

void check_finite(Point p, const char* what) {
  if (!is_finite(p)) {
    throw Error(std::string("path: non-finite coordinate in ") + what);
  }
}

void check_finite(double v, const char* what) {
  if (!std::isfinite(v)) {
    throw Error(std::string("path: non-finite value in ") + what);
  }
}

// Angle from vector u to vector v, in (-pi, pi].
double vector_angle(Point u, Point v) { return std::atan2(cross(u, v), dot(u, v)); }

// Parameters t in (0, 1) where the derivative of a 1-D quadratic or cubic Bezier is zero.
int quad_extrema(double a, double b, double c, double* t) {
  const double den = a - 2 * b + c;
  if (den == 0) return 0;
  const double s = (a - b) / den;
  if (s > 0 && s < 1) {
    t[0] = s;
    return 1;
  }
  return 0;
}

int cubic_extrema(double a, double b, double c, double d, double* t) {
  // B'(t)/3 = (b-a)(1-t)^2 + 2(c-b)(1-t)t + (d-c)t^2 = A t^2 + B t + C.
  const double qa = -a + 3 * b - 3 * c + d;
  const double qb = 2 * (a - 2 * b + c);
  const double qc = b - a;
  int n = 0;
  auto keep = [&](double s) {
    if (s > 0 && s < 1) t[n++] = s;
  };
  if (std::abs(qa) < 1e-12 * (std::abs(qb) + std::abs(qc)) || qa == 0) {
    if (qb != 0) keep(-qc / qb);
    return n;
  }
  const double disc = qb * qb - 4 * qa * qc;
  if (disc < 0) return 0;
  const double sq = std::sqrt(disc);
  // Numerically stable roots of a quadratic.
  const double q = -0.5 * (qb + std::copysign(sq, qb));
  if (q != 0) {
    keep(q / qa);
    keep(qc / q);
  } else {
    keep(0);
  }
  return n;
}

Point eval_quad(Point p0, Point p1, Point p2, double t) {
  const double u = 1 - t;
  return p0 * (u * u) + p1 * (2 * u * t) + p2 * (t * t);
}

Point eval_cubic(Point p0, Point p1, Point p2, Point p3, double t) {
  const double u = 1 - t;
  return p0 * (u * u * u) + p1 * (3 * u * u * t) + p2 * (3 * u * t * t) + p3 * (t * t * t);
}

}  // namespace

void Path::restore(const Snapshot& s) {
  verbs_.resize(s.verbs);
  points_.resize(s.points);
  current_ = s.current;
  contour_start_ = s.contour_start;
  contour_open_ = s.contour_open;
}

template <class F>
Path& Path::atomically(F&& build) {
  const Snapshot before = snapshot();
  try {
    build();
  } catch (...) {
    restore(before);
    throw;
  }
  return *this;
}

// Room for a shape's verbs and points in one allocation per vector (a shape on an empty path would otherwise grow
// it several times), growing geometrically so that many shapes appended to one path stay linear.
void Path::reserve_more(std::size_t verbs, std::size_t points) {
  if (verbs_.capacity() < verbs_.size() + verbs) verbs_.reserve(std::max(verbs_.size() + verbs, 2 * verbs_.size()));
  if (points_.capacity() < points_.size() + points)
    points_.reserve(std::max(points_.size() + points, 2 * points_.size()));
}

void Path::ensure_contour() {
  if (!contour_open_) {
    verbs_.push_back(Verb::Move);
    points_.push_back(current_);
    contour_start_ = current_;
    contour_open_ = true;
  }
}

Path& Path::move_to(Point p) {
  check_finite(p, "move_to");
  // A move right after a move replaces it: an empty contour draws nothing.
  if (contour_open_ && !verbs_.empty() && verbs_.back() == Verb::Move) {
    points_.back() = p;
  } else {
    verbs_.push_back(Verb::Move);
    points_.push_back(p);
  }
  current_ = contour_start_ = p;
  contour_open_ = true;
  return *this;
}

Path& Path::line_to(Point p) {
  check_finite(p, "line_to");
  ensure_contour();
  verbs_.push_back(Verb::Line);
  points_.push_back(p);
  current_ = p;
  return *this;
}

Path& Path::quad_to(Point control, Point p) {
  check_finite(control, "quad_to");
  check_finite(p, "quad_to");
  ensure_contour();
  verbs_.push_back(Verb::Quad);
  points_.push_back(control);
  points_.push_back(p);
  current_ = p;
  return *this;
}

Path& Path::cubic_to(Point control1, Point control2, Point p) {
  check_finite(control1, "cubic_to");
  check_finite(control2, "cubic_to");
  check_finite(p, "cubic_to");
  ensure_contour();
  verbs_.push_back(Verb::Cubic);
  points_.push_back(control1);
  points_.push_back(control2);
  points_.push_back(p);
  current_ = p;
  return *this;
}

Path& Path::close() {
  if (contour_open_) {
    verbs_.push_back(Verb::Close);
    current_ = contour_start_;
    contour_open_ = false;
  }
  return *this;
}

// Appends cubics approximating the ellipse arc that starts at the current point (angle theta1) and turns by dtheta
// (radians) on the ellipse with radii rx, ry whose x axis is rotated by phi. Points are computed relative to the
// start point with cos t - cos t1 = -2 sin((t + t1) / 2) sin((t - t1) / 2) (and likewise for sine), which keeps
// arcs of huge radius precise: centre + radius * cos t would cancel catastrophically there.
void Path::arc_segments(double rx, double ry, double phi, double theta1, double dtheta) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(dtheta) / kMaxArcStep - 1e-9)));
  const double step = dtheta / n;
  const double k = 4.0 / 3.0 * std::tan(step / 4);
  const double cs = std::cos(phi), sn = std::sin(phi);
  const Point start = current_;
  reserve_more(static_cast<std::size_t>(n) + 1, 3 * static_cast<std::size_t>(n));  // the cubics and a close
  auto point_at = [&](double t) {
    const double half = std::sin((t - theta1) / 2), mid = (t + theta1) / 2;
    const double x = -2 * rx * std::sin(mid) * half, y = 2 * ry * std::cos(mid) * half;
    return Point{start.x + cs * x - sn * y, start.y + sn * x + cs * y};
  };
  auto tangent_at = [&](double t) {
    const double x = -rx * std::sin(t), y = ry * std::cos(t);
    return Point{cs * x - sn * y, sn * x + cs * y};
  };
  double t = theta1;
  Point from = start;
  for (int i = 0; i < n; ++i) {
    const double t2 = (i + 1 == n) ? theta1 + dtheta : t + step;
    const Point to = point_at(t2);
    cubic_to(from + tangent_at(t) * k, to - tangent_at(t2) * k, to);
    from = to;
    t = t2;
  }
}

Path& Path::arc_to(double rx, double ry, double x_rotation_degrees, bool large_arc, bool sweep, Point p) {
  check_finite(rx, "arc_to radius");
  check_finite(ry, "arc_to radius");
  check_finite(x_rotation_degrees, "arc_to rotation");
  check_finite(p, "arc_to");
  return atomically([&] {
    ensure_contour();
    const Point p1 = current_;
    if (p1 == p) return;  // SVG: an arc to the current point is omitted
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (rx == 0 || ry == 0) {
      line_to(p);
      return;
    }
    // SVG 1.1 implementation notes F.6.5: endpoint to centre parameterisation, written with the ratios
    // u = (x1', y1') / (rx, ry) so that no product of two radii can overflow.
    const double phi = std::fmod(x_rotation_degrees, 360.0) * kPi / 180.0;
    const double cs = std::cos(phi), sn = std::sin(phi);
    const double hx = (p1.x - p.x) / 2, hy = (p1.y - p.y) / 2;
    const double x1p = cs * hx + sn * hy;
    const double y1p = -sn * hx + cs * hy;
    double ux = x1p / rx, uy = y1p / ry;
    // F.6.6: scale the radii up when they cannot reach the end point.
    const double lambda = ux * ux + uy * uy;
    if (lambda > 1) {
      const double s = std::sqrt(lambda);
      rx *= s;
      ry *= s;
      ux /= s;
      uy /= s;
    }
    // coef = sqrt((1 - |u|^2) / |u|^2), with |u| from hypot so that huge radii (|u|^2 underflowing) still work.
    const double u_len = std::hypot(ux, uy);
    double coef = (u_len > 0 && u_len < 1) ? std::sqrt(1 - u_len * u_len) / u_len : 0.0;
    if (large_arc == sweep) coef = -coef;
    const double cxp = coef * rx * uy;
    const double cyp = -coef * ry * ux;
    const Point u{ux - coef * uy, uy + coef * ux};
    const Point v{-ux - coef * uy, -uy + coef * ux};
    const double theta1 = vector_angle({1, 0}, u);
    double dtheta = vector_angle(u, v);
    if (!sweep && dtheta > 0) dtheta -= 2 * kPi;
    if (sweep && dtheta < 0) dtheta += 2 * kPi;
    if (!std::isfinite(cxp) || !std::isfinite(cyp) || !std::isfinite(dtheta)) {
      line_to(p);
      return;
    }
    arc_segments(rx, ry, phi, theta1, dtheta);
    // Land exactly on the requested end point (the cosine/sine round trip is off by an ulp or so).
    points_.back() = p;
    current_ = p;
  });
}

Path& Path::add_rect(const Rect& r) {
  check_finite(Point{r.x0, r.y0}, "add_rect");
  check_finite(Point{r.x1, r.y1}, "add_rect");
  reserve_more(5, 4);
  move_to({r.x0, r.y0});
  line_to({r.x1, r.y0});
  line_to({r.x1, r.y1});
  line_to({r.x0, r.y1});
  return close();
}

Path& Path::add_round_rect(const Rect& r, double rx, double ry) {
  check_finite(Point{r.x0, r.y0}, "add_round_rect");
  check_finite(Point{r.x1, r.y1}, "add_round_rect");
  check_finite(rx, "add_round_rect");
  check_finite(ry, "add_round_rect");
  rx = std::min(std::abs(rx), std::abs(r.width()) / 2);
  ry = std::min(std::abs(ry), std::abs(r.height()) / 2);
  if (!(rx > 0) || !(ry > 0)) return add_rect(r);
  return atomically([&] {
    move_to({r.x0 + rx, r.y0});
    line_to({r.x1 - rx, r.y0});
    arc_to(rx, ry, 0, false, true, {r.x1, r.y0 + ry});
    line_to({r.x1, r.y1 - ry});
    arc_to(rx, ry, 0, false, true, {r.x1 - rx, r.y1});
    line_to({r.x0 + rx, r.y1});
    arc_to(rx, ry, 0, false, true, {r.x0, r.y1 - ry});
    line_to({r.x0, r.y0 + ry});
    arc_to(rx, ry, 0, false, true, {r.x0 + rx, r.y0});
    close();
  });
}

namespace {

// The full ellipse's cubics: arc_segments' construction (steps of kMaxArcStep from angle 0, handles k = 4/3
// tan(step / 4)) on the unit circle, computed once: a circle is among the commonest shapes, and its path took some
// eighty sine and cosine calls.
struct UnitCircle {
  static constexpr int kSteps = 12;
  static_assert(kSteps * kMaxArcStep > 2 * kPi - 1e-9 && (kSteps - 1) * kMaxArcStep < 2 * kPi);
  double cos_t[kSteps + 1], sin_t[kSteps + 1], k;
  UnitCircle() : k(4.0 / 3.0 * std::tan(2 * kPi / kSteps / 4)) {
    for (int i = 0; i <= kSteps; ++i) {
      cos_t[i] = std::cos(2 * kPi * i / kSteps);
      sin_t[i] = std::sin(2 * kPi * i / kSteps);
    }
  }
};

}  // namespace

Path& Path::add_ellipse(Point c, double rx, double ry) {
  check_finite(c, "add_ellipse");
  check_finite(rx, "add_ellipse");
  check_finite(ry, "add_ellipse");
  rx = std::abs(rx);
  ry = std::abs(ry);
  static const UnitCircle unit;
  constexpr int n = UnitCircle::kSteps;
  reserve_more(n + 2, 3 * n + 1);  // a move, the cubics, a close
  return atomically([&] {
    move_to({c.x + rx, c.y});
    auto point = [&](int i) {  // the last point is the first one exactly
      return i == n ? Point{c.x + rx, c.y} : Point{c.x + rx * unit.cos_t[i], c.y + ry * unit.sin_t[i]};
    };
    auto tangent = [&](int i) { return Point{-rx * unit.sin_t[i], ry * unit.cos_t[i]}; };
    for (int i = 0; i < n; ++i) {
      const Point from = point(i), to = point(i + 1);
      cubic_to(from + tangent(i) * unit.k, to - tangent(i + 1) * unit.k, to);
    }
    close();
  });
}

Path& Path::add_polygon(std::span<const Point> pts, bool closed) {
  for (const Point& p : pts) check_finite(p, "add_polygon");
  if (pts.empty()) return *this;
  move_to(pts[0]);
  for (std::size_t i = 1; i < pts.size(); ++i) line_to(pts[i]);
  if (closed) close();
  return *this;
}

Path& Path::add_path(const Path& other) {
  // Every point of `other` is already finite: nothing here can throw half way.
  std::size_t i = 0;
  for (Verb v : other.verbs_) {
    switch (v) {
      case Verb::Move: move_to(other.points_[i++]); break;
      case Verb::Line: line_to(other.points_[i++]); break;
      case Verb::Quad: quad_to(other.points_[i], other.points_[i + 1]); i += 2; break;
      case Verb::Cubic: cubic_to(other.points_[i], other.points_[i + 1], other.points_[i + 2]); i += 3; break;
      case Verb::Close: close(); break;
    }
  }
  return *this;
}

void Path::transform(const Affine& m) {
  // Map into a copy first: a non-finite result must leave the path untouched.
  std::vector<Point> mapped(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    mapped[i] = m.apply(points_[i]);
    if (!is_finite(mapped[i])) throw Error("path: transform produced a non-finite coordinate");
  }
  const Point current = m.apply(current_), start = m.apply(contour_start_);
  if (!is_finite(current) || !is_finite(start)) throw Error("path: transform produced a non-finite coordinate");
  points_.swap(mapped);
  current_ = current;
  contour_start_ = start;
}

Path Path::transformed(const Affine& m) const {
  Path copy = *this;
  copy.transform(m);
  return copy;
}

void Path::clear() {
  verbs_.clear();
  points_.clear();
  current_ = contour_start_ = Point{};
  contour_open_ = false;
}

Rect Path::control_bounds() const {
  if (points_.empty()) return {};
  const detail::PointBounds b = detail::point_bounds(points_);  // (a path's points are finite)
  return {b.x_lo, b.y_lo, b.x_hi, b.y_hi};
}

Rect Path::bounds() const {
  if (points_.empty()) return {};
  // The on-curve points first; a curve reaches beyond them only where a control point lies outside (a curve stays in
  // the hull of its control points), so only those curves need their extrema (most curves of most paths do not).
  Rect r = Rect::from_point(points_[0]);
  std::size_t i = 0;
  for (Verb v : verbs_) {
    const std::size_t n = v == Verb::Quad ? 2 : v == Verb::Cubic ? 3 : v == Verb::Close ? 0 : 1;
    if (n > 0) r.include(points_[i + n - 1]);
    i += n;
  }
  const auto inside = [&r](Point c) { return c.x >= r.x0 && c.x <= r.x1 && c.y >= r.y0 && c.y <= r.y1; };
  i = 0;
  Point last{};
  Rect out = r;
  for (Verb v : verbs_) {
    switch (v) {
      case Verb::Move:
      case Verb::Line:
        last = points_[i++];
        break;
      case Verb::Quad: {
        const Point c = points_[i], p = points_[i + 1];
        if (!inside(c)) {
          double t[2];
          int n = quad_extrema(last.x, c.x, p.x, t);
          n += quad_extrema(last.y, c.y, p.y, t + n);
          for (int k = 0; k < n; ++k) out.include(eval_quad(last, c, p, t[k]));
        }
        last = p;
        i += 2;
        break;
      }
      case Verb::Cubic: {
        const Point c1 = points_[i], c2 = points_[i + 1], p = points_[i + 2];
        if (!inside(c1) || !inside(c2)) {
          double t[4];
          int n = cubic_extrema(last.x, c1.x, c2.x, p.x, t);
          n += cubic_extrema(last.y, c1.y, c2.y, p.y, t + n);
          for (int k = 0; k < n; ++k) out.include(eval_cubic(last, c1, c2, p, t[k]));
        }
        last = p;
        i += 3;
        break;
      }
      case Verb::Close: break;
    }
  }
  return out;
}

}  // namespace vraster
