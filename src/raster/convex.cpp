#include "raster/convex.hpp"

namespace vraster::detail {

bool is_single_convex_contour(const Polylines& lines) {
  if (lines.contour_count() != 1) return false;
  const auto pts = lines.contour(0);
  const std::size_t n = pts.size();
  if (n < 3) return false;
  int turn_sign = 0;    // sign shared by every non-zero turn
  int y_changes = 0;    // sign changes of the direction's y component, around the closed contour
  int first_dy = 0, last_dy = 0;
  Point prev{};         // previous non-zero direction
  bool have_prev = false;
  // Walk the closed contour's segments, plus the first one again so its turn is checked.
  for (std::size_t k = 0; k <= n; ++k) {
    const Point a = pts[k % n], b = pts[(k + 1) % n];
    const Point d = b - a;
    if (d.x == 0 && d.y == 0) continue;  // repeated point
    if (have_prev) {
      const double cross = prev.x * d.y - prev.y * d.x;
      if (cross == 0) {
        if (prev.x * d.x + prev.y * d.y < 0) return false;  // straight back: a spike
      } else {
        const int s = cross > 0 ? 1 : -1;
        if (turn_sign != 0 && s != turn_sign) return false;
        turn_sign = s;
      }
    }
    if (k < n) {  // count the y sign changes once around
      const int dy = d.y > 0 ? 1 : (d.y < 0 ? -1 : 0);
      if (dy != 0) {
        if (last_dy != 0 && dy != last_dy) ++y_changes;
        if (first_dy == 0) first_dy = dy;
        last_dy = dy;
      }
    }
    prev = d;
    have_prev = true;
  }
  if (first_dy != 0 && last_dy != first_dy) ++y_changes;  // the change across the closing vertex
  return turn_sign != 0 && y_changes == 2;
}

}  // namespace vraster::detail
