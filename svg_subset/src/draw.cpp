// svg_subset: drawing the resolved tree on a vraster::Canvas (design notes: docs/design.md, "SVG: drawing the tree on
// the canvas").
//
// Groups map to save/transform/restore, and to a canvas layer only when an effect needs one (opacity, a blend
// mode, isolation, a mask, a clip the canvas cannot express as one clip() call). Clip paths and masks become
// coverage images in device pixels, used as the layer's alpha mask: a clipPath's children form a union, which
// the canvas's intersecting clip() cannot express, so the children are drawn white into an offscreen image.
#include "svg_subset/draw.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "image_element.hpp"
#include "svg_subset/svg.hpp"
#include "vraster/composite.hpp"
#include "vraster/files.hpp"

namespace vraster::svg {

namespace {

// Offscreen images in flight at once (patterns in patterns, masks on masks): deeper content draws nothing.
constexpr int kMaxNesting = 12;
// Offscreen pixels alive at once (layers, clip and mask coverage, pattern tiles being drawn), 256 MiB at 8
// bits: past it a group, clip, mask or pattern is not drawn (nested effects on a large image would otherwise
// multiply the image's size by the nesting depth).
constexpr double kMaxLivePixels = double(std::int64_t{1} << 26);
// Largest pattern tile, in pixels: 2^24, and 4 times the canvas (past that a tile is drawn below device
// resolution: so large a tile shows one corner at most).
constexpr double kMaxTilePixels = double(1 << 24);
constexpr double kMinTileCap = double(1 << 16);

bool usable_box(const Rect& r) {
  return r.width() > 0 && r.height() > 0 && std::isfinite(r.width()) && std::isfinite(r.height());
}

/// Maps the unit square onto `box` (objectBoundingBox units).
Affine box_transform(const Rect& box) { return {box.width(), 0, 0, box.height(), box.x0, box.y0}; }

Rect map_rect(const Rect& r, const Rect& box) {
  return {box.x0 + r.x0 * box.width(), box.y0 + r.y0 * box.height(), box.x0 + r.x1 * box.width(),
          box.y0 + r.y1 * box.height()};
}

void include(std::optional<Rect>& acc, const Rect& r) {
  if (!acc) {
    acc = r;
    return;
  }
  acc->include({r.x0, r.y0});
  acc->include({r.x1, r.y1});
}

Rect transformed_rect(const Rect& r, const Affine& m) {
  Rect out = Rect::from_point(m.apply({r.x0, r.y0}));
  out.include(m.apply({r.x1, r.y0}));
  out.include(m.apply({r.x0, r.y1}));
  out.include(m.apply({r.x1, r.y1}));
  return out;
}

/// Where a group's children can paint, mapped by `m` (conservative: a stroke reaches at most half its width
/// times the larger of the miter limit and 1.5 (square caps: 1/sqrt(2) of the width) past the path).
std::optional<Rect> paint_bounds(const Group& g, const Affine& m) {
  std::optional<Rect> box;
  for (const Node& child : g.children) {
    if (const PathNode* p = std::get_if<PathNode>(&child.value)) {
      if (p->path.empty() || (!p->fill && !p->stroke)) continue;
      Rect r = p->path.control_bounds();
      if (p->stroke) {
        const double reach = 0.5 * p->stroke->style.width * std::max(p->stroke->style.miter_limit, 1.5);
        r = {r.x0 - reach, r.y0 - reach, r.x1 + reach, r.y1 + reach};
      }
      include(box, transformed_rect(r, m));
    } else if (const Group* sub = std::get_if<Group>(&child.value)) {
      if (const auto r = paint_bounds(*sub, m * sub->transform)) include(box, *r);
    } else if (const ImageNode* image = std::get_if<ImageNode>(&child.value)) {
      include(box, transformed_rect(image->clip, m));
    }
  }
  return box;
}

/// A device-pixel rectangle.
struct Area {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

Area intersect(const Area& a, const Area& b) {
  const Area r{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
  return r.empty() ? Area{} : r;
}

/// Device pixels that `r` (user space, mapped by `m`) can touch, inside a w x h canvas.
Area device_area(const Rect& r, const Affine& m, int w, int h) {
  const Rect d = transformed_rect(r, m);
  if (!(d.x0 <= d.x1) || !(d.y0 <= d.y1)) return {};  // NaN
  auto clamp = [](double v, int hi) { return static_cast<int>(std::clamp(v, 0.0, double(hi))); };
  return {clamp(std::floor(d.x0), w), clamp(std::floor(d.y0), h), clamp(std::ceil(d.x1), w),
          clamp(std::ceil(d.y1), h)};
}

/// Pixels counted against kMaxLivePixels while this object lives.
class Reservation {
 public:
  Reservation(double& live, double pixels) : live_(live), pixels_(pixels) { live_ += pixels_; }
  ~Reservation() { live_ -= pixels_; }
  Reservation(const Reservation&) = delete;
  Reservation& operator=(const Reservation&) = delete;

 private:
  double& live_;
  double pixels_;
};

/// What every Drawer of one draw_tree call shares.
struct Shared {
  const DrawSettings& settings;
  const std::string& file;
  DrawStats& stats;
  double live_pixels = 0;

  /// Counts `pixels` as alive until the returned object goes; null (and a note in stats) when over the limit.
  std::shared_ptr<Reservation> reserve(double pixels) {
    if (!(live_pixels + pixels <= kMaxLivePixels)) {
      stats.over_budget = true;
      return nullptr;
    }
    return std::make_shared<Reservation>(live_pixels, pixels);
  }
};

/// A coverage image in device pixels (every channel holds the coverage, so it works as an alpha mask), its
/// top-left pixel at (x, y). Pixels outside it have coverage 0.
struct Coverage {
  std::shared_ptr<Image> image;
  int x = 0, y = 0;
  std::shared_ptr<Reservation> hold;  // its pixels, counted while it lives
};

bool uses_box(const ClipPath* clip) {
  for (; clip; clip = clip->clip.get()) {
    if (clip->units == Units::ObjectBoundingBox) return true;
  }
  return false;
}

bool uses_box(const Mask* mask) {
  for (; mask; mask = mask->mask.get()) {
    if (mask->units == Units::ObjectBoundingBox || mask->content_units == Units::ObjectBoundingBox) return true;
  }
  return false;
}

/// Multiplies `a` by `b` where they overlap; zero elsewhere.
void multiply(Coverage& a, const Coverage& b) {
  Image& img = *a.image;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const int bx = x + a.x - b.x, by = y + a.y - b.y;
      const int v = bx >= 0 && by >= 0 && bx < b.image->width && by < b.image->height ? b.image->pixel(bx, by)[3] : 0;
      std::uint8_t* px = img.pixel(x, y);
      const auto m = static_cast<std::uint8_t>((px[3] * v + 127) / 255);
      px[0] = px[1] = px[2] = px[3] = m;
    }
  }
}

/// The last stop's colour: what SVG paints for a gradient whose vector or radius is zero.
Color last_stop(const Gradient& g) { return g.stops.empty() ? Color::transparent() : g.stops.back().color; }

class Drawer {
 public:
  /// `clip_mode`: drawing a clipPath's content (paths filled opaque with their clip-rule; paint, stroke,
  /// opacity, masks and images have no effect; clip-path on children does).
  Drawer(Canvas& canvas, Shared& shared, int nesting, bool clip_mode)
      : canvas_(canvas), shared_(shared), settings_(shared.settings), nesting_(nesting), clip_mode_(clip_mode) {}

