// The scene planner: one pass to find each command's device box and layer structure, one pass backwards for
// occlusion, one pass over each layer for what it really needs. Every rule below keeps the picture as it is
// (up to rounding): a rule that cannot prove that for a command leaves the command alone.
//
//   culled       box empty (outside the canvas or its clip); invisible (alpha 0 or a transparent paint with an
//                operator that leaves the destination alone); a fill of zero area; hidden (every pixel it can
//                change is overwritten later, in the same layer, by an opaque pixel-aligned rectangle, a `copy`
//                or `clear`, or put_pixels, with no post-filter in between); a layer with nothing left to draw
//   aliased      a fill that is a rectangle with whole-pixel corners: antialiasing computes 0 or 1 anyway
//   layers       opacity 1, source-over, no mask, clipped only by pixel-aligned rectangles, and only source-over
//                drawing inside: dropped (source-over is associative); the same with opacity < 1 whose children
//                touch disjoint pixels and cast no shadow: dropped, the opacity folded into each child's alpha
//   meshes       an opaque mesh with the z-buffer: drawn nearest triangle first, so hidden fragments are rejected
//                before they are shaded (ties go to the triangle given first: the same picture)
//   tiles        the 64 x 64 tiles that some kept command can change
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <unordered_map>

#include "vraster/scene.hpp"

