// svg_subset: a document as a recorded scene (vraster/scene.hpp), for planned rendering and `vraster explain`.
#pragma once

#include "svg_subset/draw.hpp"
#include "vraster/scene.hpp"

namespace vraster::svg {

/// Records `tree` drawn at `width` x `height` pixels (scaled from its intrinsic size on each axis) into a scene.
/// Offscreen work the drawing needs while recording (mask and pattern contents, clip masks) is done then; the
/// scene holds its results. Same errors as draw_tree().
Scene record_tree(const Tree& tree, int width, int height, const DrawSettings& settings = {},
                  DrawStats* stats = nullptr);

}  // namespace vraster::svg