  void group(const Group& g) {
    if (!clip_mode_ && !(g.opacity > 0)) return;
    if (g.clip && !g.clip->content) return;  // a clipPath in a reference loop clips everything away
    if (!clip_mode_ && g.mask && !g.mask->content) return;
    canvas_.save();
    canvas_.transform(g.transform);
    if (!clip_mode_ && opacity_only_on_one_paint(g)) {
      canvas_.set_global_alpha(g.opacity);  // one fill or stroke: its alpha times the opacity is the layer's result
      children(g);
    } else if (clip_mode_ ? g.clip != nullptr : g.needs_layer()) {
      effects(g);
    } else {
      children(g);
    }
    canvas_.restore();
  }

 private:
  /// Whether the group's only effect is opacity and it draws exactly one fill or one stroke.
  static bool opacity_only_on_one_paint(const Group& g) {
    if (!(g.opacity < 1) || g.clip || g.mask || g.isolate || g.blend_mode != "normal" || g.children.size() != 1) {
      return false;
    }
    const PathNode* p = std::get_if<PathNode>(&g.children[0].value);
    return p && (p->fill.has_value() != p->stroke.has_value());
  }

  void children(const Group& g) {
    for (const Node& child : g.children) {
      if (const Group* sub = std::get_if<Group>(&child.value)) {
        group(*sub);
      } else if (const PathNode* p = std::get_if<PathNode>(&child.value)) {
        path(*p);
      } else if (const ImageNode* image = std::get_if<ImageNode>(&child.value)) {
        this->image(*image);
      }
    }
  }