namespace vraster {
namespace {

using Kind = SceneCommand::Kind;
using Action = PlanDecision::Action;
using Reason = PlanReason;

PixelBox intersect(const PixelBox& a, const PixelBox& b) {
  PixelBox r{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
  return r.empty() ? PixelBox{} : r;
}

PixelBox unite(const PixelBox& a, const PixelBox& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

bool contains(const PixelBox& outer, const PixelBox& inner) {
  return inner.x0 >= outer.x0 && inner.y0 >= outer.y0 && inner.x1 <= outer.x1 && inner.y1 <= outer.y1;
}

/// floor and ceil of a value already clamped to the int range (std::floor is a libm call on baseline x86-64,
/// and this runs for every command).
int floor_int(double v) {
  const int i = static_cast<int>(v);
  return i - (v < i);
}
int ceil_int(double v) {
  const int i = static_cast<int>(v);
  return i + (v > i);
}

/// The pixels a device rectangle can touch, grown by `margin` pixels; a box that is not finite is "everywhere".
PixelBox touching(const Rect& r, double margin, const PixelBox& everywhere) {
  constexpr double kLimit = 1 << 30;
  if (!(r.x0 > -kLimit && r.y0 > -kLimit && r.x1 < kLimit && r.y1 < kLimit)) {
    if (!std::isfinite(r.x0) || !std::isfinite(r.y0) || !std::isfinite(r.x1) || !std::isfinite(r.y1)) {
      return everywhere;
    }
  }
  auto clamp = [&](double v) { return std::clamp(v, -kLimit, kLimit); };
  return {floor_int(clamp(r.x0 - margin)), floor_int(clamp(r.y0 - margin)), ceil_int(clamp(r.x1 + margin)),
          ceil_int(clamp(r.y1 + margin))};
}

/// The device box of a path's control points (the curves lie inside it); false when it has no points.
bool device_box(const Path& path, const Affine& m, Rect& out) {
  const auto pts = path.points();
  if (pts.empty()) return false;
  out = Rect::from_point(m.apply(pts[0]));
  for (const Point& p : pts) out.include(m.apply(p));
  return true;
}

/// Whether `path` mapped by `m` is one axis-aligned rectangle (move, three or four lines, optional close).
bool device_rectangle(const Path& path, const Affine& m, Rect& out) {
  const auto verbs = path.verbs();
  const auto pts = path.points();
  std::size_t n = verbs.size();
  if (n > 0 && verbs[n - 1] == Verb::Close) --n;
  if (n < 4 || n > 5 || verbs[0] != Verb::Move) return false;
  for (std::size_t i = 1; i < n; ++i) {
    if (verbs[i] != Verb::Line) return false;
  }
  Point c[5];
  for (std::size_t i = 0; i < n; ++i) c[i] = m.apply(pts[i]);
  if (n == 5 && !(c[4] == c[0])) return false;
  for (int i = 0; i < 4; ++i) {
    const Point a = c[i], b = c[(i + 1) % 4];
    if (!is_finite(a)) return false;
    const bool horizontal = a.y == b.y, vertical = a.x == b.x;
    if (horizontal == vertical) return false;  // diagonal, or a repeated point
    const bool first_horizontal = c[0].y == c[1].y;
    if (horizontal != (first_horizontal == (i % 2 == 0))) return false;  // sides must alternate
  }
  out = Rect::from_point(c[0]);
  for (int i = 1; i < 4; ++i) out.include(c[i]);
  return !out.empty();
}

bool whole(double v) { return v == std::round(v); }

/// The whole pixels a rectangle covers completely.
PixelBox interior(const Rect& r) {
  constexpr double kLimit = 1 << 30;
  auto clamp = [&](double v) { return static_cast<int>(std::clamp(v, -kLimit, kLimit)); };
  PixelBox b{clamp(std::ceil(r.x0)), clamp(std::ceil(r.y0)), clamp(std::floor(r.x1)), clamp(std::floor(r.y1))};
  return b.empty() ? PixelBox{} : b;
}

/// The largest factor a transform stretches a length by.
double max_scale(const Affine& m) {
  const double s1 = m.a * m.a + m.b * m.b + m.c * m.c + m.d * m.d;
  const double det = m.a * m.d - m.b * m.c;
  return std::sqrt(s1 / 2 + std::sqrt(std::max(0.0, s1 * s1 / 4 - det * det)));
}

bool casts_shadow(const SceneState& s) {
  return s.shadow.color.a > 0 && (s.shadow.blur > 0 || s.shadow.offset_x != 0 || s.shadow.offset_y != 0);
}

/// Operators for which a source pixel of alpha 1 and full coverage gives the source (the destination is lost).
bool opaque_source_replaces(CompositeOp op) { return op == CompositeOp::SourceOver || op == CompositeOp::Copy; }

class Planner {
 public:
  Planner(const Scene& scene, ScenePlan& plan)
      : scene_(scene), plan_(plan), canvas_{0, 0, std::max(scene.width, 0), std::max(scene.height, 0)} {}

  void run() {
    const std::size_t n = scene_.commands.size();
    plan_.decisions.assign(n, PlanDecision{});
    layer_of_.assign(n, -1);
    end_of_.assign(n, -1);
    unclipped_.assign(n, PixelBox{});
    kind_.resize(n);
    device_.assign(n, Rect{});
    is_rect_.assign(n, 0);
    may_overwrite_at_.assign(n, 0);
    // Commands are large (paths, paints): one pass reads them; the later ones read the decisions.
    find_layers_and_boxes();
    cull_layers();
    cull_hidden();
    plan_layers();
    summarise();
  }

 private:
  // ---- structure and boxes ----

  PixelBox clip_box(const SceneClip* clip) {
    if (!clip) return canvas_;
    const auto it = clip_boxes_.find(clip);
    if (it != clip_boxes_.end()) return it->second;
    PixelBox box = clip_box(clip->parent.get());
    Rect r;
    if (device_box(clip->path, clip->to_device, r)) {
      box = intersect(box, touching(r, 1, canvas_));
    } else {
      box = {};
    }
    clip_boxes_[clip] = box;
    return box;
  }

  /// Whether every clip of the chain is a rectangle with whole-pixel corners that keeps its inside (a clip
  /// without a mask).
  static bool rectangular_clips(const SceneClip* clip) {
    for (; clip; clip = clip->parent.get()) {
      Rect r;
      if (!device_rectangle(clip->path, clip->to_device, r) || !whole(r.x0) || !whole(r.y0) || !whole(r.x1) ||
          !whole(r.y1)) {
        return false;
      }
      if (clip->rule != FillRule::NonZero && clip->rule != FillRule::EvenOdd && clip->rule != FillRule::NonExterior) {
        return false;  // the signed rules keep the inside or nothing, depending on the orientation
      }
    }
    return true;
  }

  /// The exact pixels a chain of rectangular clips keeps (only when rectangular_clips() holds).
  PixelBox rectangle_clip_region(const SceneClip* clip) const {
    PixelBox box = canvas_;
    for (; clip; clip = clip->parent.get()) {
      Rect r;
      device_rectangle(clip->path, clip->to_device, r);
      box = intersect(box, interior(r));
    }
    return box;
  }

  PixelBox own_box(const SceneCommand& c, std::size_t index) {
    const PixelBox everywhere = canvas_;
    const SceneState& s = c.state;
    PixelBox box;
    switch (c.kind) {
      case Kind::Fill: {
        Rect& r = device_[index];
        if (c.path.verbs().size() <= 6 && device_rectangle(c.path, c.to_device, r)) {
          is_rect_[index] = 1;
          may_overwrite_at_[index] = 1;
          may_overwrite_ = true;
        } else if (!device_box(c.path, c.to_device, r)) {
          r = Rect{0, 0, 0, 0};
          break;
        }
        box = touching(r, 1, everywhere);
        if (s.op == CompositeOp::Copy || s.op == CompositeOp::Clear) may_overwrite_at_[index] = 1;
        may_overwrite_ = may_overwrite_ || may_overwrite_at_[index];
        break;
      }
      case Kind::Stroke: {
        Rect r;
        if (!device_box(c.path, c.to_device, r)) break;
        const bool miter_join = s.line.join == LineJoin::Miter || s.line.join == LineJoin::MiterClip;
        const double miter = miter_join ? std::max(1.0, s.line.miter_limit) : 1.0;
        const double reach = s.line.width / 2 * std::max(std::sqrt(2.0), miter) * max_scale(c.to_device);
        box = touching(r, (std::isfinite(reach) ? reach : 1e300) + 1, everywhere);
        break;
      }
      case Kind::DrawImage: {
        Path rect;
        rect.add_rect(c.dst);
        Rect r;
        if (device_box(rect, s.transform, r)) box = touching(r, 1, everywhere);
        break;
      }
      case Kind::FillMask:
      case Kind::PutPixels:
        if (c.image) box = {c.x, c.y, c.x + c.image->width, c.y + c.image->height};
        break;
      case Kind::Mesh: {
        if (!c.mesh) break;
        bool any = false;
        Rect r;
        for (const MeshVertex& v : c.mesh->vertices) {
          const Point p = c.to_device.apply(v.position);
          if (!is_finite(p)) continue;  // the triangles using it are skipped
          if (!any) r = Rect::from_point(p);
          r.include(p);
          any = true;
        }
        if (any) box = touching(r, 1, everywhere);
        return box;  // meshes cast no shadow
      }
      case Kind::Fxaa:
      case Kind::FloodFill:
        return canvas_;
      case Kind::BeginLayer:
      case Kind::EndLayer:
        return {};
    }
    if (c.kind != Kind::PutPixels && casts_shadow(s)) {
      const double spread = 1.5 * s.shadow.blur + 1;  // three standard deviations of blur / 2
      Rect moved{static_cast<double>(box.x0) + s.shadow.offset_x, static_cast<double>(box.y0) + s.shadow.offset_y,
                 static_cast<double>(box.x1) + s.shadow.offset_x, static_cast<double>(box.y1) + s.shadow.offset_y};
      if (!box.empty()) box = unite(box, touching(moved, spread, everywhere));
    }
    return box;
  }

  void find_layers_and_boxes() {
    std::vector<int> open;  // BeginLayer indices
    for (std::size_t i = 0; i < scene_.commands.size(); ++i) {
      const SceneCommand& c = scene_.commands[i];
      PlanDecision& d = plan_.decisions[i];
      kind_[i] = c.kind;
      layer_of_[i] = open.empty() ? -1 : open.back();
      if (c.kind == Kind::BeginLayer) {
        // A layer covers its clip's box (in the enclosing layer's box); drawing inside is clipped to it.
        const PixelBox outer = open.empty() ? canvas_ : plan_.decisions[open.back()].bounds;
        d.bounds = intersect(clip_box(c.clip.get()), outer);
        open.push_back(static_cast<int>(i));
        continue;
      }
      if (c.kind == Kind::EndLayer) {
        if (open.empty()) continue;  // unbalanced: replay ignores it
        const int begin = open.back();
        open.pop_back();
        end_of_[begin] = static_cast<int>(i);
        layer_of_[i] = begin;
        plan_.decisions[i].bounds = plan_.decisions[begin].bounds;
        continue;
      }
      const PixelBox region = open.empty() ? canvas_ : plan_.decisions[open.back()].bounds;
      unclipped_[i] = own_box(c, i);
      if (c.kind == Kind::PutPixels) {
        may_overwrite_at_[i] = 1;
        may_overwrite_ = true;
        d.bounds = intersect(unclipped_[i], canvas_);  // put_pixels ignores clips and layers
      } else if (c.kind == Kind::Fxaa || c.kind == Kind::FloodFill) {
        d.bounds = canvas_;
      } else if (!is_bounded(c.state.op)) {
        d.bounds = intersect(clip_box(c.clip.get()), region);  // the whole clip region changes
      } else {
        d.bounds = intersect(intersect(unclipped_[i], clip_box(c.clip.get())), region);
      }
      cull_call(i);
      mark_aliased(i);
      mark_front_to_back(i);
    }
    open_at_end_ = std::move(open);
  }

  // ---- culling ----

  void cull(std::size_t i, Reason reason, int ref = -1) {
    PlanDecision& d = plan_.decisions[i];
    d.action = Action::Cull;
    d.reason = reason;
    d.ref = ref;
    if (kind_[i] == Kind::BeginLayer && end_of_[i] >= 0) {
      for (int k = static_cast<int>(i) + 1; k <= end_of_[i]; ++k) {
        PlanDecision& inner = plan_.decisions[k];
        if (inner.action != Action::Cull) {
          inner.action = Action::Cull;
          inner.reason = Reason::InsideCulledLayer;
          inner.ref = static_cast<int>(i);
        }
      }
    }
  }

  /// Culls a layer that never ends (and everything in it), or one that cannot show.
  void cull_layers() {
    for (const int b : open_at_end_) {
      if (plan_.decisions[b].action == Action::Cull) continue;  // inside an earlier one that never ends
      cull(b, Reason::LayerNeverEnds);
      // Everything after it is inside it, except what writes the target itself.
      for (std::size_t k = b + 1; k < scene_.commands.size(); ++k) {
        if (kind_[k] == Kind::PutPixels || kind_[k] == Kind::Fxaa || kind_[k] == Kind::FloodFill) continue;
        plan_.decisions[k].action = Action::Cull;
        plan_.decisions[k].reason = Reason::InsideNeverEndingLayer;
        plan_.decisions[k].ref = b;
      }
    }
    for (std::size_t i = 0; i < scene_.commands.size(); ++i) {
      if (kind_[i] != Kind::BeginLayer || plan_.decisions[i].action == Action::Cull) continue;
      const SceneCommand& c = scene_.commands[i];
      if (is_bounded(c.layer.op) && !(c.layer.opacity > 0)) {
        cull(i, Reason::LayerOpacityZero);
      } else if (is_bounded(c.layer.op) && plan_.decisions[i].bounds.empty()) {
        cull(i, Reason::LayerOutside);
      }
    }
  }

  /// Culls a drawing call that is outside, invisible or empty.
  void cull_call(std::size_t i) {
    const SceneCommand& c = scene_.commands[i];
    const PlanDecision& d = plan_.decisions[i];
    if (c.kind == Kind::Fxaa || c.kind == Kind::FloodFill) return;
    if (c.kind == Kind::PutPixels) {
      if (d.bounds.empty()) cull(i, Reason::OutsideCanvas);
      return;
    }
    if (c.kind == Kind::Mesh && (!c.mesh || c.mesh->triangles.empty())) {
      cull(i, Reason::ZeroArea);
      return;
    }
    if (d.bounds.empty()) {
      cull(i, intersect(unclipped_[i], canvas_).empty() ? Reason::OutsideCanvas : Reason::OutsideClip);
      return;
    }
    const SceneState& s = c.state;
    if (!is_bounded(s.op)) return;  // changes the clip region whatever it draws
    const Paint& paint = c.kind == Kind::Stroke ? s.stroke_paint : s.fill_paint;
    const bool paints_itself = c.kind == Kind::DrawImage || c.kind == Kind::Mesh;  // no fill or stroke paint
    if (!(s.global_alpha > 0)) {
      cull(i, Reason::GlobalAlphaZero);
    } else if (!paints_itself && paint.is_invisible()) {
      cull(i, Reason::TransparentPaint);
    } else if (c.kind == Kind::Fill && !casts_shadow(s)) {
      const Rect& r = device_[i];
      if (r.width() == 0 || r.height() == 0) cull(i, Reason::ZeroArea);
    } else if (c.kind == Kind::Stroke && !(s.line.width > 0)) {
      cull(i, Reason::ZeroWidth);
    } else if (c.kind == Kind::Mesh && !(c.mesh_options.opacity > 0)) {
      cull(i, Reason::GlobalAlphaZero);
    }
  }

  /// The pixels command j overwrites whatever was there before (empty when it cannot promise that).
  PixelBox overwritten_by(std::size_t j) {
    const SceneCommand& c = scene_.commands[j];
    const PlanDecision& d = plan_.decisions[j];
    if (d.action != Action::Draw) return {};
    if (c.kind == Kind::PutPixels) return d.bounds;
    if (c.kind != Kind::Fill || !rectangular_clips(c.clip.get())) return {};
    const SceneState& s = c.state;
    const PixelBox clip = rectangle_clip_region(c.clip.get());
    if (s.op == CompositeOp::Clear || (s.op == CompositeOp::Copy && !casts_shadow(s))) {
      return clip;  // the whole clip region is replaced
    }
    if (!is_rect_[j]) return {};
    const Rect& r = device_[j];
    if (c.rule != FillRule::NonZero && c.rule != FillRule::EvenOdd && c.rule != FillRule::NonExterior) return {};
    const bool opaque = s.global_alpha * d.alpha_scale >= 1 && s.fill_paint.is_opaque();
    const bool erases = s.op == CompositeOp::DestinationOut && opaque;  // clear_rect
    if (!erases && !(opaque && opaque_source_replaces(s.op))) return {};
    return intersect(interior(r), clip);
  }

  void cull_hidden() {
    if (!may_overwrite_) return;  // nothing overwrites anything: nothing is hidden
    // Backwards: each level (layer instance, or -1 for the target) keeps the largest regions that later
    // commands overwrite. A post-filter reads neighbouring pixels, so nothing before it is hidden by what after.
    constexpr std::size_t kOccluders = 8;
    // One list per level: slot 0 for the target, 1 + the layer's number for each layer.
    std::vector<int> slot(scene_.commands.size(), 0);
    int layers = 0;
    for (std::size_t k = 0; k < scene_.commands.size(); ++k) {
      if (kind_[k] == Kind::BeginLayer) slot[k] = ++layers;
    }
    std::vector<std::vector<std::pair<PixelBox, int>>> occluders(static_cast<std::size_t>(layers) + 1);
    for (std::size_t k = scene_.commands.size(); k-- > 0;) {
      const Kind kind = kind_[k];
      if (kind == Kind::Fxaa || kind == Kind::FloodFill) {  // they read the pixels around
        for (auto& list : occluders) list.clear();
        continue;
      }
      if (kind == Kind::EndLayer) continue;
      const int level = layer_of_[k];
      PlanDecision& d = plan_.decisions[k];
      auto& mine = occluders[level < 0 ? 0 : slot[level]];
      if (d.action == Action::Draw && !mine.empty() && !d.bounds.empty() && kind != Kind::PutPixels) {
        for (const auto& [region, by] : mine) {
          if (contains(region, d.bounds)) {
            cull(k, Reason::Hidden, by);
            break;
          }
        }
      }
      if (kind == Kind::BeginLayer) {
        occluders[slot[k]].clear();  // its inside is done
        continue;
      }
      if (!may_overwrite_at_[k]) continue;
      const PixelBox region = overwritten_by(k);
      if (region.empty()) continue;
      // put_pixels writes the target even inside a layer: it hides what came before at the top level.
      auto& list = kind == Kind::PutPixels ? occluders[0] : mine;
      list.emplace_back(region, static_cast<int>(k));
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first.area() > b.first.area(); });
      if (list.size() > kOccluders) list.pop_back();
    }
  }

  // ---- layers ----

  void plan_layers() {
    // Innermost first, so an outer layer sees what became of the inner ones.
    std::vector<std::size_t> begins;
    for (std::size_t i = 0; i < scene_.commands.size(); ++i) {
      if (kind_[i] == Kind::BeginLayer && end_of_[i] >= 0) begins.push_back(i);
    }
    std::sort(begins.begin(), begins.end(), [&](std::size_t a, std::size_t b) { return end_of_[a] - a < end_of_[b] - b; });
    for (const std::size_t b : begins) plan_layer(b);
  }

  void plan_layer(std::size_t b) {
    PlanDecision& d = plan_.decisions[b];
    if (d.action != Action::Draw) return;
    const SceneCommand& c = scene_.commands[b];
    const int e = end_of_[b];
    bool any = false, plain = true, shadows = false, nested = false, self_overlap = false;
    // Its children: the drawing calls inside it that no kept inner layer encloses (a dropped inner layer's
    // children draw straight into this one).
    std::vector<std::size_t> children;
    std::vector<bool> inner_kept;  // the inner layers open at k: kept or dropped
    for (int k = static_cast<int>(b) + 1; k < e; ++k) {
      const SceneCommand& inner = scene_.commands[k];
      const PlanDecision& id = plan_.decisions[k];
      if (id.action == Action::Cull) continue;
      if (inner.kind == Kind::EndLayer) {
        if (!inner_kept.empty()) inner_kept.pop_back();
        continue;
      }
      if (inner.kind == Kind::PutPixels || inner.kind == Kind::Fxaa || inner.kind == Kind::FloodFill) plain = false;
      if (inner.kind == Kind::BeginLayer) {
        if (id.action == Action::Draw && inner.layer.op != CompositeOp::SourceOver) plain = false;
        nested = nested || id.action == Action::Draw;
        inner_kept.push_back(id.action == Action::Draw);
        continue;
      }
      any = true;
      if (inner.state.op != CompositeOp::SourceOver) plain = false;
      // A mesh's triangles may overlap each other: a group opacity does not fold into its fragments.
      self_overlap = self_overlap || inner.kind == Kind::Mesh;
      shadows = shadows || casts_shadow(inner.state);
      if (std::find(inner_kept.begin(), inner_kept.end(), true) == inner_kept.end()) {
        children.push_back(static_cast<std::size_t>(k));
      }
    }
    if (!any && is_bounded(c.layer.op)) {
      cull(b, Reason::LayerEmpty);
      return;
    }
    const std::int64_t area = d.bounds.area();
    if (c.layer.mask) {
      d.reason = Reason::LayerNeedsMask;
    } else if (c.layer.op != CompositeOp::SourceOver) {
      d.reason = Reason::LayerNeedsOperator;
    } else if (!plain) {
      d.reason = Reason::LayerNeedsIsolation;
    } else if (!rectangular_clips(c.clip.get())) {
      d.reason = Reason::LayerNeedsClip;
    } else if (c.layer.opacity >= 1) {
      drop(b, Reason::LayerDropped, 1);
      plan_.layers_dropped++;
      plan_.layer_pixels_saved += area;
    } else if (nested) {  // opacity folds into the children only when no pixel is drawn twice
      d.reason = Reason::LayerNeedsNested;
    } else if (shadows) {
      d.reason = Reason::LayerNeedsShadows;
    } else if (self_overlap || !disjoint(children)) {
      d.reason = Reason::LayerNeedsOverlap;
    } else {
      drop(b, Reason::LayerFolded, c.layer.opacity);
      d.value = c.layer.opacity;
      d.count = static_cast<int>(children.size());
      plan_.layers_folded++;
      plan_.layer_pixels_saved += area;
    }
  }

  bool disjoint(std::vector<std::size_t> children) {
    std::sort(children.begin(), children.end(),
              [&](std::size_t a, std::size_t b) { return plan_.decisions[a].bounds.x0 < plan_.decisions[b].bounds.x0; });
    // Sweep by x: each box is compared with the earlier ones that still reach its left side.
    std::vector<std::size_t> active;
    for (const std::size_t k : children) {
      const PixelBox& box = plan_.decisions[k].bounds;
      std::erase_if(active, [&](std::size_t a) { return plan_.decisions[a].bounds.x1 <= box.x0; });
      for (const std::size_t a : active) {
        if (!intersect(plan_.decisions[a].bounds, box).empty()) return false;
      }
      active.push_back(k);
    }
    return true;
  }

  void drop(std::size_t b, Reason reason, float alpha) {
    PlanDecision& d = plan_.decisions[b];
    d.action = Action::DropLayer;
    d.reason = reason;
    PlanDecision& e = plan_.decisions[end_of_[b]];
    e.action = Action::DropLayer;
    e.reason = Reason::EndOfDroppedLayer;
    e.ref = static_cast<int>(b);
    if (alpha >= 1) return;
    for (int k = static_cast<int>(b) + 1; k < end_of_[b]; ++k) plan_.decisions[k].alpha_scale *= alpha;
  }

  // ---- coverage ----

  /// An opaque mesh drawn aliased with a z-buffer it writes: drawn nearest triangle first.
  void mark_front_to_back(std::size_t i) {
    const SceneCommand& c = scene_.commands[i];
    PlanDecision& d = plan_.decisions[i];
    if (d.action == Action::Draw && c.kind == Kind::Mesh) {
      // Opaque fragments and a z-buffer: the nearest fragment decides each pixel whatever the order, so
      // drawing nearest first only saves shading (global alpha folds into the opacity, so it must be 1 too;
      // a group opacity is never folded into a mesh).
      const MeshOptions& o = c.mesh_options;
      d.front_to_back = o.depth == DepthMode::ZBuffer && !o.antialias && o.write_depth && c.state.global_alpha >= 1 &&
                        c.mesh && c.mesh->triangles.size() > 1 && mesh_is_opaque(*c.mesh, o);
    }
  }

  /// A fill that is a rectangle with whole-pixel corners needs no antialiasing work: its coverage is 0 or 1.
  /// Not with a shadow: the shadow pass draws the shape moved by a fractional offset.
  void mark_aliased(std::size_t i) {
    const SceneCommand& c = scene_.commands[i];
    PlanDecision& d = plan_.decisions[i];
    if (d.action != Action::Draw || c.kind != Kind::Fill || c.state.aa == AntiAlias::None || casts_shadow(c.state)) {
      return;
    }
    const Rect& r = device_[i];
    if (is_rect_[i] && whole(r.x0) && whole(r.y0) && whole(r.x1) && whole(r.y1)) d.aliased = true;
  }

  // ---- summary ----

  void summarise() {
    const int ts = plan_.tile_size;
    plan_.width = canvas_.x1;
    plan_.height = canvas_.y1;
    plan_.tiles_x = (canvas_.x1 + ts - 1) / ts;
    plan_.tiles_y = (canvas_.y1 + ts - 1) / ts;
    plan_.touched_tiles.assign(static_cast<std::size_t>(plan_.tiles_x) * plan_.tiles_y, 0);
    for (std::size_t i = 0; i < scene_.commands.size(); ++i) {
      const Kind kind = kind_[i];
      PlanDecision& d = plan_.decisions[i];
      if (d.action == Action::Cull) {
        plan_.culled++;
        if (kind != Kind::BeginLayer && kind != Kind::EndLayer) plan_.pixels_not_composited += d.bounds.area();
        continue;
      }
      if (d.aliased) plan_.aliased++;
      if (d.front_to_back) plan_.front_to_back++;
      if (kind == Kind::BeginLayer) continue;
      if (kind == Kind::EndLayer && d.action == Action::Draw) d.reason = Reason::LayerComposited;
      const PixelBox box = intersect(d.bounds, canvas_);
      if (box.empty()) continue;
      for (int ty = box.y0 / ts; ty <= (box.y1 - 1) / ts; ++ty) {
        for (int tx = box.x0 / ts; tx <= (box.x1 - 1) / ts; ++tx) {
          plan_.touched_tiles[static_cast<std::size_t>(ty) * plan_.tiles_x + tx] = 1;
        }
      }
    }
  }

  const Scene& scene_;
  ScenePlan& plan_;
  PixelBox canvas_;
  std::vector<int> layer_of_;  // the BeginLayer a command is inside (-1: none); EndLayer: its own BeginLayer
  std::vector<int> end_of_;    // BeginLayer: its EndLayer (-1: never ended)
  std::vector<PixelBox> unclipped_;  // the box of each call before its clip
  std::vector<Rect> device_;         // fills: the device box of the path's points (the rectangle itself)
  std::vector<std::uint8_t> is_rect_;  // fills: the path is one axis-aligned rectangle in device space
  std::vector<std::uint8_t> may_overwrite_at_;  // the call may overwrite pixels (checked by overwritten_by)
  bool may_overwrite_ = false;
  std::vector<Kind> kind_;           // each command's kind, read without touching the command
  std::vector<int> open_at_end_;     // layers never ended       // some call can overwrite pixels (an occlusion pass is worth running)
  std::unordered_map<const SceneClip*, PixelBox> clip_boxes_;
};

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string drawn_sentence(const SceneCommand& c, const PlanDecision& d) {
  const SceneState& s = c.state;
  switch (c.kind) {
    case Kind::PutPixels: return "drawn: pixels stored as given";
    case Kind::Fxaa: return "drawn: post-filter over the whole target";
    case Kind::FloodFill: return "drawn: flood fill (reads the pixels drawn before)";
    case Kind::Mesh:
      if (d.front_to_back) {
        return "drawn: opaque mesh with a z-buffer, nearest triangles first (" + std::to_string(c.mesh->triangles.size()) +
               " triangles; hidden fragments rejected before shading)";
      }
      return "drawn: mesh of " + std::to_string(c.mesh ? c.mesh->triangles.size() : 0) + " triangles, in the given order";
    default: break;
  }
  std::string why = "drawn";
  if (d.aliased) {
    why += ", no antialiasing work (whole-pixel rectangle)";
  } else if (s.aa == AntiAlias::Exact) {
    why += ", exact coverage where edges meet inside a pixel (analytic elsewhere)";
  }
  const Paint& paint = c.kind == Kind::Stroke ? s.stroke_paint : s.fill_paint;
  const float alpha = s.global_alpha * d.alpha_scale;
  if (d.alpha_scale < 1) why += ", folded opacity " + format_number(d.alpha_scale);
  if (c.kind != Kind::DrawImage && s.op == CompositeOp::SourceOver && alpha >= 1 && paint.is_opaque()) {
    why += ", opaque paint: full coverage stored without blending";
  } else {
    why += ", blended (" + std::string(to_string(s.op)) + ")";
  }
  if (casts_shadow(s)) why += ", with shadow";
  return why;
}

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::Fill: return "fill";
    case Kind::Stroke: return "stroke";
    case Kind::DrawImage: return "image";
    case Kind::FillMask: return "mask";
    case Kind::PutPixels: return "pixels";
    case Kind::BeginLayer: return "layer";
    case Kind::EndLayer: return "end";
    case Kind::Fxaa: return "fxaa";
    case Kind::FloodFill: return "flood";
    case Kind::Mesh: return "mesh";
  }
  return "?";
}

