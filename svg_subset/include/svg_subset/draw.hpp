// svg_subset: draws the resolved tree (tree.hpp) on a vraster::Canvas, with everything the tree describes:
// paint servers (gradients, patterns), clip paths, masks, group opacity as a layer, mix-blend-mode, isolation.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"
#include "vraster/canvas.hpp"
#include "vraster/flatten.hpp"
#include "vraster/image.hpp"
#include "vraster/raster.hpp"

namespace vraster::svg {

/// Settings shared by every element.
struct DrawSettings {
  AntiAlias aa = AntiAlias::Analytic;  ///< shape-rendering crispEdges still draws aliased
  double tolerance = kDefaultTolerance;
  std::optional<FillRule> rule_override;  ///< replaces the file's fill-rule (not clip-rule)
};

/// What a drawing reports back.
struct DrawStats {
  /// Fills that went over the exact-coverage work limit and were drawn analytic (callers warn about them).
  std::uint64_t exact_fallbacks = 0;
  /// Some group, clip, mask or pattern was left out: its offscreen images would have taken the pixels alive
  /// at once past 2^26 (deeply nested effects on a large image).
  bool over_budget = false;
};

/// Draws `tree` with the canvas's current transform as the viewport's (the tree's root maps its user space to
/// CSS px: scale the canvas first to draw at another size). The canvas state is the same afterwards. A core
/// limit reached while drawing one element (vraster::Error) is rethrown as a ParseError at that element.
DrawStats draw_tree(const Tree& tree, Canvas& canvas, const DrawSettings& settings = {});

/// The pixel size of the tree drawn at its intrinsic size (rounded up), or at a requested width and/or height
/// and zoom (0 = not given) as output_size() computes it for a Document.
std::pair<int, int> tree_output_size(const Tree& tree, int width = 0, int height = 0, double zoom = 0);

/// The tree cut down to the element with `id`, as resvg's --export-id renders it: the first drawn element with
/// that id in document order (use-expanded copies included), alone, under its ancestors' transforms but not their
/// group effects (opacity, clip, mask, blend mode); its own effects and resolved style are kept. The intrinsic
/// size is the element's bounding box in the viewport (fill and stroke outline, images by their viewport),
/// rounded up to whole px, and the box's top-left corner is the origin. Nothing when no drawn element has that
/// id (elements in <defs>, paint servers, hidden elements are not drawn); throws vraster::Error when the
/// element's box is empty (a fill-only straight line, say).
std::optional<Tree> element_tree(const Tree& tree, std::string_view id);

/// Draws `tree` over `image` (not cleared first), scaled from the intrinsic size to the image size on each axis.
template <class T>
DrawStats render_tree(const Tree& tree, BasicImage<T>& image, const DrawSettings& settings = {});

/// Reads and parses a file into the resolved tree (throws vraster::Error when it cannot be read).
/// Images may come from the file's folder (options.base_dir defaults to it), as load_svg.
Tree load_svg_tree(const std::string& path, ParseOptions options = {});

}  // namespace vraster::svg