  /// A group with effects: the clip (a canvas clip when it is one path, else a coverage image), the mask (a
  /// coverage image), then a layer with opacity and blend mode unless only a plain clip was needed.
  void effects(const Group& g) {
    const Affine ctm = canvas_.get_transform();
    // The device pixels the children can touch: the layer and the offscreen images need no more. Clipping to
    // them (a pixel-aligned rectangle: no mask, no change to what is drawn) keeps the canvas's layer that small.
    const std::optional<Rect> reach = paint_bounds(g, Affine{});
    if (!reach) return;
    const Area area = device_area(*reach, ctm, canvas_.width(), canvas_.height());
    if (area.empty()) return;
    Path device_rect;
    device_rect.add_rect(Rect{double(area.x0), double(area.y0), double(area.x1), double(area.y1)});
    canvas_.set_transform(Affine{});
    canvas_.clip(device_rect, FillRule::NonZero);
    canvas_.set_transform(ctm);
    // The box costs a pass over every path below: only when objectBoundingBox units need it.
    const bool box_needed = uses_box(g.clip.get()) || (!clip_mode_ && uses_box(g.mask.get()));
    const std::optional<Rect> bbox = box_needed ? object_bounds(g, Affine{}) : std::nullopt;
    std::optional<Coverage> mask;
    std::shared_ptr<Reservation> clip_hold;
    if (g.clip) {
      Path clip_path;
      FillRule rule = FillRule::NonZero;
      if (single_clip_path(*g.clip, bbox, clip_path, rule)) {
        // The canvas keeps a coverage plane over the clip's pixels unless it is a pixel-aligned rectangle:
        // counted like an offscreen image (nested viewports on a large image would pile them up).
        const Area reach_of_clip = intersect(device_area(clip_path.control_bounds(), ctm, canvas_.width(),
                                                         canvas_.height()), area);
        clip_hold = shared_.reserve(double(reach_of_clip.width()) * reach_of_clip.height());
        if (!clip_hold) return;
        canvas_.set_anti_alias(settings_.aa);  // not what the last path drawn left (crispEdges draws aliased)
        canvas_.clip(clip_path, rule);
      } else {
        mask = clip_coverage(*g.clip, bbox, ctm, area);
        if (!mask) return;  // clipped away
      }
    }
    if (g.mask && !clip_mode_) {
      std::optional<Coverage> m = mask_coverage(*g.mask, bbox, ctm, area);
      if (!m) return;  // masked away
      if (mask) multiply(*m, *mask);
      mask = std::move(m);
    }
    LayerOptions options;
    if (!clip_mode_) {
      options.opacity = g.opacity;
      if (g.blend_mode != "normal" && !parse_composite_op(g.blend_mode, options.op)) options.op = CompositeOp::SourceOver;
    }
    if (!mask && options.opacity >= 1 && options.op == CompositeOp::SourceOver && (clip_mode_ || !g.isolate)) {
      children(g);  // only a clip: no layer needed
      return;
    }
    const std::shared_ptr<Reservation> hold = shared_.reserve(double(area.width()) * area.height());
    if (!hold) return;  // too many pixels alive already: the group is left out
    if (mask) {
      options.mask = mask->image;
      options.mask_x = mask->x;
      options.mask_y = mask->y;
      options.mask_mode = MaskMode::Alpha;
    }
    canvas_.begin_layer(options);
    children(g);
    canvas_.end_layer();
  }

  /// The clip-path's transform from clip content space to the clipped element's user space, or nothing when
  /// objectBoundingBox units meet an element without a usable box (then nothing is drawn).
  static std::optional<Affine> clip_space(const ClipPath& clip, const std::optional<Rect>& bbox) {
    if (clip.units == Units::UserSpaceOnUse) return clip.transform;
    if (!bbox || !usable_box(*bbox)) return std::nullopt;
    return clip.transform * box_transform(*bbox);
  }

