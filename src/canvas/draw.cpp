// The canvas's drawing pipeline: coverage source -> clip -> compositor -> target or layer; clips, layers, shadows
// and images. Where each decision is taken is listed in docs/design.md ("The canvas").
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "canvas/canvas_impl.hpp"
#include "canvas/shadow_blur.hpp"
#include "paint/blend.hpp"
#include "raster/rect.hpp"
#include "vraster/error.hpp"

namespace vraster {

using canvas_detail::Clip;
using canvas_detail::ClipMask;
using canvas_detail::CoverageSource;
using canvas_detail::IntRect;

namespace {

// ---- step 2: the clip ----

// Receives coverage relative to `region` (a rectangle inside the clip box), offsets it to device pixels, and hands
// it to the compositor with the clip mask's row. For unbounded operators it covers every row and pixel of the
// region (coverage 0 where the shape is absent), so the operator reaches the whole clip region as the canvas says.
// Where the mask is 0 nothing is composited (a clip of 0 keeps the destination, whatever the operator); where it
// is full the compositor gets no clip (a store or a plain blend instead of the lerp).
template <class T>
class ClipSink final : public CoverageSink {
 public:
  ClipSink(Compositor<T>& out, const ClipMask* mask, const IntRect& region, bool unbounded, std::vector<float>& row)
      : out_(out), mask_(mask), region_(region), unbounded_(unbounded), row_(row) {
    if (unbounded_) row_.assign(static_cast<std::size_t>(region_.width()), 0.f);
  }

  void span(int y, int x0, int x1, float coverage) override {
    if (unbounded_) {
      move_to_row(y);
      std::fill(row_.begin() + x0, row_.begin() + x1, coverage);
      return;
    }
    const int dy = y + region_.y0;
    through_mask(dy, x0 + region_.x0, x1 + region_.x0,
                 [&](int a, int b, const T* clip) { out_.span(dy, a, b, coverage, clip); });
  }

  void row(int y, int x0, int x1, const float* coverage) override {
    if (unbounded_) {
      move_to_row(y);
      std::copy(coverage, coverage + (x1 - x0), row_.begin() + x0);
      return;
    }
    const int dy = y + region_.y0, dx0 = x0 + region_.x0;
    through_mask(dy, dx0, x1 + region_.x0,
                 [&](int a, int b, const T* clip) { out_.row(dy, a, b, coverage + (a - dx0), clip); });
  }

  void expect(int y0, int y1, int x0, int x1) override {
    out_.expect(y0 + region_.y0, y1 + region_.y0, x0 + region_.x0, x1 + region_.x0);
  }

  /// Bounded operators read only the clip mask, so rows are independent when the compositor's are; unbounded ones
  /// collect each row and flush the rows in between, which needs them in order.
  bool takes_concurrent_rows() const override { return !unbounded_ && out_.takes_concurrent_rows(); }

  /// Without a clip mask, a bounded operator's pixels are the compositor's, moved to the region's corner.
  bool solid_over8(SolidOver8& target) const override {
    if (unbounded_ || mask_ || !out_.solid_over8(target)) return false;
    if (region_.x0 < target.x0 || region_.y0 < target.y0 || region_.x1 > target.x0 + target.width ||
        region_.y1 > target.y0 + target.height) {
      return false;
    }
    std::uint8_t* const corner =
        target.pixels + (region_.y0 - target.y0) * target.stride + std::ptrdiff_t{region_.x0 - target.x0} * 4;
    target = {corner, target.stride, target.color, 0, 0, region_.width(), region_.height()};
    return true;
  }

  /// Unbounded operators: composites the rows not reached yet (with coverage 0 where nothing was drawn).
  void finish() {
    if (unbounded_) move_to_row(region_.height());
  }

 private:
  // Device pixels [x0, x1) of row dy in up to three pieces f(a, b, clip): none where the mask is 0, clip null where
  // it is full, the mask's row elsewhere.
  template <class F>
  void through_mask(int dy, int x0, int x1, F&& f) {
    if (!mask_) return f(x0, x1, nullptr);
    const ClipMask::RowExtent& e = mask_->extent(dy);
    const int a = std::max(x0, e.x0), b = std::min(x1, e.x1);
    if (a >= b) return;
    const int f0 = std::clamp(e.full0, a, b), f1 = std::clamp(e.full1, f0, b);
    if (f0 > a) f(a, f0, mask_->at<T>(a, dy));
    if (f1 > f0) f(f0, f1, nullptr);
    if (b > f1) f(f1, b, mask_->at<T>(f1, dy));
  }

