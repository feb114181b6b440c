// Frames drawn one over another: only the tiles a frame or the one before it touches are cleared and redrawn
// (Canvas::draw_frame, in src/canvas/record.cpp, uses the regions found here).
//
// Why it is exact: after clearing to the background and drawing the scene, a pixel outside every tile the plan
// touches still holds the background (no kept call can change it). So if the image held the previous frame, drawn
// the same way, the pixels outside both frames' tiles hold the background already, and clearing just the union
// of the two sets of tiles before drawing gives what clearing everything would.
#include <algorithm>
#include <string>

#include "vraster/error.hpp"
#include "vraster/scene.hpp"

namespace vraster {

std::vector<PixelBox> changed_regions(const ScenePlan& plan, const ScenePlan* previous) {
  const bool same_grid = previous == nullptr ||
                         (previous->width == plan.width && previous->height == plan.height &&
                          previous->tile_size == plan.tile_size && previous->touched_tiles.size() == plan.touched_tiles.size());
  if (!same_grid) throw Error("changed_regions: the two plans are for canvases of different sizes");
  const int ts = plan.tile_size;
  auto touched = [&](int tx, int ty) {
    const std::size_t i = static_cast<std::size_t>(ty) * plan.tiles_x + tx;
    return plan.touched_tiles[i] != 0 || (previous != nullptr && previous->touched_tiles[i] != 0);
  };
  std::vector<PixelBox> out;
  std::vector<std::size_t> open;  // boxes ending at the previous tile row, which may grow down
  for (int ty = 0; ty < plan.tiles_y; ++ty) {
    std::vector<std::size_t> next;
    for (int tx = 0; tx < plan.tiles_x;) {
      if (!touched(tx, ty)) {
        ++tx;
        continue;
      }
      const int start = tx;
      while (tx < plan.tiles_x && touched(tx, ty)) ++tx;
      const PixelBox run{start * ts, ty * ts, std::min(tx * ts, plan.width), std::min((ty + 1) * ts, plan.height)};
      const auto same = std::find_if(open.begin(), open.end(), [&](std::size_t k) {
        return out[k].x0 == run.x0 && out[k].x1 == run.x1;
      });
      if (same != open.end()) {
        out[*same].y1 = run.y1;
        next.push_back(*same);
      } else {
        out.push_back(run);
        next.push_back(out.size() - 1);
      }
    }
    open = std::move(next);
  }
  return out;
}

}  // namespace vraster