  /// When the clip is one path with nothing else (no clip on the clipPath or inside it): that path in the
  /// element's user space, for canvas clip() (the fast path: no offscreen image, no layer).
  static bool single_clip_path(const ClipPath& clip, const std::optional<Rect>& bbox, Path& out, FillRule& rule) {
    if (clip.clip || !clip.content) return false;
    std::optional<Affine> m = clip_space(clip, bbox);
    if (!m) return false;
    const Group* g = clip.content.get();
    while (g->children.size() == 1) {
      const Node& child = g->children[0];
      if (const PathNode* p = std::get_if<PathNode>(&child.value)) {
        if (!p->fill || p->crisp_edges) return false;
        out = p->path.transformed(*m);
        rule = p->fill->rule;
        return true;
      }
      const Group* sub = std::get_if<Group>(&child.value);
      if (!sub || sub->clip) return false;
      *m = *m * sub->transform;
      g = sub;
    }
    return false;
  }

  /// A transparent image covering `area` and a canvas on it whose transform is `ctm` moved to the image.
  struct Offscreen {
    std::shared_ptr<Image> image;
    std::unique_ptr<Canvas> canvas;
  };
  Offscreen offscreen(const Area& area, const Affine& ctm) const {
    Offscreen o;
    o.image = std::make_shared<Image>(area.width(), area.height());
    o.canvas = std::make_unique<Canvas>(*o.image);
    o.canvas->set_transform(Affine::translate(-area.x0, -area.y0) * ctm);
    o.canvas->set_anti_alias(settings_.aa);
    o.canvas->set_tolerance(settings_.tolerance);
    return o;
  }

  /// The clip as coverage: every child path filled into an offscreen image (their union), times the clip on the
  /// clipPath itself, over no more than `limit` (the pixels the clipped group can touch). Nothing: everything is
  /// clipped away.
  std::optional<Coverage> clip_coverage(const ClipPath& clip, const std::optional<Rect>& bbox, const Affine& ctm,
                                        const Area& limit) {
    if (!clip.content || nesting_ >= kMaxNesting) return std::nullopt;
    const std::optional<Affine> m = clip_space(clip, bbox);
    if (!m) return std::nullopt;
    const std::optional<Rect> content = object_bounds(*clip.content, *m);
    if (!content) return std::nullopt;
    const Area area = intersect(device_area(*content, ctm, canvas_.width(), canvas_.height()), limit);
    if (area.empty()) return std::nullopt;
    std::shared_ptr<Reservation> hold = shared_.reserve(double(area.width()) * area.height());
    if (!hold) return std::nullopt;
    Offscreen o = offscreen(area, ctm * *m);
    Drawer(*o.canvas, shared_, nesting_ + 1, true).group(*clip.content);
    shared_.stats.exact_fallbacks += o.canvas->exact_fallbacks();
    Coverage out{o.image, area.x0, area.y0, std::move(hold)};
    if (clip.clip) {
      const std::optional<Coverage> inner = clip_coverage(*clip.clip, bbox, ctm, limit);
      if (!inner) return std::nullopt;
      multiply(out, *inner);
    }
    return out;
  }

  /// The mask as coverage: its content drawn inside the mask rectangle, turned into luminance or alpha, times
  /// the mask on the mask element, over no more than `limit`. Nothing: everything is masked away.
  std::optional<Coverage> mask_coverage(const Mask& mask, const std::optional<Rect>& bbox, const Affine& ctm,
                                        const Area& limit) {
    if (!mask.content || nesting_ >= kMaxNesting) return std::nullopt;
    const bool box_units = mask.units == Units::ObjectBoundingBox || mask.content_units == Units::ObjectBoundingBox;
    if (box_units && (!bbox || !usable_box(*bbox))) return std::nullopt;
    const Rect rect = mask.units == Units::ObjectBoundingBox ? map_rect(mask.rect, *bbox) : mask.rect;
    if (!usable_box(rect)) return std::nullopt;
    const Area area = intersect(device_area(rect, ctm, canvas_.width(), canvas_.height()), limit);
    if (area.empty()) return std::nullopt;
    std::shared_ptr<Reservation> hold = shared_.reserve(double(area.width()) * area.height());
    if (!hold) return std::nullopt;
    Offscreen o = offscreen(area, ctm);
    // Clip to the mask rectangle unless it covers the whole offscreen image anyway (a clip that is not
    // pixel-aligned costs the canvas a coverage plane the size of the image).
    const Rect device = transformed_rect(rect, ctm);
    const bool covers = ctm.b == 0 && ctm.c == 0 && device.x0 <= area.x0 && device.y0 <= area.y0 &&
                        device.x1 >= area.x1 && device.y1 >= area.y1;
    if (!covers) {
      Path r;
      r.add_rect(rect);
      o.canvas->clip(r, FillRule::NonZero);
    }
    if (mask.content_units == Units::ObjectBoundingBox) o.canvas->transform(box_transform(*bbox));
    Drawer(*o.canvas, shared_, nesting_ + 1, false).group(*mask.content);
    shared_.stats.exact_fallbacks += o.canvas->exact_fallbacks();
    // Luminance of the premultiplied colour = luminance of the colour times its alpha (sRGB coefficients).
    Image& img = *o.image;
    for (std::size_t i = 0; i < img.data.size(); i += 4) {
      std::uint8_t* px = img.data.data() + i;
      const double v = mask.luminance ? 0.2125 * px[0] + 0.7154 * px[1] + 0.0721 * px[2] : px[3];
      px[0] = px[1] = px[2] = px[3] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
    }
    Coverage out{o.image, area.x0, area.y0, std::move(hold)};
    if (mask.mask) {
      const std::optional<Coverage> inner = mask_coverage(*mask.mask, bbox, ctm, limit);
      if (!inner) return std::nullopt;
      multiply(out, *inner);
    }
    return out;
  }