  // Flushes every row before `y` (the one being collected, then empty ones) and starts collecting row y.
  void move_to_row(int y) {
    while (next_ < y) {
      const int dy = next_ + region_.y0;
      through_mask(dy, region_.x0, region_.x1, [&](int a, int b, const T* clip) {
        out_.row(dy, a, b, row_.data() + (a - region_.x0), clip);
      });
      if (started_) {
        std::fill(row_.begin(), row_.end(), 0.f);
        started_ = false;
      }
      ++next_;
    }
    started_ = true;
  }

  Compositor<T>& out_;
  const ClipMask* mask_;
  IntRect region_;
  bool unbounded_;
  std::vector<float>& row_;
  int next_ = 0;         // unbounded: first row not yet composited
  bool started_ = false;  // unbounded: row_ holds coverage of row next_
};

// ---- step 1: coverage sources ----

// A path under a transform, flattened and rasterized for exactly the region it is asked for (the rasterizer never
// sees geometry outside it).
class PathSource final : public CoverageSource {
 public:
  PathSource(Renderer& renderer, const Path& path, const Affine& to_device, FillRule rule, AntiAlias aa,
             double tolerance)
      : renderer_(renderer), path_(path), to_device_(to_device), rule_(rule), aa_(aa), tolerance_(tolerance) {}

  IntRect bounds() const override {
    const Rect box = path_.control_bounds();
    const Point corners[4] = {to_device_.apply({box.x0, box.y0}), to_device_.apply({box.x1, box.y0}),
                              to_device_.apply({box.x1, box.y1}), to_device_.apply({box.x0, box.y1})};
    Rect device = Rect::from_point(corners[0]);
    for (const Point& p : corners) device.include(p);
    if (!is_finite({device.x0, device.y0}) || !is_finite({device.x1, device.y1})) return {};
    return IntRect::covering(device);
  }

  void produce(const IntRect& region, Point offset, CoverageSink& sink) override {
    const Affine local = Affine::translate(offset.x - region.x0, offset.y - region.y0) * to_device_;
    const Polylines& lines = renderer_.flatten_for_fill(path_, local, tolerance_, region.width(), region.height());
    renderer_.rasterizer().fill(lines, rule_, aa_, region.width(), region.height(), sink);
  }

 private:
  Renderer& renderer_;
  const Path& path_;
  Affine to_device_;
  FillRule rule_;
  AntiAlias aa_;
  double tolerance_;
};

// An 8-bit coverage mask placed at a device pixel (cached glyphs). Shadow offsets are rounded to whole pixels.
class MaskSource final : public CoverageSource {
 public:
  MaskSource(const std::uint8_t* mask, int width, int height, std::ptrdiff_t stride, int x, int y,
             std::vector<float>& row)
      : mask_(mask), box_{x, y, x + width, y + height}, stride_(stride), row_(row) {}

  IntRect bounds() const override { return box_; }

  void produce(const IntRect& region, Point offset, CoverageSink& sink) override {
    const int ox = static_cast<int>(std::lround(offset.x)), oy = static_cast<int>(std::lround(offset.y));
    const IntRect placed = box_.offset(ox, oy).intersect(region);
    if (placed.empty()) return;
    row_.resize(static_cast<std::size_t>(placed.width()));
    for (int y = placed.y0; y < placed.y1; ++y) {
      const std::uint8_t* src = mask_ + (y - oy - box_.y0) * stride_ + (placed.x0 - ox - box_.x0);
      for (int i = 0; i < placed.width(); ++i) row_[i] = static_cast<float>(src[i]) * (1.f / 255.f);
      sink.row(y - region.y0, placed.x0 - region.x0, placed.x1 - region.x0, row_.data());
    }
  }

