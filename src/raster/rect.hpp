// Paths that are one axis-aligned rectangle (after the transform): the rasterizer fills them without a sweep, the
// canvas turns pixel-aligned ones into clip boxes.
#pragma once

#include "vraster/flatten.hpp"
#include "vraster/geometry.hpp"

namespace vraster::detail {

/// Whether `lines` is one contour tracing an axis-aligned rectangle of non-zero area with finite corners (repeated
/// points and a closing point equal to the first are ignored). Sets `box` and the winding number of its inside
/// (+1 when its left side runs down the screen, i.e. counterclockwise on screen).
bool axis_aligned_rectangle(const Polylines& lines, Rect& box, int& winding);

}  // namespace vraster::detail