  // ---- paints ----

  /// The canvas paint for a fill or stroke of `shape` (whose box objectBoundingBox units refer to).
  std::optional<vraster::Paint> paint(const svg::Paint& p, const PathNode& shape) {
    // A context paint (SVG 2) refers to the context element's user space and box, not the shape's.
    auto bbox = [&] {
      return p.context ? p.context->box : shape.paint_box ? *shape.paint_box : shape.path.bounds();
    };
    const Affine space = p.context ? p.context->space : Affine{};
    // A server in objectBoundingBox units cannot apply to a box without area (a horizontal or vertical line):
    // the fallback colour paints instead when there is one (SVG 2, 13.2), else nothing.
    const bool box_units =
        (p.kind == svg::Paint::Kind::Gradient && p.gradient && p.gradient->units == Units::ObjectBoundingBox) ||
        (p.kind == svg::Paint::Kind::Pattern && p.pattern &&
         (p.pattern->units == Units::ObjectBoundingBox ||
          (p.pattern->content_units == Units::ObjectBoundingBox && !p.pattern->view_box)));
    if (box_units && !usable_box(bbox())) return p.fallback ? solid(*p.fallback, p.opacity) : std::nullopt;
    switch (p.kind) {
      case svg::Paint::Kind::None:
        return std::nullopt;
      case svg::Paint::Kind::Color:
        return solid(p.color, p.opacity);
      case svg::Paint::Kind::Gradient:
        return p.gradient ? gradient(*p.gradient, bbox(), space, p.opacity) : std::nullopt;
      case svg::Paint::Kind::Pattern:
        return p.pattern ? pattern(*p.pattern, bbox(), space, p.opacity) : std::nullopt;
    }
    return std::nullopt;
  }

  static std::optional<vraster::Paint> solid(Color c, float opacity) {
    c.a *= opacity;
    if (!(c.a > 0)) return std::nullopt;
    return vraster::Paint::solid(c);
  }

  /// `space` maps the space the gradient is placed in (and `bbox` is given in) into the shape's user space.
  static std::optional<vraster::Paint> gradient(const Gradient& g, const Rect& bbox, const Affine& space,
                                                float opacity) {
    Affine to_user = g.transform;
    if (g.units == Units::ObjectBoundingBox) {
      if (!usable_box(bbox)) return std::nullopt;  // SVG: a box without area paints nothing
      to_user = box_transform(bbox) * g.transform;
    }
    vraster::Paint out;
    if (g.kind == Gradient::Kind::Linear) {
      if (g.x1 == g.x2 && g.y1 == g.y2) return solid(last_stop(g), opacity);
      out = vraster::Paint::linear({g.x1, g.y1}, {g.x2, g.y2});
    } else {
      if (!(g.r > 0)) return solid(last_stop(g), opacity);
      // SVG 2: the focal circle (fx, fy, fr) is where offset 0 starts, the end circle (cx, cy, r) offset 1.
      out = vraster::Paint::radial({g.fx, g.fy}, std::max(0.0, g.fr), {g.cx, g.cy}, g.r);
    }
    // Stops with equal offsets make a step. The canvas pads below offset 0 with the colour at 0, which is the last
    // of a leading run of equal offsets; resvg pads with the first: the run's later stops move up by a hair.
    const std::size_t n = g.stops.size();
    std::size_t run = 1;
    while (run < n && g.stops[run].offset == g.stops[0].offset) ++run;
    const double lifted = std::min(g.stops[0].offset + 1e-6, run < n ? g.stops[run].offset : 1.0);
    for (std::size_t i = 0; i < n; ++i) out.add_stop(i > 0 && i < run ? lifted : g.stops[i].offset, g.stops[i].color);
    out.set_extend(g.spread == Spread::Reflect ? Extend::Reflect
                   : g.spread == Spread::Repeat ? Extend::Repeat
                                                : Extend::Pad);
    out.set_transform(space * to_user);
    out.set_opacity(opacity);
    return out;
  }

