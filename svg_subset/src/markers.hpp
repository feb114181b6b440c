// svg_subset: where markers go on a path (its vertices) and which way they point (orient="auto").
#pragma once

#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/path.hpp"

namespace vraster::svg::detail {

/// A vertex of a path as SVG's markers see it.
struct MarkerVertex {
  enum class Kind { Start, Mid, End };
  Kind kind = Kind::Mid;
  Point at;
  double angle = 0;  ///< orient="auto": degrees, the bisector of the incoming and outgoing directions
};

/// The vertices of `path`: the first is Start, the last End, every other Mid (one path of a single point has
/// a Start and an End at the same place). Each subpath's start is a vertex, and so is each segment's end (a
/// closepath ends at the subpath's start). Directions come from the segments' tangents; a zero-length segment
/// takes its neighbours' direction; at a closed subpath's start and end the closing and the first segment
/// meet.
std::vector<MarkerVertex> marker_vertices(const Path& path);

/// The path whose vertices carry a circle's or an ellipse's markers (four quarter arcs, SVG 2), for the
/// ellipse inscribed in `box`: the drawn path has more segments than that.
Path ellipse_marker_path(const Rect& box);

}  // namespace vraster::svg::detail
