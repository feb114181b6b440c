// svg_subset: the resolved tree (svg_subset/README.md has its spec).
//
// What parse_svg_tree() returns once CSS, inheritance, units and references are resolved: groups, paths and
// images only. No node refers to the XML any more: `use` is expanded, nested viewports are groups with a
// transform and a clip, paint servers are records with their href chains resolved, lengths are user units.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/path.hpp"
#include "vraster/raster.hpp"
#include "vraster/stroke.hpp"
#include "svg_subset/svg.hpp"

namespace vraster::text {
class FontDb;  // vraster_text/font_db.hpp
}

namespace vraster::svg {

/// Which coordinates a paint server, clip path or mask is given in.
enum class Units : std::uint8_t { UserSpaceOnUse, ObjectBoundingBox };

/// What a gradient does outside its 0..1 range.
enum class Spread : std::uint8_t { Pad, Reflect, Repeat };

/// A gradient stop, resolved: offset clamped to 0..1 and never below the previous stop's; stop-opacity folded
/// into color.a (straight, not premultiplied).
struct GradientStop {
  double offset = 0;
  Color color;
};

/// A linearGradient or radialGradient with every attribute resolved through its href chain.
struct Gradient {
  enum class Kind : std::uint8_t { Linear, Radial };
  Kind kind = Kind::Linear;
  std::string id;
  Units units = Units::ObjectBoundingBox;
  Affine transform;  ///< gradientTransform
  Spread spread = Spread::Pad;
  double x1 = 0, y1 = 0, x2 = 1, y2 = 0;                     ///< linear: the gradient vector
  double cx = 0.5, cy = 0.5, r = 0.5, fx = 0.5, fy = 0.5, fr = 0;  ///< radial: end circle, focal circle
  std::vector<GradientStop> stops;  ///< at least two (a gradient with fewer is resolved to a colour or none)
};

struct Group;

/// A pattern with its href chain resolved; `content` is in pattern space (the viewBox or content units applied).
struct Pattern {
  std::string id;
  Units units = Units::ObjectBoundingBox;          ///< patternUnits: what `rect` is in
  Units content_units = Units::UserSpaceOnUse;     ///< patternContentUnits (ignored when there is a viewBox)
  Affine transform;                                ///< patternTransform
  Rect rect;                                       ///< x, y, x + width, y + height of one tile
  std::optional<Rect> view_box;                    ///< min-x, min-y, min-x + width, min-y + height
  std::shared_ptr<const Group> content;            ///< the tile's children
};

/// Where a context paint's server lives: `space` maps the context element's user space into the shape's,
/// `box` is the context element's object bounding box in it.
struct ContextPlacement {
  Affine space;
  Rect box;
};

/// A paint, resolved: none, a colour, or a paint server record. `opacity` is fill-opacity / stroke-opacity.
struct Paint {
  enum class Kind : std::uint8_t { None, Color, Gradient, Pattern };
  Kind kind = Kind::None;
  Color color;  ///< Kind::Color (currentColor resolved); the fallback colour otherwise
  std::shared_ptr<const Gradient> gradient;
  std::shared_ptr<const Pattern> pattern;
  float opacity = 1;
  /// Gradient or Pattern: the fallback after url() (currentColor resolved; `none` is transparent), painted when
  /// the server cannot apply to the shape (objectBoundingBox units on a box without width or height). Unset:
  /// no fallback was given, and such a shape paints nothing.
  std::optional<Color> fallback;
  /// `context-fill` / `context-stroke` that took a gradient or pattern: SVG 2 places the server in the context
  /// element's user space and bounding box (the `use` element's, or the marked shape's), not the shape's. Null:
  /// the shape's own space and box. (Behind a pointer: most paints have none, and every shape holds two paints.)
  std::shared_ptr<const ContextPlacement> context;
  bool from_context = false;  ///< while the tree is built: a context paint its context element has not placed yet
};

/// A fill: paint and rule.
struct Fill {
  Paint paint;
  FillRule rule = FillRule::NonZero;
};

/// A stroke: paint and geometry, lengths in user units.
struct Stroke {
  Paint paint;
  StrokeStyle style;
};

/// A shape or <path>: geometry in the user space of its parent group. A shape that paints nothing (fill and
/// stroke none, or visibility hidden) has neither fill nor stroke: it draws nothing but still counts in the
/// bounding box of the groups around it (objectBoundingBox clip paths, masks and paints of a group).
struct PathNode {
  std::string id;
  Path path;
  std::optional<Fill> fill;
  std::optional<Stroke> stroke;
  bool stroke_first = false;  ///< paint-order: stroke before fill
  bool crisp_edges = false;   ///< shape-rendering: crispEdges / optimizeSpeed (draw aliased)
  /// The box that objectBoundingBox units of this node's paint servers refer to, when it is not the path's own
  /// bounding box (text: the whole text element's box, while the path holds one chunk of glyphs).
  std::optional<Rect> paint_box;
  int line = 0, column = 0;   ///< where the element starts in the file
};

/// A raster <image>, decoded and placed: its pixels drawn into `dest` (user units of the parent group, after
/// preserveAspectRatio), clipped to `clip` (the element's x/y/width/height viewport). An <image> that refers to
/// an SVG document becomes a Group instead (the document's root, with its viewport transform and clip).
struct ImageNode {
  std::string id;
  std::string href;
  std::shared_ptr<const Image> image;  ///< premultiplied RGBA8; null: nothing to draw (missing or undecodable)
  Rect view;                           ///< x, y, x + width, y + height of the element
  Rect dest;                           ///< where the whole image lands (preserveAspectRatio applied)
  Rect clip;                           ///< the viewport rectangle (same as view)
  bool smooth = true;                  ///< image-rendering: false for optimizeSpeed / pixelated / crisp-edges
  int line = 0, column = 0;
};

/// A clipPath, resolved: its children (paths only, with their clip-rule in fill.rule) in clip space.
struct ClipPath {
  std::string id;
  Units units = Units::UserSpaceOnUse;  ///< clipPathUnits
  Affine transform;                     ///< the clipPath's own transform
  std::shared_ptr<const Group> content;  ///< null: clips everything away (a clipPath in a reference loop)
  std::shared_ptr<const ClipPath> clip;  ///< clip-path on the clipPath itself
};

/// A mask, resolved.
struct Mask {
  std::string id;
  Units units = Units::ObjectBoundingBox;          ///< maskUnits: what `rect` is in
  Units content_units = Units::UserSpaceOnUse;     ///< maskContentUnits
  Rect rect{-0.1, -0.1, 1.1, 1.1};
  bool luminance = true;                           ///< mask-type: luminance (true) or alpha
  std::shared_ptr<const Group> content;  ///< null: masks everything away (a mask in a reference loop)
  std::shared_ptr<const Mask> mask;  ///< mask on the mask element
};

/// A node of the tree.
struct Node;

/// A group: a transform and the effects that apply to its children as one layer (opacity, blend mode,
/// isolation, clip, mask). `needs_layer()` says whether drawing it takes an offscreen layer.
struct Group {
  std::string id;
  Affine transform;  ///< maps the children's user space to the parent's
  float opacity = 1;
  std::string blend_mode = "normal";  ///< mix-blend-mode keyword
  bool isolate = false;
  std::shared_ptr<const ClipPath> clip;
  std::shared_ptr<const Mask> mask;
  std::vector<Node> children;
  bool needs_layer() const { return opacity < 1 || blend_mode != "normal" || isolate || clip || mask; }
};

struct Node {
  std::variant<Group, PathNode, ImageNode> value;
};

/// The object bounding box of a group's children (fill geometry, as SVG defines it: hidden and unpainted shapes
/// count, images by their viewport) mapped by `m`; nothing when the group has no geometry.
std::optional<Rect> object_bounds(const Group& g, const Affine& m);

/// The nodes of `g`, itself included, with those of every group below it (not clip, mask or pattern content);
/// the count stops soon after it passes `limit`.
std::size_t count_nodes(const Group& g, std::size_t limit = SIZE_MAX);

/// A parsed document as a resolved tree.
struct Tree {
  double width = 0, height = 0;  ///< intrinsic size in CSS px
  Group root;                    ///< root.transform maps the root's user space (viewBox) to the viewport
  /// The root element's CSS background-color (straight RGBA), painted over the whole viewport before the root
  /// group, as a browser paints the canvas background of a standalone SVG document; none when not given.
  std::optional<Color> background;
  std::vector<std::string> warnings;  ///< "LINE:COLUMN: message"
  std::string file;
};


/// Parses SVG text into the resolved tree. Throws ParseError (svg.hpp) only for a document that cannot be used
/// at all: malformed XML, no <svg> root, a size that cannot be resolved or is out of range, a reference loop,
/// a limit exceeded. Invalid values are treated as not given, with a warning.
/// No file is read unless `options` names a base folder, and no font unless it names fonts (see ParseOptions).
Tree parse_svg_tree(std::string_view text, const std::string& file = "<memory>", const ParseOptions& options = {});

}  // namespace vraster::svg