  /// A pattern: one tile drawn into an image at about device resolution, repeated by a pattern paint.
  /// `space` as for gradients.
  std::optional<vraster::Paint> pattern(const Pattern& pat, const Rect& bbox, const Affine& space, float opacity) {
    if (!pat.content || nesting_ >= kMaxNesting) return std::nullopt;
    const bool box_units = pat.units == Units::ObjectBoundingBox ||
                           (pat.content_units == Units::ObjectBoundingBox && !pat.view_box);
    if (box_units && !usable_box(bbox)) return std::nullopt;
    const Rect tile = pat.units == Units::ObjectBoundingBox ? map_rect(pat.rect, bbox) : pat.rect;
    if (!usable_box(tile)) return std::nullopt;
    const double tw = tile.width(), th = tile.height();
    // Device scale along each tile axis.
    const Affine pattern_space = space * pat.transform;
    const Affine m = canvas_.get_transform() * pattern_space;
    // Rounding noise (a context paint's space undoes the shape's transform) must not add a pixel to the tile.
    auto whole_pixels = [](double v) { return std::ceil(v - 1e-6 * std::max(1.0, v)); };
    double iw = whole_pixels(tw * std::hypot(m.a, m.b)), ih = whole_pixels(th * std::hypot(m.c, m.d));
    if (!std::isfinite(iw) || !std::isfinite(ih)) return std::nullopt;
    iw = std::clamp(iw, 1.0, double(kMaxImageSide));
    ih = std::clamp(ih, 1.0, double(kMaxImageSide));
    const double cap = std::min(kMaxTilePixels, std::max(kMinTileCap, 4.0 * canvas_.width() * canvas_.height()));
    if (iw * ih > cap) {
      const double k = std::sqrt(cap / (iw * ih));
      iw = std::max(1.0, std::floor(iw * k));
      ih = std::max(1.0, std::floor(ih * k));
    }
    // Counted while the tile's content is drawn (nested patterns stack up there); a finished tile is not: it
    // lives only while one fill or stroke is drawn, so one at a time.
    const std::shared_ptr<Reservation> hold = shared_.reserve(iw * ih);
    if (!hold) return std::nullopt;
    auto image = std::make_shared<Image>(static_cast<int>(iw), static_cast<int>(ih));
    {
      Canvas c(*image);
      c.set_anti_alias(settings_.aa);
      c.set_tolerance(settings_.tolerance);
      c.scale(iw / tw, ih / th);
      if (pat.view_box) {
        // The viewBox fills the tile (preserveAspectRatio's default, xMidYMid meet).
        const Rect& vb = *pat.view_box;
        if (!usable_box(vb)) return std::nullopt;
        const double s = std::min(tw / vb.width(), th / vb.height());
        c.translate((tw - vb.width() * s) / 2 - vb.x0 * s, (th - vb.height() * s) / 2 - vb.y0 * s);
        c.scale(s, s);
      } else if (pat.content_units == Units::ObjectBoundingBox) {
        c.scale(bbox.width(), bbox.height());
      }
      Drawer(c, shared_, nesting_ + 1, false).group(*pat.content);
      shared_.stats.exact_fallbacks += c.exact_fallbacks();
    }
    vraster::Paint out = vraster::Paint::pattern(std::shared_ptr<const Image>(image));
    out.set_extend(Extend::Repeat);
    const Affine to_user = pattern_space * Affine::translate(tile.x0, tile.y0) * Affine::scale(tw / iw, th / ih);
    out.set_transform(to_user);
    // A tile drawn at exactly device resolution, with no rotation or skew on the way, is copied pixel for pixel:
    // filtering would only blur its edges (a tile starting at half a pixel would smear every seam). Rotations
    // that happen to cancel still resample, as in resvg.
    const Affine ctm = canvas_.get_transform();
    const Affine to_device = ctm * to_user;
    const bool axis_aligned = ctm.b == 0 && ctm.c == 0 && pattern_space.b == 0 && pattern_space.c == 0;
    const bool pixel_exact = axis_aligned && std::abs(to_device.a - 1) < 1e-9 && std::abs(to_device.d - 1) < 1e-9;
    out.set_filter(pixel_exact ? ImageFilter::Nearest : ImageFilter::Bilinear);
    out.set_opacity(opacity);
    return out;
  }