 private:
  const std::uint8_t* mask_;
  IntRect box_;
  std::ptrdiff_t stride_;
  std::vector<float>& row_;
};

// A plane of float coverage over a device box (a blurred shadow).
class PlaneSource final : public CoverageSource {
 public:
  PlaneSource(const std::vector<float>& plane, const IntRect& box) : plane_(plane), box_(box) {}
  IntRect bounds() const override { return box_; }
  void produce(const IntRect& region, Point, CoverageSink& sink) override {
    const IntRect area = box_.intersect(region);
    for (int y = area.y0; y < area.y1; ++y) {
      const float* src = plane_.data() + static_cast<std::size_t>(y - box_.y0) * box_.width() + (area.x0 - box_.x0);
      sink.row(y - region.y0, area.x0 - region.x0, area.x1 - region.x0, src);
    }
  }

 private:
  const std::vector<float>& plane_;
  IntRect box_;
};

// Writes coverage into a zeroed plane of levels (a clip mask in the making), quantized as the compositor would, and
// notes each row's extents (relative to the plane) from the calls themselves: the pixels not 0 lie in the span of
// the calls, the longest full span is the full run (rows from the sweep are the borders; a full run inside one is
// only missed, never wrong).
template <class T>
class LevelSink final : public CoverageSink {
 public:
  using Extent = ClipMask::RowExtent;
  LevelSink(T* plane, int width, Extent* rows) : plane_(plane), width_(width), rows_(rows) {}
  void span(int y, int x0, int x1, float coverage) override {
    const auto q = static_cast<T>(detail::ChannelMath<T>::quantize(coverage));
    if (q == 0) return;
    T* row = plane_ + static_cast<std::size_t>(y) * width_;
    std::fill(row + x0, row + x1, q);
    Extent& e = extend(y, x0, x1);
    if (q == detail::ChannelMath<T>::M && x1 - x0 > e.full1 - e.full0) {
      e.full0 = x0;
      e.full1 = x1;
    }
  }
  /// Each call writes its row of the plane and that row's extent only.
  bool takes_concurrent_rows() const override { return true; }

  void row(int y, int x0, int x1, const float* coverage) override {
    T* row = plane_ + static_cast<std::size_t>(y) * width_;
    for (int x = x0; x < x1; ++x) row[x] = static_cast<T>(detail::ChannelMath<T>::quantize(coverage[x - x0]));
    extend(y, x0, x1);
  }

