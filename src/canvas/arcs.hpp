// Canvas path geometry: the HTML canvas arc, arcTo and roundRect steps as point lists (user space), before the
// canvas maps them by its transform.
#pragma once

#include <vector>

#include "vraster/geometry.hpp"

namespace vraster::canvas_detail {

/// An elliptical arc as cubic Beziers: `points` holds the start point, then three points (two controls and an end)
/// per cubic. Pieces span at most 30 degrees (radial error below 4e-7 of the radius, as Path's own arcs).
struct ArcPoints {
  std::vector<Point> points;
  void clear() { points.clear(); }
};

/// The signed sweep of canvas arc()/ellipse() from a0 to a1 (the spec's rule): clockwise (positive, y down)
/// unless `ccw`; a difference of 2 pi or more in the drawing direction is a full turn, anything else is reduced
/// to [0, 2 pi) in that direction (so equal angles give an empty arc).
double canvas_arc_sweep(double a0, double a1, bool ccw);

/// Appends the arc of the ellipse centred at `c` with radii rx, ry (>= 0) whose x axis is rotated by `rotation`,
/// from angle a0 over `sweep` radians, to `out` (start point included).
void append_ellipse_arc(Point c, double rx, double ry, double rotation, double a0, double sweep, ArcPoints& out);

/// arcTo geometry for a corner p0 -> p1 -> p2 with radius r > 0, p0 != p1, p1 != p2, not collinear: the arc
/// (start = tangent point on p0p1, end = tangent point on p1p2) appended to `out`. Returns false when the
/// corner is too flat to give finite tangent points (the caller draws a line to p1 instead).
bool append_arc_to(Point p0, Point p1, Point p2, double r, ArcPoints& out);

}  // namespace vraster::canvas_detail