  // ---- leaves ----

  void set_stroke_style(const StrokeStyle& s) {
    canvas_.set_line_width(s.width);
    canvas_.set_line_cap(s.cap);
    canvas_.set_line_join(s.join);
    canvas_.set_miter_limit(s.miter_limit);
    canvas_.set_line_dash(s.dashes);
    canvas_.set_line_dash_offset(s.dash_offset);
  }

  void path(const PathNode& p) {
    canvas_.set_anti_alias(p.crisp_edges ? AntiAlias::None : settings_.aa);
    if (clip_mode_) {
      if (!p.fill) return;
      canvas_.set_fill_color(Color{1, 1, 1, 1});
      canvas_.fill(p.path, p.fill->rule);
      return;
    }
    const char* what = "fill";
    auto fill = [&] {
      what = "fill";
      if (!p.fill) return;
      const std::optional<vraster::Paint> paint = this->paint(p.fill->paint, p);
      if (!paint) return;
      canvas_.set_fill_paint(*paint);
      canvas_.fill(p.path, settings_.rule_override.value_or(p.fill->rule));
    };
    auto stroke = [&] {
      what = "stroke";
      if (!p.stroke) return;
      const std::optional<vraster::Paint> paint = this->paint(p.stroke->paint, p);
      if (!paint) return;
      canvas_.set_stroke_paint(*paint);
      set_stroke_style(p.stroke->style);
      canvas_.stroke(p.path);
    };
    try {
      if (p.stroke_first) {
        stroke();
        fill();
      } else {
        fill();
        stroke();
      }
    } catch (const ParseError&) {
      throw;
    } catch (const Error& e) {
      // A limit of the core (work or memory per draw call): the message names the element.
      throw ParseError(shared_.file, p.line, p.column, std::string("cannot draw the ") + what + " of this element: " + e.what());
    }
  }

  void image(const ImageNode& n) {
    if (clip_mode_ || !n.image || n.image->width <= 0 || n.image->height <= 0) return;
    try {
      canvas_.save();
      Path r;
      r.add_rect(n.clip);
      canvas_.clip(r, FillRule::NonZero);
      canvas_.set_image_smoothing(n.smooth);
      canvas_.draw_image(n.image, n.dest.x0, n.dest.y0, n.dest.width(), n.dest.height());
      canvas_.restore();
    } catch (const Error& e) {
      throw ParseError(shared_.file, n.line, n.column, std::string("cannot draw this image: ") + e.what());
    }
  }