const char* action_name(Action a) {
  switch (a) {
    case Action::Draw: return "draw";
    case Action::Cull: return "cull";
    case Action::DropLayer: return "drop";
  }
  return "?";
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", ch);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

}  // namespace

std::string describe_decision(const Scene& scene, const ScenePlan& plan, std::size_t i) {
  const SceneCommand& c = scene.commands.at(i);
  const PlanDecision& d = plan.decisions.at(i);
  std::string ref = "#";  // appended, not "#" + ...: GCC 12 warns falsely (-Wrestrict) on that form here
  ref += std::to_string(d.ref);
  const std::string op = std::string(to_string(c.kind == Kind::BeginLayer ? c.layer.op : c.state.op));
  switch (d.reason) {
    case Reason::Drawn: return drawn_sentence(c, d);
    case Reason::OutsideCanvas: return "outside the canvas";
    case Reason::OutsideClip: return "outside its clip";
    case Reason::GlobalAlphaZero: return "global alpha 0 with " + op + ": changes nothing";
    case Reason::TransparentPaint: return "transparent paint with " + op + ": changes nothing";
    case Reason::ZeroArea: return "zero area";
    case Reason::ZeroWidth: return "zero line width";
    case Reason::Hidden:
      return std::string(c.kind == Kind::BeginLayer ? "layer " : "") + "hidden under " + ref +
             ", which overwrites every pixel it can change";
    case Reason::LayerNeverEnds: return "layer never ended: never shows";
    case Reason::InsideNeverEndingLayer: return "inside layer " + ref + ", which never ends";
    case Reason::InsideCulledLayer: return "inside layer " + ref + ", which is culled";
    case Reason::LayerOpacityZero: return "layer opacity 0: draws nothing";
    case Reason::LayerOutside: return "layer outside the canvas or its clip";
    case Reason::LayerEmpty: return "layer with nothing left to draw";
    case Reason::LayerNeedsMask: return "layer needed: a mask";
    case Reason::LayerNeedsOperator: return "layer needed: composited with " + op;
    case Reason::LayerNeedsIsolation: return "layer needed: drawing inside that is not source-over";
    case Reason::LayerNeedsClip: return "layer needed: an antialiased clip applied once to the whole layer";
    case Reason::LayerNeedsOverlap: return "layer needed: opacity " + format_number(c.layer.opacity) + " over children that overlap";
    case Reason::LayerNeedsNested: return "layer needed: opacity " + format_number(c.layer.opacity) + " over a layer of its own";
    case Reason::LayerNeedsShadows: return "layer needed: opacity " + format_number(c.layer.opacity) + " over shadows";
    case Reason::LayerDropped:
      return "layer dropped: opacity 1, source-over and source-over inside give the same pixels without it";
    case Reason::LayerFolded:
      return "layer folded: opacity " + format_number(d.value) + " goes into each of " + std::to_string(d.count) +
             " children, which touch disjoint pixels";
    case Reason::EndOfDroppedLayer: return "end of dropped layer " + ref;
    case Reason::LayerComposited: return "layer composited";
  }
  return "?";
}

