// Test support: a slow, independent reference for coverage, written without the engine's cover/area cells.
//
//  - Coverage of a pixel = area of (polygon ∩ pixel square), found by clipping the polygon against the square's four
//    half-planes (Sutherland–Hodgman) and measuring the result with the shoelace formula. Signed areas of the
//    contours are summed per pixel, so the result is exact for a single simple polygon (and for disjoint simple
//    polygons of one orientation) under every fill rule; it is NOT valid for self-intersecting or overlapping input.
//  - Winding number of a point by direct crossing counting, with the rasterizer's half-open conventions.
#pragma once

#include <optional>
#include <ostream>
#include <random>
#include <vector>

#include "vraster/vraster.hpp"

namespace vraster {
/// Readable points in GoogleTest messages.
inline void PrintTo(const Point& p, std::ostream* os) { *os << "(" << p.x << ", " << p.y << ")"; }
}  // namespace vraster

namespace vraster::test {

using Polygon = std::vector<Point>;

/// Signed area by the shoelace formula (positive for clockwise on screen, i.e. with y pointing down).
double shoelace_area(const Polygon& poly);

/// The part of `poly` inside the box [x0, x1] x [y0, y1] (Sutherland–Hodgman against the four half-planes).
/// The result keeps the orientation of the input; it may contain degenerate zero-area slivers.
Polygon clip_to_box(const Polygon& poly, double x0, double y0, double x1, double y1);

/// Reference coverage grid (row-major, width x height): |sum over contours of the signed area of contour ∩ pixel|,
/// clamped to 1. Exact for simple, non-overlapping input (see above).
std::vector<double> reference_coverage(const std::vector<Polygon>& contours, int width, int height);

/// Winding number of point p by direct crossing counting: an edge from a to b counts (+1 when it runs downward,
/// i.e. b.y > a.y, else -1) when min(a.y, b.y) <= p.y < max(a.y, b.y) (half-open in y, as the rasterizer) and it
/// passes strictly left of p. Returns nothing when p lies exactly on such an edge (ambiguous), decided by an
/// orientation test that is exact for small dyadic coordinates.
std::optional<int> winding_number(const std::vector<Polygon>& contours, Point p);

/// Whether winding number w is inside under `rule` (EvenOdd, NonZero, Positive, Negative, AbsGeq2).
bool rule_inside(FillRule rule, int w);

/// The path of closed contours (move, lines, close).
Path path_of(const std::vector<Polygon>& contours);

/// Reverses the direction of every contour.
std::vector<Polygon> reversed(const std::vector<Polygon>& contours);

/// A random star-shaped (hence simple) polygon: `n` vertices at sorted distinct random angles around `center` with
/// radii in [r_min, r_max]. Orientation is random when `random_orientation`.
Polygon random_star_polygon(std::mt19937& rng, Point center, int n, double r_min, double r_max,
                            bool random_orientation = true);

/// A random polygon with vertices on the grid k/64 + 1/128 inside [lo, hi]^2 (usually self-intersecting).
Polygon random_dyadic_polygon(std::mt19937& rng, int n, double lo, double hi);

}  // namespace vraster::test
