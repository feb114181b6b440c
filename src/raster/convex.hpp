// Shapes whose analytic coverage is already exact.
#pragma once

#include "vraster/flatten.hpp"

namespace vraster::detail {

/// True when `lines` is one closed contour bounding a convex region, traversed once: every turn goes the same way
/// and the direction turns through one full circle (its y component changes sign exactly twice). Then every point
/// has winding 0 or the contour's single non-zero winding, each pixel sees at most those two values, and the
/// analytic accumulation equals the exact area under any fill rule: exact mode can skip the boundary sweep.
/// Rectangles, circles, ellipses, rounded rectangles and triangles pass; spikes (a turn straight back) do not.
bool is_single_convex_contour(const Polylines& lines);

}  // namespace vraster::detail
