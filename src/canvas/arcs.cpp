// Canvas arcs (HTML canvas "ellipse method steps" and arcTo), emitted as cubic Beziers.
#include "canvas/arcs.hpp"

#include <cmath>

namespace vraster::canvas_detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2 * kPi;
constexpr double kMaxStep = kPi / 6;

}  // namespace

double canvas_arc_sweep(double a0, double a1, bool ccw) {
  const double forward = ccw ? a0 - a1 : a1 - a0;
  double sweep;
  if (forward >= kTwoPi) {
    sweep = kTwoPi;
  } else {
    sweep = std::fmod(forward, kTwoPi);
    if (sweep < 0) sweep += kTwoPi;
    if (sweep >= kTwoPi) sweep = 0;  // -tiny + 2 pi rounding to 2 pi: the points coincide
  }
  return ccw ? -sweep : sweep;
}

void append_ellipse_arc(Point c, double rx, double ry, double rotation, double a0, double sweep, ArcPoints& out) {
  const double cr = std::cos(rotation), sr = std::sin(rotation);
  // Unit circle -> ellipse: scale by (rx, ry), rotate, move to c.
  auto map = [&](double u, double v) {
    const double x = rx * u, y = ry * v;
    return Point{c.x + cr * x - sr * y, c.y + sr * x + cr * y};
  };
  out.points.push_back(map(std::cos(a0), std::sin(a0)));
  if (sweep == 0) return;
  const int n = static_cast<int>(std::ceil(std::abs(sweep) / kMaxStep - 1e-9));
  const int steps = n < 1 ? 1 : n;
  const double step = sweep / steps;
  // Control arm length of a cubic approximating a unit circular arc of angle `step`.
  const double k = 4.0 / 3.0 * std::tan(step / 4);
  double t0 = a0;
  double c0 = std::cos(t0), s0 = std::sin(t0);
  for (int i = 1; i <= steps; ++i) {
    const double t1 = i == steps ? a0 + sweep : a0 + step * i;
    const double c1 = std::cos(t1), s1 = std::sin(t1);
    out.points.push_back(map(c0 - k * s0, s0 + k * c0));
    out.points.push_back(map(c1 + k * s1, s1 - k * c1));
    out.points.push_back(map(c1, s1));
    c0 = c1;
    s0 = s1;
  }
}

bool append_arc_to(Point p0, Point p1, Point p2, double r, ArcPoints& out) {
  const Point u = p0 - p1, v = p2 - p1;
  const double lu = length(u), lv = length(v);
  if (!(lu > 0) || !(lv > 0)) return false;
  const Point du = u * (1 / lu), dv = v * (1 / lv);
  // Angle between the two legs at p1, in (0, pi).
  const double angle = std::atan2(std::abs(cross(du, dv)), dot(du, dv));
  const double half = angle / 2;
  const double tangent = r / std::tan(half);    // distance from p1 to each tangent point
  const double centre_dist = r / std::sin(half);  // distance from p1 to the circle's centre
  const Point bisector = du + dv;
  const double lb = length(bisector);
  if (!std::isfinite(tangent) || !std::isfinite(centre_dist) || !(lb > 0)) return false;
  const Point t1 = p1 + du * tangent, t2 = p1 + dv * tangent;
  const Point centre = p1 + bisector * (centre_dist / lb);
  if (!is_finite(t1) || !is_finite(t2) || !is_finite(centre)) return false;
  const double a0 = std::atan2(t1.y - centre.y, t1.x - centre.x);
  const double a1 = std::atan2(t2.y - centre.y, t2.x - centre.x);
  // The arc is the short way round (it spans pi - angle).
  double sweep = a1 - a0;
  while (sweep > kPi) sweep -= kTwoPi;
  while (sweep < -kPi) sweep += kTwoPi;
  const std::size_t first = out.points.size();
  append_ellipse_arc(centre, r, r, 0, a0, sweep, out);
  out.points[first] = t1;  // exact tangent points, not their trigonometric round trip
  out.points.back() = t2;
  return true;
}

}  // namespace vraster::canvas_detail