int ScenePlan::touched_tile_count() const {
  return static_cast<int>(std::count(touched_tiles.begin(), touched_tiles.end(), std::uint8_t{1}));
}

ScenePlan plan_scene(const Scene& scene) {
  ScenePlan plan;
  Planner(scene, plan).run();
  return plan;
}

std::string explain_plan(const Scene& scene, const ScenePlan& plan) {
  std::ostringstream out;
  for (std::size_t i = 0; i < scene.commands.size() && i < plan.decisions.size(); ++i) {
    const PlanDecision& d = plan.decisions[i];
    char head[96];
    const PixelBox& b = d.bounds;
    if (b.empty()) {
      std::snprintf(head, sizeof head, "#%-5zu %-6s %-4s %-22s ", i, kind_name(scene.commands[i].kind),
                    action_name(d.action), "(no pixels)");
    } else {
      char box[48];
      std::snprintf(box, sizeof box, "%d,%d %dx%d", b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0);
      std::snprintf(head, sizeof head, "#%-5zu %-6s %-4s %-22s ", i, kind_name(scene.commands[i].kind),
                    action_name(d.action), box);
    }
    out << head << describe_decision(scene, plan, i) << '\n';
  }
  const int tiles = plan.tiles_x * plan.tiles_y;
  out << "summary: " << scene.commands.size() << " commands, " << plan.culled << " culled ("
      << plan.pixels_not_composited << " pixels not composited); layers: " << plan.layers_dropped << " dropped, "
      << plan.layers_folded << " folded (" << plan.layer_pixels_saved << " layer pixels not allocated); "
      << plan.aliased << " without antialiasing work; " << plan.front_to_back
      << " meshes front to back; tiles touched: " << plan.touched_tile_count() << " of " << tiles << " ("
      << plan.tile_size << " px)\n";
  return out.str();
}