  Canvas& canvas_;
  Shared& shared_;
  const DrawSettings& settings_;
  int nesting_;
  bool clip_mode_;
};

}  // namespace

std::size_t count_nodes(const Group& g, std::size_t limit) {
  std::size_t n = 1;
  for (const Node& child : g.children) {
    if (n > limit) break;
    const Group* sub = std::get_if<Group>(&child.value);
    n += sub ? count_nodes(*sub, limit - n) : 1;
  }
  return n;
}

std::optional<Rect> object_bounds(const Group& g, const Affine& m) {
  std::optional<Rect> box;
  for (const Node& child : g.children) {
    if (const PathNode* p = std::get_if<PathNode>(&child.value)) {
      if (p->paint_box) {
        include(box, transformed_rect(*p->paint_box, m));  // text: its glyph cells' box (SVG 2, 8.10)
      } else if (!p->path.empty()) {
        include(box, p->path.transformed(m).bounds());
      }
    } else if (const Group* sub = std::get_if<Group>(&child.value)) {
      if (const auto r = object_bounds(*sub, m * sub->transform)) include(box, *r);
    } else if (const ImageNode* image = std::get_if<ImageNode>(&child.value)) {
      include(box, transformed_rect(image->view, m));
    }
  }
  return box;
}

DrawStats draw_tree(const Tree& tree, Canvas& canvas, const DrawSettings& settings) {
  DrawStats stats;
  const std::uint64_t fallbacks_before = canvas.exact_fallbacks();
  canvas.save();
  canvas.set_anti_alias(settings.aa);
  canvas.set_tolerance(settings.tolerance);
  Shared shared{settings, tree.file, stats};
  if (tree.background && tree.background->a > 0) {
    canvas.set_fill_color(*tree.background);
    canvas.fill_rect(0, 0, tree.width, tree.height);
  }
  Drawer(canvas, shared, 0, false).group(tree.root);
  canvas.restore();
  stats.exact_fallbacks += canvas.exact_fallbacks() - fallbacks_before;
  return stats;
}

std::pair<int, int> tree_output_size(const Tree& tree, int width, int height, double zoom) {
  Document sizes;
  sizes.intrinsic_width = tree.width;
  sizes.intrinsic_height = tree.height;
  // Fractional sizes round up so the drawing is not cut off (as to_document does).
  sizes.width = static_cast<int>(std::ceil(tree.width - 1e-9));
  sizes.height = static_cast<int>(std::ceil(tree.height - 1e-9));
  return output_size(sizes, width, height, zoom);
}

namespace {

/// Where `node` paints, mapped by `m` (its parent's user space to the viewport), added to `box`: fill geometry and
/// the exact stroke outline (resvg's stroke bounding box), images by their viewport.
void include_painted(std::optional<Rect>& box, const Node& node, const Affine& m) {
  if (const PathNode* p = std::get_if<PathNode>(&node.value)) {
    if (p->path.empty()) return;
    include(box, p->path.transformed(m).bounds());
    if (!p->stroke) return;
    try {
      const Path outline = stroke_to_path(p->path, p->stroke->style, user_tolerance(m, 0.05));
      if (!outline.empty()) include(box, outline.transformed(m).bounds());
    } catch (const Error&) {  // an outline past the point limit: the conservative reach instead
      Group alone;
      alone.children.push_back(node);
      if (const auto r = paint_bounds(alone, m)) include(box, *r);
    }
  } else if (const Group* g = std::get_if<Group>(&node.value)) {
    for (const Node& child : g->children) include_painted(box, child, m * g->transform);
  } else if (const ImageNode* image = std::get_if<ImageNode>(&node.value)) {
    include(box, transformed_rect(image->clip, m));
  }
}

/// The first node with `id` below `g` in document order (depth first); `m` is updated to the transform from
/// that node's parent's user space to the viewport.
const Node* find_node(const Group& g, std::string_view id, Affine& m) {
  for (const Node& child : g.children) {
    if (std::visit([](const auto& n) -> const std::string& { return n.id; }, child.value) == id) return &child;
    const Group* sub = std::get_if<Group>(&child.value);
    if (!sub) continue;
    Affine inner = m * sub->transform;
    if (const Node* found = find_node(*sub, id, inner)) {
      m = inner;
      return found;
    }
  }
  return nullptr;
}

}  // namespace

std::optional<Tree> element_tree(const Tree& tree, std::string_view id) {
  if (id.empty()) return std::nullopt;
  Node node;
  Affine m;  // the node's parent's user space to the viewport
  if (tree.root.id == id) {
    node.value = tree.root;
  } else {
    m = tree.root.transform;
    const Node* found = find_node(tree.root, id, m);
    if (!found) return std::nullopt;
    node = *found;
  }
  std::optional<Rect> box;
  include_painted(box, node, m);
  if (!box || !usable_box(*box)) {
    throw Error("the element with id " + vraster::quoted(id) + " draws nothing: its bounding box is empty");
  }
  Tree out;
  out.file = tree.file;
  out.warnings = tree.warnings;
  // Whole px, so that the element is drawn 1:1 at its own size (the box grows right and down).
  out.width = std::max(1.0, std::ceil(box->width() - 1e-9));
  out.height = std::max(1.0, std::ceil(box->height() - 1e-9));
  out.root.transform = Affine::translate(-box->x0, -box->y0) * m;
  out.root.children.push_back(std::move(node));
  return out;
}

template <class T>
DrawStats render_tree(const Tree& tree, BasicImage<T>& image, const DrawSettings& settings) {
  Canvas canvas(image);
  if (tree.width > 0 && tree.height > 0) canvas.scale(image.width / tree.width, image.height / tree.height);
  return draw_tree(tree, canvas, settings);
}

template DrawStats render_tree<std::uint8_t>(const Tree&, Image&, const DrawSettings&);
template DrawStats render_tree<std::uint16_t>(const Tree&, Image16&, const DrawSettings&);

Tree load_svg_tree(const std::string& path, ParseOptions options) {
  const std::vector<std::uint8_t> bytes = read_file_limited(path, kMaxSvgFileBytes, "SVG file");
  if (options.base_dir.empty()) options.base_dir = detail::folder_of(path);  // images next to the file
  return parse_svg_tree(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path, options);
}

}  // namespace vraster::svg
