// vraster: flattening paths into polylines with a stated error bound.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/path.hpp"

namespace vraster {

/// Flattened contours in device space. Contour k is points[start(k) .. ends[k]).
/// `closed[k]` says whether the path closed it explicitly (fills treat every contour as closed).
struct Polylines {
  std::vector<Point> points;
  std::vector<std::uint32_t> ends;
  std::vector<std::uint8_t> closed;

  std::size_t contour_count() const { return ends.size(); }
  std::uint32_t start(std::size_t k) const { return k == 0 ? 0 : ends[k - 1]; }
  std::span<const Point> contour(std::size_t k) const {
    return std::span<const Point>(points).subspan(start(k), ends[k] - start(k));
  }
  /// Calls f(p, q) for every segment, each contour closed implicitly (last point back to the first), as fills see
  /// them. Contours of fewer than two points have no segment.
  template <class F>
  void for_each_segment(F&& f) const {
    for (std::size_t k = 0; k < contour_count(); ++k) {
      const auto pts = contour(k);
      const std::size_t n = pts.size();
      if (n < 2) continue;
      for (std::size_t i = 0; i < n; ++i) f(pts[i], pts[i + 1 == n ? 0 : i + 1]);
    }
  }

  void clear() {
    points.clear();
    ends.clear();
    closed.clear();
  }
};

/// Most points one flatten() call may produce (2^22: 64 MiB of points, and the edges the rasterizer builds from
/// them). More throws vraster::Error: the tolerance is too fine for the curves' size on the device.
inline constexpr std::size_t kMaxFlattenedPoints = std::size_t{1} << 22;

/// Default flattening tolerance in device pixels.
inline constexpr double kDefaultTolerance = 0.1;

/// Options for flatten().
struct FlattenOptions {
  /// Maximum distance between a curve and its polyline, in device pixels (> 0).
  double tolerance = kDefaultTolerance;
  /// When set, geometry whose control hull misses this device rectangle is replaced by its chord. That changes
  /// nothing inside the rectangle for fills (a curve and its chord enclose no point outside their hull), and
  /// keeps huge or far-away curves from producing millions of segments. Leave unset for strokes.
  const Rect* clip = nullptr;
};

/// Maps `path` by `transform` and appends its contours to `out` as polylines.
///
/// Error bound: every curve is split into n uniform parameter steps with n from Wang's formula,
/// n = ceil(sqrt(k * M / tolerance)) where M is the largest second difference of the device-space control points
/// (k = 1/4 for quadratics, 3/4 for cubics). Then every point of the curve lies within `tolerance` of the
/// polyline (and every polyline point within `tolerance` of the curve). Curves larger than the clip are first
/// split in halves so that n stays small; without a clip n is capped at 2^20 per curve.
/// Throws vraster::Error when a transformed coordinate is not finite, the tolerance is not positive, or the
/// result would pass kMaxFlattenedPoints.
void flatten(const Path& path, const Affine& transform, const FlattenOptions& options, Polylines& out);

/// The number of uniform segments Wang's formula asks for (exposed for tests).
int wang_segments_quad(Point p0, Point p1, Point p2, double tolerance);
int wang_segments_cubic(Point p0, Point p1, Point p2, Point p3, double tolerance);

}  // namespace vraster