std::string explain_plan_json(const Scene& scene, const ScenePlan& plan) {
  std::ostringstream out;
  out << "{\"width\":" << scene.width << ",\"height\":" << scene.height << ",\"commands\":[";
  for (std::size_t i = 0; i < scene.commands.size() && i < plan.decisions.size(); ++i) {
    const PlanDecision& d = plan.decisions[i];
    if (i) out << ',';
    out << "{\"index\":" << i << ",\"kind\":\"" << kind_name(scene.commands[i].kind) << "\",\"action\":\""
        << action_name(d.action) << "\",\"bounds\":[" << d.bounds.x0 << ',' << d.bounds.y0 << ',' << d.bounds.x1
        << ',' << d.bounds.y1 << "],\"alpha_scale\":" << d.alpha_scale << ",\"aliased\":"
        << (d.aliased ? "true" : "false") << ",\"front_to_back\":" << (d.front_to_back ? "true" : "false")
        << ",\"ref\":" << d.ref << ",\"why\":"
        << json_string(describe_decision(scene, plan, i))
        << '}';
  }
  out << "],\"summary\":{\"commands\":" << scene.commands.size() << ",\"culled\":" << plan.culled
      << ",\"pixels_not_composited\":" << plan.pixels_not_composited << ",\"layers_dropped\":" << plan.layers_dropped
      << ",\"layers_folded\":" << plan.layers_folded << ",\"layer_pixels_saved\":" << plan.layer_pixels_saved
      << ",\"aliased\":" << plan.aliased << ",\"front_to_back\":" << plan.front_to_back << ",\"tiles_touched\":" << plan.touched_tile_count()
      << ",\"tiles\":" << plan.tiles_x * plan.tiles_y << ",\"tile_size\":" << plan.tile_size << "}}\n";
  return out.str();
}

}  // namespace vraster

