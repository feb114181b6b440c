// Test support: exact coverage references for self-intersecting and overlapping polygons, written independently of
// the engine (no cover/area cells, no boundary sweep).
//
// Two methods, cross-checked against each other by the tests:
//
//  1. scan_coverage (winding rules): per pixel [x, x+1] x [y, y+1], every height where something changes inside the
//     pixel is collected (vertex y's, y's of pairwise segment intersections lying in the pixel's column, y's where a
//     segment crosses the pixel's sides x or x+1). Between two consecutive such heights the filled length inside
//     [x, x+1] is a linear function of height, so the area of that sub-slab is its height times the filled length at
//     mid-height; the filled length comes from all crossings of the horizontal line at mid-height, sorted, walked
//     with their winding directions, and the rule applied to each interval.
//
//  2. trapezoid_coverage (winding rules and NonExterior): the plane is cut into horizontal slabs at every vertex y
//     and every intersection y of the whole polygon (not only inside the canvas); in a slab no two segments cross,
//     so the intervals between consecutive segments are trapezoids. Each trapezoid gets the winding number of its
//     interval; for NonExterior, trapezoids are flood-filled (union-find) through the slab boundaries wherever two
//     trapezoids share a stretch of the boundary line of positive length that no horizontal segment covers; the
//     unbounded leftmost/rightmost intervals and everything above/below the path are the exterior. Filled
//     trapezoids are clipped to each pixel (Sutherland–Hodgman) and measured by the shoelace formula.
//
// Winding convention (the engine's): a segment running downward (increasing y) counts +1 for points right of it.
// Contours are closed implicitly. Internally long double (11 more bits than the double inputs), so features of one
// double ulp (an edge tilted by one ulp, a crossing within an ulp of a vertex) are resolved. Cost is O(n^2) per
// pixel (method 1) or per image (method 2) — test sizes only.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/reference.hpp"
#include "vraster/vraster.hpp"

namespace vraster::test::exact {

/// True in optimized builds without sanitizers. Slow builds (Debug, sanitizers) run smaller inputs of the same kind,
/// so that the suites stay within their time budget there too.
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
inline constexpr bool kOptimizedBuild = true;
#else
inline constexpr bool kOptimizedBuild = false;
#endif


/// Method 1. Coverage grid (row-major, width x height) under a winding rule (not NonExterior).
std::vector<double> scan_coverage(const std::vector<Polygon>& contours, FillRule rule, int width, int height);

/// Method 2. Coverage grid under any rule, NonExterior included. `gap_tolerance`: two trapezoids are connected
/// through a slab boundary only when their common free stretch is longer than this plus the x uncertainty of the
/// segments bounding it (|dx/dy| times the rounding of the boundary height), so that the rounding of computed
/// intersection heights never opens a passage through a crossing point. Consequence: gaps narrower than that
/// (e.g. one double ulp) count as closed.
std::vector<double> trapezoid_coverage(const std::vector<Polygon>& contours, FillRule rule, int width, int height,
                                       double gap_tolerance = 1e-12);

/// Exact total filled area of the whole (unclipped) plane under the rule (trapezoid decomposition, closed form).
double total_area(const std::vector<Polygon>& contours, FillRule rule, double gap_tolerance = 1e-12);

/// Winding number at p (must not lie on a segment), by counting crossings of the horizontal line through p left
/// of p with the half-open convention min(y) <= p.y < max(y).
int winding_at(const std::vector<Polygon>& contours, Point p);

/// A polygon with n vertices uniform in [lo, hi]^2 (doubles, not snapped; usually self-intersecting).
Polygon random_polygon(std::mt19937& rng, int n, double lo, double hi);

/// The contours as closed polylines (no flattening: the engine sees exactly these points).
Polylines polylines_of(const std::vector<Polygon>& contours);

/// The engine's coverage (as doubles, row-major) of the contours under (rule, aa). Sink-contract violations are
/// appended to `violations` when given (and reported by ADD_FAILURE otherwise).
std::vector<double> engine_coverage(const std::vector<Polygon>& contours, FillRule rule, AntiAlias aa, int width,
                                    int height, std::vector<std::string>* violations = nullptr);

/// The same for a Path flattened with tolerance `tol` (clipped flattening off).
std::vector<double> engine_coverage(const Path& path, FillRule rule, AntiAlias aa, int width, int height,
                                    double tol = 0.01);

/// Compares two coverage grids pixel by pixel: |got - want| <= abs_tol + |want| * 2^-24 (the second term is the
/// rounding of the engine's coverage to float, which a CoverageSink receives). Reports the worst pixel and the
/// grids on failure; `max_error` (optional) receives the largest |got - want|.
::testing::AssertionResult grids_near(const std::vector<double>& got, const std::vector<double>& want, int width,
                                      double abs_tol, double* max_error = nullptr);

/// Sum of a grid.
double sum(const std::vector<double>& grid);

/// Readable grid (hundredths) for messages.
std::string grid_text(const std::vector<double>& grid, int width);

}  // namespace vraster::test::exact