 private:
  Extent& extend(int y, int x0, int x1) {
    Extent& e = rows_[y];
    if (e.x1 <= e.x0) e.x0 = x0;  // the first call of the row (calls come in increasing x)
    e.x1 = x1;
    return e;
  }
  T* plane_;
  int width_;
  Extent* rows_;
};

template <class T>
std::vector<T>& layer_pixels(canvas_detail::Layer& layer) {
  if constexpr (sizeof(T) == 1) {
    return layer.pixels8;
  } else {
    return layer.pixels16;
  }
}

// Shadows further than this from the shape (offset or blur, in device pixels) cannot reach any image (sides are
// at most kMaxImageSide): they are not drawn, and no pixel arithmetic ever sees such numbers.
constexpr double kShadowReachLimit = 1 << 24;

bool shadow_visible(const Shadow& shadow) {
  return shadow.color.a > 0 && (shadow.blur > 0 || shadow.offset_x != 0 || shadow.offset_y != 0) &&
         std::fabs(shadow.offset_x) < kShadowReachLimit && std::fabs(shadow.offset_y) < kShadowReachLimit &&
         shadow.blur < kShadowReachLimit;
}

// The most pixels a shadow's working buffer may take (as an image would): a larger blurred box is not drawn.
constexpr std::int64_t kMaxShadowPixels = std::int64_t{1} << 26;

// ---- the draw call, for one channel type ----

}  // namespace

template <class T>
void Canvas::Impl::draw_typed(CoverageSource& shape, const Paint& paint, const Affine& paint_to_device,
                              CompositeOp op, float alpha, bool with_shadow) {
  Impl& s = *this;
  const auto& st = s.state;
  const IntRect region = st.clip.box.intersect(s.target_box());
  if (region.empty()) return;
  const bool unbounded = !is_bounded(op);
  Compositor<T>& compositor = s.compositor<T>();
  const ImageView<T> target = s.target_view<T>();

  if (with_shadow && shadow_visible(st.shadow)) {
    // HTML canvas shadows: the shape's alpha (coverage x paint alpha), blurred with sigma = blur / 2, moved by the
    // offset, in the shadow colour, composited under the shape with the same operator, alpha and clip.
    const Shadow& sh = st.shadow;
    const double sigma = sh.blur / 2;
    const int reach = canvas_detail::blur_reach(sigma);
    const Point offset{sh.offset_x, sh.offset_y};
    IntRect box = shape.bounds().offset(static_cast<int>(std::floor(offset.x)), static_cast<int>(std::floor(offset.y)));
    box = IntRect{box.x0, box.y0, box.x1 + 1, box.y1 + 1}.expand(reach).intersect(region.expand(reach));
    if (!box.empty() && std::int64_t{box.width()} * box.height() <= kMaxShadowPixels) {
      auto& pixels = [&]() -> std::vector<T>& {
        if constexpr (sizeof(T) == 1) {
          return s.shadow8;
        } else {
          return s.shadow16;
        }
      }();
      pixels.assign(static_cast<std::size_t>(box.width()) * box.height() * 4, T{0});
      const ImageView<T> view{pixels.data(), box.x0, box.y0, box.width(), box.height(),
                              static_cast<std::ptrdiff_t>(box.width()) * 4};
      compositor.set(view, paint, Affine::translate(offset.x, offset.y) * paint_to_device, CompositeOp::SourceOver, 1);
      ClipSink<T> direct(compositor, nullptr, box, false, s.row_coverage);
      shape.produce(box, offset, direct);
      s.plane.resize(static_cast<std::size_t>(box.width()) * box.height());
      const float scale = 1.f / static_cast<float>(BasicImage<T>::kMax);
      for (std::size_t i = 0; i < s.plane.size(); ++i) s.plane[i] = static_cast<float>(pixels[i * 4 + 3]) * scale;
      canvas_detail::gaussian_blur(s.plane, s.plane_scratch, box.width(), box.height(), sigma);
      PlaneSource blurred(s.plane, box);
      compositor.set(target, Paint::solid(sh.color), Affine{}, op, alpha);
      if (!compositor.draws_nothing()) {
        const IntRect area = unbounded ? region : region.intersect(box);
        if (!area.empty()) {
          ClipSink<T> sink(compositor, st.clip.mask.get(), area, unbounded, s.row_coverage);
          blurred.produce(area, {}, sink);
          sink.finish();
        }
      }
    }
  }

  compositor.set(target, paint, paint_to_device, op, alpha);
  if (compositor.draws_nothing()) return;
  // Bounded operators touch only the shape: rasterize only where it and the clip meet.
  const IntRect area = unbounded ? region : region.intersect(shape.bounds());
  if (area.empty()) return;
  ClipSink<T> sink(compositor, st.clip.mask.get(), area, unbounded, s.row_coverage);
  shape.produce(area, {}, sink);
  sink.finish();
}

void Canvas::Impl::draw(CoverageSource& shape, const Paint& paint, const Affine& paint_to_device, CompositeOp op,
                        float alpha, bool with_shadow) {
  try {
    if (is16()) {
      draw_typed<std::uint16_t>(shape, paint, paint_to_device, op, alpha, with_shadow);
    } else {
      draw_typed<std::uint8_t>(shape, paint, paint_to_device, op, alpha, with_shadow);
    }
  } catch (const Error&) {
    // Coordinates that overflow to infinity under the transform: the call draws nothing (flattening checks them
    // before any pixel is touched).
  }
}

void Canvas::Impl::fill_path(const Path& p, const Affine& to_device, FillRule rule, const Paint& paint) {
  if (p.empty()) return;
  if (recording) {
    SceneCommand& c = record(SceneCommand::Kind::Fill);
    c.path = p;
    c.to_device = to_device;
    c.rule = rule;
    c.state.fill_paint = paint;
    return;
  }
  PathSource shape(renderer, p, to_device, rule, state.aa, state.tolerance);
  draw(shape, paint, state.transform, state.op, state.global_alpha, true);
}

void Canvas::Impl::stroke_user_path(const Path& user_path, const Affine& to_device) {
  if (user_path.empty()) return;
  if (recording) {
    SceneCommand& c = record(SceneCommand::Kind::Stroke);
    c.path = user_path;
    c.to_device = to_device;
    return;
  }
  // Strokes are geometry: the outline (user space, so a non-uniform transform shapes the pen as on the canvas)
  // is filled non-zero through the same pipeline as fills. Strokes thinner than a pixel stay geometric outlines
  // (as in Cairo and Skia): their coverage is their area, so they fade instead of vanishing or turning into
  // hairlines that ignore the operator and the clip.
  const Path outline = stroke_to_path(user_path, state.line, user_tolerance(to_device, state.tolerance));
  if (outline.empty()) return;
  PathSource shape(renderer, outline, to_device, FillRule::NonZero, state.aa, state.tolerance);
  draw(shape, state.stroke_paint, state.transform, state.op, state.global_alpha, true);
}

// ---- clips ----

namespace {

// Whether `lines` is one axis-aligned rectangle with whole-pixel corners. Sets `box` and the winding number of
// its inside.
bool pixel_aligned_rectangle(const Polylines& lines, IntRect& box, int& winding) {
  Rect r;
  if (!detail::axis_aligned_rectangle(lines, r, winding)) return false;
  for (const double v : {r.x0, r.y0, r.x1, r.y1}) {
    if (v != std::round(v) || std::abs(v) > 1e9) return false;
  }
  box = {static_cast<int>(r.x0), static_cast<int>(r.y0), static_cast<int>(r.x1), static_cast<int>(r.y1)};
  return true;
}

}  // namespace

void Canvas::Impl::clip_path(const Path& p, const Affine& to_device, FillRule rule) {
  if (recording) {
    state.recorded_clip = std::make_shared<const SceneClip>(
        SceneClip{p, to_device, rule, state.aa, state.tolerance, state.recorded_clip});
    return;
  }
  Clip& clip = state.clip;
  if (clip.box.empty()) return;  // nothing left to clip
  lines.clear();
  const Rect bounds{static_cast<double>(clip.box.x0), static_cast<double>(clip.box.y0),
                    static_cast<double>(clip.box.x1), static_cast<double>(clip.box.y1)};
  FlattenOptions options;
  options.tolerance = state.tolerance;
  options.clip = &bounds;
  try {
    flatten(p, to_device, options, lines);
  } catch (const Error&) {
    return;  // not finite under the transform: the call does nothing
  }
  // A pixel-aligned rectangle needs no mask: the clip box shrinks (any mask already there stays as it is).
  IntRect rect;
  int winding = 0;
  if (pixel_aligned_rectangle(lines, rect, winding)) {
    const bool inside = rule == FillRule::NonExterior || winding_fills(rule, winding);
    clip.box = inside ? clip.box.intersect(rect) : IntRect{};
    if (clip.box.empty()) clip.mask.reset();
    return;
  }
  // Anything else: a coverage mask over the part of the clip box the path can reach, multiplied by the old mask.
  if (lines.points.empty()) {
    clip = {};
    return;
  }
  Rect device = Rect::from_point(lines.points[0]);
  for (const Point& q : lines.points) device.include(q);
  const IntRect area = clip.box.intersect(IntRect::covering(device));
  if (area.empty()) {
    clip = {};
    return;
  }
  // The last mask made is reused when no state holds it any more (save, clip, draw, restore allocates once).
  std::shared_ptr<ClipMask> mask =
      spare_mask && spare_mask.use_count() == 1 ? spare_mask : std::make_shared<ClipMask>();
  spare_mask = mask;
  for (Point& q : lines.points) q = {q.x - area.x0, q.y - area.y0};
  const IntRect covered =
      is16() ? make_clip_mask<std::uint16_t>(*mask, area, rule) : make_clip_mask<std::uint8_t>(*mask, area, rule);
  if (covered.empty()) {
    clip = {};
    return;
  }
  clip.box = covered;
  clip.mask = std::move(mask);
}

// Rasterizes `lines` (relative to area's corner) into `mask` over `area` as levels, multiplied by the current clip's
// mask (rounded once per pixel: within one level of multiplying the float coverages), with each row's extents, and
// returns the box of the rows' extents (empty when nothing is covered).
template <class T>
IntRect Canvas::Impl::make_clip_mask(ClipMask& mask, const IntRect& area, FillRule rule) {
  using CM = detail::ChannelMath<T>;
  using W = typename CM::Wide;
  std::vector<T>& levels = [&]() -> std::vector<T>& {
    if constexpr (sizeof(T) == 1) {
      return mask.levels8;
    } else {
      return mask.levels16;
    }
  }();
  const ClipMask* old = state.clip.mask.get();
  mask.box = area;
  levels.assign(static_cast<std::size_t>(area.width()) * area.height(), T{0});
  mask.rows.assign(static_cast<std::size_t>(area.height()), ClipMask::RowExtent{});
  LevelSink<T> sink(levels.data(), area.width(), mask.rows.data());
  renderer.rasterizer().fill(lines, rule, state.aa, area.width(), area.height(), sink);
  IntRect covered{area.x1, area.y1, area.x0, area.y0};
  for (int y = area.y0; y < area.y1; ++y) {
    ClipMask::RowExtent& e = mask.rows[static_cast<std::size_t>(y - area.y0)];
    if (e.x1 <= e.x0) {
      e = {};
      continue;
    }
    // To device x; then, through the old clip, the product (0 outside the old row's extent, full where both are).
    e = {e.x0 + area.x0, e.x1 + area.x0, e.full0 + area.x0, e.full1 + area.x0};
    if (old) {
      const ClipMask::RowExtent& o = old->extent(y);
      T* row = levels.data() + static_cast<std::size_t>(y - area.y0) * area.width() - area.x0;
      const T* prev = old->at<T>(area.x0, y) - area.x0;
      const int a = std::max(e.x0, o.x0), b = std::min(e.x1, o.x1);
      std::fill(row + e.x0, row + std::clamp(a, e.x0, e.x1), T{0});
      for (int x = a; x < b; ++x) row[x] = static_cast<T>(CM::div(W{row[x]} * W{prev[x]}));
      std::fill(row + std::clamp(b, e.x0, e.x1), row + e.x1, T{0});
      const int f0 = std::max(e.full0, o.full0), f1 = std::min(e.full1, o.full1);
      e = b > a ? ClipMask::RowExtent{a, b, f0 < f1 ? f0 : 0, f0 < f1 ? f1 : 0} : ClipMask::RowExtent{};
      if (b <= a) continue;
    }
    covered.x0 = std::min(covered.x0, e.x0);
    covered.x1 = std::max(covered.x1, e.x1);
    covered.y0 = std::min(covered.y0, y);
    covered.y1 = y + 1;
  }
  return covered;
}

// ---- layers ----

void Canvas::Impl::begin_layer(const LayerOptions& options) {
  if (recording) record(SceneCommand::Kind::BeginLayer).layer = options;
  stack.push_back(state);
  canvas_detail::Layer layer;
  layer.box = state.clip.box.intersect(target_box());
  layer.options = options;
  layer.depth = stack.size();
  if (!layer.box.empty() && !recording) {
    const std::size_t n = static_cast<std::size_t>(layer.box.width()) * layer.box.height() * 4;
    if (is16()) {
      layer.pixels16.assign(n, 0);
    } else {
      layer.pixels8.assign(n, 0);
    }
  }
  // Opacity, operator and the clip's mask apply once, when the layer ends; inside it, drawing starts from the
  // defaults and is clipped only to the layer's box (clips set inside still intersect, and end with it).
  state.clip = {layer.box, nullptr};
  layers.push_back(std::move(layer));
  state.global_alpha = 1;
  state.op = CompositeOp::SourceOver;
  state.shadow = Shadow{};
}

namespace {

// Mask value of one premultiplied pixel: alpha, or SVG/CSS luminance (0.2125 R + 0.7154 G + 0.0721 B) of the
// premultiplied colour, which is the luminance of the straight colour times alpha.
float mask_value(const std::uint8_t* px, MaskMode mode) {
  if (mode == MaskMode::Alpha) return static_cast<float>(px[3]) * (1.f / 255.f);
  return (0.2125f * px[0] + 0.7154f * px[1] + 0.0721f * px[2]) * (1.f / 255.f);
}

template <class T>
const T* layer_row(const std::vector<T>& pixels, const IntRect& box, int x, int y) {
  return pixels.data() + (static_cast<std::size_t>(y - box.y0) * box.width() + (x - box.x0)) * 4;
}

}  // namespace

template <class T>
void Canvas::Impl::composite_layer(canvas_detail::Layer& layer) {
  Impl& s = *this;
  const auto& st = s.state;
  const LayerOptions& opt = layer.options;
  const IntRect region = st.clip.box.intersect(s.target_box());
  if (region.empty()) return;
  const bool unbounded = !is_bounded(opt.op);
  const IntRect area = unbounded ? region : region.intersect(layer.box);
  if (area.empty()) return;
  const ImageView<T> dst = s.target_view<T>();
  const std::vector<T>& src_pixels = layer_pixels<T>(layer);
  const Image* mask = opt.mask.get();
  const bool plain = opt.opacity >= 1 && !mask;
  std::vector<T> padded(static_cast<std::size_t>(area.width()) * 4);  // a source row reaching past the layer
  const IntRect inside = area.intersect(layer.box);
  auto& coverage = s.row_coverage;
  coverage.resize(static_cast<std::size_t>(area.width()));
  for (int y = area.y0; y < area.y1; ++y) {
    // Source row: the layer's pixels, transparent outside its box (unbounded operators reach past it).
    const T* src;
    if (inside.x0 == area.x0 && inside.x1 == area.x1 && y >= inside.y0 && y < inside.y1) {
      src = layer_row(src_pixels, layer.box, area.x0, y);
    } else {
      std::fill(padded.begin(), padded.end(), T{0});
      if (y >= inside.y0 && y < inside.y1) {
        std::copy_n(layer_row(src_pixels, layer.box, inside.x0, y), static_cast<std::size_t>(inside.width()) * 4,
                    padded.data() + static_cast<std::size_t>(inside.x0 - area.x0) * 4);
      }
      src = padded.data();
    }
    const float* cov = nullptr;
    if (!plain) {
      for (int x = area.x0; x < area.x1; ++x) {
        float m = 1;
        if (mask) {
          const int mx = x - opt.mask_x, my = y - opt.mask_y;
          m = mx >= 0 && my >= 0 && mx < mask->width && my < mask->height ? mask_value(mask->pixel(mx, my), opt.mask_mode)
                                                                            : 0.f;
        }
        coverage[x - area.x0] = m * std::clamp(opt.opacity, 0.f, 1.f);
      }
      cov = coverage.data();
    }
    const T* clip = st.clip.mask ? st.clip.mask->at<T>(area.x0, y) : nullptr;
    blend_row(opt.op, dst.pixel(area.x0, y), src, cov, clip, area.width());
  }
}

void Canvas::Impl::end_layer(bool composite) {
  if (layers.empty()) return;
  if (recording) record(SceneCommand::Kind::EndLayer);
  canvas_detail::Layer layer = std::move(layers.back());
  layers.pop_back();
  // Back to the state begin_layer() saved (it has the clip the layer is composited through).
  stack.resize(layer.depth);
  state = std::move(stack.back());
  stack.pop_back();
  if (!composite || recording || (layer.box.empty() && is_bounded(layer.options.op))) return;
  if (is16()) {
    composite_layer<std::uint16_t>(layer);
  } else {
    composite_layer<std::uint8_t>(layer);
  }
}

// ---- meshes ----

void Canvas::Impl::draw_mesh(const Mesh& mesh, const Affine& to_device, MeshOptions options) {
  if (recording) {
    SceneCommand& c = record(SceneCommand::Kind::Mesh);
    c.mesh = std::make_shared<const Mesh>(mesh);
    c.to_device = to_device;
    c.mesh_options = options;
    return;
  }
  options.opacity *= state.global_alpha;
  if (!(options.opacity > 0) && is_bounded(state.op)) return;
  const Mesh* device_mesh = &mesh;
  Mesh mapped;
  if (!to_device.is_identity()) {
    mapped = mesh;
    for (MeshVertex& v : mapped.vertices) v.position = to_device.apply(v.position);
    device_mesh = &mapped;
  }
  // The mesh renderer blends source-over onto a view: another operator or an antialiased clip applies to the
  // whole mesh once, through a layer (as the mesh's fragments are one drawing).
  const bool through_layer = state.op != CompositeOp::SourceOver || state.clip.mask != nullptr;
  if (through_layer) {
    LayerOptions layer;
    layer.op = state.op;
    begin_layer(layer);
  }
  if (is16()) {
    draw_mesh_onto_target<std::uint16_t>(*device_mesh, options);
  } else {
    draw_mesh_onto_target<std::uint8_t>(*device_mesh, options);
  }
  if (through_layer) end_layer();
}

template <class T>
void Canvas::Impl::draw_mesh_onto_target(const Mesh& device_mesh, const MeshOptions& options) {
  const IntRect box = state.clip.box.intersect(target_box());
  if (box.empty()) return;
  const ImageView<T> target = target_view<T>();
  const ImageView<T> view{target.pixel(box.x0, box.y0), box.x0, box.y0, box.width(), box.height(), target.stride};
  mesh_renderer.draw(view, device_mesh, options);
}

// ---- images ----

void Canvas::Impl::draw_image(const Image& image, Rect src, Rect dst, std::shared_ptr<const Image> shared) {
  if (recording) {
    SceneCommand& c = record(SceneCommand::Kind::DrawImage);
    c.image = shared ? std::move(shared) : std::make_shared<const Image>(image);
    c.src = src;
    c.dst = dst;
    return;
  }
  // Normalise negative sizes, then clip the source rectangle to the image, shrinking the destination with it.
  auto normalise = [](Rect& r) {
    if (r.x1 < r.x0) std::swap(r.x0, r.x1);
    if (r.y1 < r.y0) std::swap(r.y0, r.y1);
  };
  normalise(src);
  normalise(dst);
  const double kx = dst.width() / src.width(), ky = dst.height() / src.height();
  const Rect clipped{std::max(src.x0, 0.0), std::max(src.y0, 0.0), std::min(src.x1, double(image.width)),
                     std::min(src.y1, double(image.height))};
  if (clipped.empty()) return;
  const Rect target{dst.x0 + (clipped.x0 - src.x0) * kx, dst.y0 + (clipped.y0 - src.y0) * ky,
                    dst.x0 + (clipped.x1 - src.x0) * kx, dst.y0 + (clipped.y1 - src.y0) * ky};
  // The image is a pattern mapped onto the destination rectangle (the canvas does not own the image: an aliasing
  // pointer without ownership).
  Paint paint = Paint::pattern(std::shared_ptr<const Image>(std::shared_ptr<const Image>(), &image));
  paint.set_extend(Extend::Pad);
  paint.set_filter(state.smoothing ? state.filter : ImageFilter::Nearest);
  paint.set_transform(Affine{kx, 0, 0, ky, dst.x0 - src.x0 * kx, dst.y0 - src.y0 * ky});
  Path rect;
  rect.add_rect(target);
  PathSource shape(renderer, rect, state.transform, FillRule::NonZero, state.aa, state.tolerance);
  draw(shape, paint, state.transform, state.op, state.global_alpha, true);
}

}  // namespace vraster

// fill_mask lives here too: it is a draw call with a mask as its coverage source.
namespace vraster {

void Canvas::fill_mask(const std::uint8_t* mask, int width, int height, std::ptrdiff_t stride, int x, int y) {
  if (!mask || width <= 0 || height <= 0 || stride < width) return;
  Impl& s = *impl_;
  if (s.recording) {
    // The coverage goes into the alpha of an image (the scene keeps one kind of pixel buffer).
    auto copy = std::make_shared<Image>(width, height);
    for (int row = 0; row < height; ++row) {
      for (int col = 0; col < width; ++col) {
        std::uint8_t* px = copy->pixel(col, row);
        px[0] = px[1] = px[2] = 0;
        px[3] = mask[row * stride + col];
      }
    }
    SceneCommand& c = s.record(SceneCommand::Kind::FillMask);
    c.image = std::move(copy);
    c.x = x;
    c.y = y;
    return;
  }
  MaskSource shape(mask, width, height, stride, x, y, s.mask_row);
  s.draw(shape, s.state.fill_paint, s.state.transform, s.state.op, s.state.global_alpha, true);
}

}  // namespace vraster