namespace vraster {
namespace {

/// Appends the commands [first, last) to `out` in depth order: each block (a call, or a layer from its
/// BeginLayer to its EndLayer) keeps its inside together and is placed by its first command's z.
void append_by_depth(const Scene& scene, std::size_t first, std::size_t last, std::deque<SceneCommand>& out) {
  struct Block {
    std::size_t begin, end;  // [begin, end)
    double z;
  };
  std::vector<Block> blocks;
  for (std::size_t i = first; i < last;) {
    std::size_t end = i + 1;
    if (scene.commands[i].kind == SceneCommand::Kind::BeginLayer) {
      int depth = 1;
      while (end < last && depth > 0) {
        const auto k = scene.commands[end].kind;
        depth += k == SceneCommand::Kind::BeginLayer ? 1 : k == SceneCommand::Kind::EndLayer ? -1 : 0;
        ++end;
      }
    }
    blocks.push_back({i, end, scene.commands[i].state.z});
    i = end;
  }
  std::stable_sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) { return a.z < b.z; });
  for (const Block& b : blocks) {
    const bool layer = scene.commands[b.begin].kind == SceneCommand::Kind::BeginLayer;
    if (!layer) {
      out.push_back(scene.commands[b.begin]);
      continue;
    }
    out.push_back(scene.commands[b.begin]);
    const bool ended = scene.commands[b.end - 1].kind == SceneCommand::Kind::EndLayer && b.end - b.begin >= 2;
    append_by_depth(scene, b.begin + 1, ended ? b.end - 1 : b.end, out);
    if (ended) out.push_back(scene.commands[b.end - 1]);
  }
}

}  // namespace

Scene order_by_depth(const Scene& scene) {
  Scene out;
  out.width = scene.width;
  out.height = scene.height;
  append_by_depth(scene, 0, scene.commands.size(), out.commands);
  return out;
}

}  // namespace vraster
