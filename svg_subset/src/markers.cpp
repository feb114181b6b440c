// svg_subset: marker vertices and directions (markers.hpp). SVG's rules ("path directionality"): the direction
// at the start of a segment points to its first control point that differs from its start (or to its end), at
// the end it comes from the last one that differs from its end; a marker between two segments takes the
// bisector of the two directions.
#include "markers.hpp"

#include <cmath>
#include <optional>

namespace vraster::svg::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A segment as a cubic: lines have their end points as control points, quadratics their one control point twice.
struct Segment {
  Point p0, c1, c2, p1;
};

struct Subpath {
  Point start;
  std::vector<Segment> segments;
  bool closed = false;
};

std::optional<Point> direction(Point from, Point to) {
  const Point d{to.x - from.x, to.y - from.y};
  if (d.x == 0 && d.y == 0) return std::nullopt;
  return d;
}

std::optional<Point> start_direction(const Segment& s) {
  if (auto d = direction(s.p0, s.c1)) return d;
  if (auto d = direction(s.p0, s.c2)) return d;
  return direction(s.p0, s.p1);
}

std::optional<Point> end_direction(const Segment& s) {
  if (auto d = direction(s.c2, s.p1)) return d;
  if (auto d = direction(s.c1, s.p1)) return d;
  return direction(s.p0, s.p1);
}

/// The direction of a vector in degrees, in [0, 360).
double degrees(Point v) {
  const double d = std::atan2(v.y, v.x) * 180 / kPi;
  return d < 0 ? d + 360 : d;
}

/// The marker angle for incoming and outgoing directions (either may be missing): the bisector of the two
/// directions, on the side of the smaller turn (a U-turn, 180 degrees either way, takes in + 90 - 180 as resvg).
double vertex_angle(const std::optional<Point>& in, const std::optional<Point>& out) {
  if (in && out) {
    const double a_in = degrees(*in), half = (degrees(*out) - a_in) / 2;
    return std::abs(half) > 90 ? a_in + half - 180 : a_in + half;
  }
  if (in) return degrees(*in);
  if (out) return degrees(*out);
  return 0;
}

std::vector<Subpath> subpaths(const Path& path) {
  std::vector<Subpath> out;
  const auto verbs = path.verbs();
  const auto pts = path.points();
  std::size_t i = 0;
  Point current{0, 0};
  for (const Verb v : verbs) {
    if (v != Verb::Move && out.empty()) out.push_back(Subpath{current, {}, false});  // a Path starts with a Move
    switch (v) {
      case Verb::Move:
        current = pts[i++];
        out.push_back(Subpath{current, {}, false});
        break;
      case Verb::Line:
        out.back().segments.push_back(Segment{current, current, pts[i], pts[i]});
        current = pts[i++];
        break;
      case Verb::Quad:
        out.back().segments.push_back(Segment{current, pts[i], pts[i], pts[i + 1]});
        current = pts[i + 1];
        i += 2;
        break;
      case Verb::Cubic:
        out.back().segments.push_back(Segment{current, pts[i], pts[i + 1], pts[i + 2]});
        current = pts[i + 2];
        i += 3;
        break;
      case Verb::Close: {
        Subpath& s = out.back();
        s.segments.push_back(Segment{current, current, s.start, s.start});
        s.closed = true;
        current = s.start;
        break;
      }
    }
  }
  return out;
}

}  // namespace

std::vector<MarkerVertex> marker_vertices(const Path& path) {
  std::vector<MarkerVertex> out;
  std::vector<std::optional<Point>> ins;  // each vertex's incoming direction (outgoing ones are used in place)
  for (const Subpath& s : subpaths(path)) {
    const std::size_t n = s.segments.size();
    std::vector<std::optional<Point>> starts(n), ends(n);
    for (std::size_t k = 0; k < n; ++k) {
      starts[k] = start_direction(s.segments[k]);
      ends[k] = end_direction(s.segments[k]);
    }
    // Zero-length segments take the direction of the nearest segment that has one (before for incoming
    // directions, after for outgoing ones).
    auto incoming = [&](std::size_t k) -> std::optional<Point> {  // arriving at the end of segment k
      for (std::size_t j = k + 1; j-- > 0;) {
        if (ends[j]) return ends[j];
      }
      return std::nullopt;
    };
    auto outgoing = [&](std::size_t k) -> std::optional<Point> {  // leaving at the start of segment k
      for (std::size_t j = k; j < n; ++j) {
        if (starts[j]) return starts[j];
      }
      return std::nullopt;
    };
    const std::optional<Point> first_out = n > 0 ? outgoing(0) : std::nullopt;
    // A subpath's start looks only forwards (as resvg does; the closing vertex is where the loop joins).
    out.push_back(MarkerVertex{MarkerVertex::Kind::Mid, s.start, vertex_angle(std::nullopt, first_out)});
    ins.push_back(std::nullopt);
    for (std::size_t k = 0; k < n; ++k) {
      std::optional<Point> next = k + 1 < n ? outgoing(k + 1) : std::nullopt;
      if (k + 1 == n && s.closed) next = first_out;  // the closing vertex joins the first segment again
      out.push_back(MarkerVertex{MarkerVertex::Kind::Mid, s.segments[k].p1, vertex_angle(incoming(k), next)});
      ins.push_back(incoming(k));
    }
  }
  if (out.empty()) return out;
  if (out.size() == 1) {
    out.push_back(out.front());
    ins.push_back(ins.front());
  }
  out.front().kind = MarkerVertex::Kind::Start;
  out.back().kind = MarkerVertex::Kind::End;
  // The path's last vertex looks only backwards, even where it closes a loop.
  if (ins.back()) out.back().angle = vertex_angle(ins.back(), std::nullopt);
  return out;
}

Path ellipse_marker_path(const Rect& box) {
  // SVG 2's equivalent path: from (cx + rx, cy) through the four quadrant points in the positive angle
  // direction, each quarter one segment (a cubic here; only its end points and tangents matter to markers).
  const double cx = (box.x0 + box.x1) / 2, cy = (box.y0 + box.y1) / 2;
  const double rx = (box.x1 - box.x0) / 2, ry = (box.y1 - box.y0) / 2;
  constexpr double k = 0.5522847498307936;  // 4/3 (sqrt(2) - 1)
  Path p;
  p.move_to(cx + rx, cy)
      .cubic_to({cx + rx, cy + k * ry}, {cx + k * rx, cy + ry}, {cx, cy + ry})
      .cubic_to({cx - k * rx, cy + ry}, {cx - rx, cy + k * ry}, {cx - rx, cy})
      .cubic_to({cx - rx, cy - k * ry}, {cx - k * rx, cy - ry}, {cx, cy - ry})
      .cubic_to({cx + k * rx, cy - ry}, {cx + rx, cy - k * ry}, {cx + rx, cy})
      .close();
  return p;
}

}  // namespace vraster::svg::detail
