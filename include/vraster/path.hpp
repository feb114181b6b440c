// vraster: the path type (move, line, quadratic, cubic, arc, close).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "vraster/geometry.hpp"

namespace vraster {

/// One path command. Each verb consumes points: Move 1, Line 1, Quad 2, Cubic 3, Close 0.
enum class Verb : std::uint8_t { Move, Line, Quad, Cubic, Close };

/// A vector path in user space.
///
/// Guarantees (checked as the path is built, trusted by every later stage):
///  - every coordinate is finite: a NaN or infinite argument (or an arc, shape or transform whose result is not
///    finite) throws vraster::Error and leaves the path exactly as it was;
///  - every contour starts with Move (a drawing command with no open contour starts one at the current point,
///    which after close() is the start of the closed contour, as in SVG);
///  - arcs are stored as cubic segments of at most 30 degrees each (relative radial error below 4e-7 of the radius).
class Path {
 public:
  Path& move_to(Point p);
  Path& line_to(Point p);
  Path& quad_to(Point control, Point p);
  Path& cubic_to(Point control1, Point control2, Point p);
  /// SVG elliptical arc from the current point to p (SVG 1.1 F.6): radii are made positive, scaled up when too
  /// small to reach p, and zero radii draw a straight line. `x_rotation_degrees` rotates the ellipse's x axis.
  Path& arc_to(double rx, double ry, double x_rotation_degrees, bool large_arc, bool sweep, Point p);
  Path& close();

  Path& move_to(double x, double y) { return move_to(Point{x, y}); }
  Path& line_to(double x, double y) { return line_to(Point{x, y}); }

  /// Closed rectangle, clockwise on screen (y down), starting at (x0, y0).
  Path& add_rect(const Rect& r);
  /// Rounded rectangle; radii are clamped to half the width and height (as SVG does).
  Path& add_round_rect(const Rect& r, double rx, double ry);
  /// Closed ellipse centred at c, clockwise on screen.
  Path& add_ellipse(Point c, double rx, double ry);
  Path& add_circle(Point c, double r) { return add_ellipse(c, r, r); }
  /// A polygon (closed) or polyline (open) through the points.
  Path& add_polygon(std::span<const Point> points, bool closed = true);
  /// Appends all contours of another path.
  Path& add_path(const Path& other);

  /// This path with every point mapped by m (throws vraster::Error when a result is not finite).
  Path transformed(const Affine& m) const;
  void transform(const Affine& m);

  /// The tight bounding box of the curve (curve extrema, not control points). Empty path: all zeros.
  Rect bounds() const;
  /// The box of all points including control points (cheaper; contains bounds()).
  Rect control_bounds() const;

  bool empty() const { return verbs_.empty(); }
  void clear();
  /// Room for this many more verbs and points (growing geometrically): for code that knows how much it will add.
  void reserve_more(std::size_t verbs, std::size_t points);
  std::span<const Verb> verbs() const { return verbs_; }
  std::span<const Point> points() const { return points_; }
  /// The current point (where the next segment starts).
  Point current_point() const { return current_; }

 private:
  struct Snapshot {
    std::size_t verbs, points;
    Point current, contour_start;
    bool contour_open;
  };
  Snapshot snapshot() const { return {verbs_.size(), points_.size(), current_, contour_start_, contour_open_}; }
  void restore(const Snapshot& s);
  /// Runs `build` (several builder calls) all or nothing: on an exception the path is restored, then it rethrows.
  template <class F>
  Path& atomically(F&& build);
  void ensure_contour();
  void arc_segments(double rx, double ry, double phi, double theta1, double dtheta);

  std::vector<Verb> verbs_;
  std::vector<Point> points_;
  Point current_{};
  Point contour_start_{};
  bool contour_open_ = false;
};

}  // namespace vraster
