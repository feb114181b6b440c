// The canvas front door: the state stack, the current path (HTML canvas semantics), hit testing and pixel access.
// Drawing, clipping and layers are in draw.cpp.
//
// Every entry point checks its numbers first: a NaN or infinite argument makes it do nothing (the canvas spec),
// so the state, the path and the pixels stay exactly as they were.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "canvas/canvas_impl.hpp"
#include "vraster/error.hpp"
#include "vraster/fxaa.hpp"

namespace vraster {
namespace {

bool finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

namespace canvas_detail {

IntRect IntRect::intersect(const IntRect& o) const {
  IntRect r{std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  if (r.empty()) return {};
  return r;
}

IntRect IntRect::expand(int d) const { return {x0 - d, y0 - d, x1 + d, y1 + d}; }
IntRect IntRect::offset(int dx, int dy) const { return {x0 + dx, y0 + dy, x1 + dx, y1 + dy}; }

IntRect IntRect::covering(const Rect& r) {
  static constexpr double kLimit = 1 << 30;
  auto lo = [](double v) { return static_cast<int>(std::clamp(std::floor(v), -kLimit, kLimit)); };
  auto hi = [](double v) { return static_cast<int>(std::clamp(std::ceil(v), -kLimit, kLimit)); };
  if (!(r.x0 <= r.x1) || !(r.y0 <= r.y1)) return {};
  return {lo(r.x0), lo(r.y0), hi(r.x1), hi(r.y1)};
}

}  // namespace canvas_detail

using canvas_detail::IntRect;

Canvas::Impl::Impl(Image* i8, Image16* i16, int w, int h) : image8(i8), image16(i16), width(w), height(h) {
  state.clip.box = {0, 0, w, h};
}

IntRect Canvas::Impl::target_box() const {
  if (!layers.empty()) return layers.back().box;
  return {0, 0, width, height};
}

template <class T>
ImageView<T> Canvas::Impl::target_view() {
  if (!layers.empty()) {
    auto& layer = layers.back();
    T* px;
    if constexpr (sizeof(T) == 1) {
      px = layer.pixels8.data();
    } else {
      px = layer.pixels16.data();
    }
    return {px, layer.box.x0, layer.box.y0, layer.box.width(), layer.box.height(),
            static_cast<std::ptrdiff_t>(layer.box.width()) * 4};
  }
  if constexpr (sizeof(T) == 1) {
    return ImageView<T>::of(*image8);
  } else {
    return ImageView<T>::of(*image16);
  }
}
template ImageView<std::uint8_t> Canvas::Impl::target_view();
template ImageView<std::uint16_t> Canvas::Impl::target_view();

template <class T>
Compositor<T>& Canvas::Impl::compositor() {
  if constexpr (sizeof(T) == 1) {
    return compositor8;
  } else {
    return compositor16;
  }
}
template Compositor<std::uint8_t>& Canvas::Impl::compositor();
template Compositor<std::uint16_t>& Canvas::Impl::compositor();

void Canvas::Impl::restore() {
  const std::size_t floor = layers.empty() ? 0 : layers.back().depth;
  if (stack.size() <= floor) return;  // unmatched, or it would pop the state saved by begin_layer()
  state = std::move(stack.back());
  stack.pop_back();
}

void Canvas::Impl::add_arc_points() {
  const Affine& m = state.transform;
  for (Point& p : arc.points) {
    p = m.apply(p);
    if (!is_finite(p)) return;
  }
  const auto& pts = arc.points;
  if (pts.empty()) return;
  if (has_subpath()) {
    path.line_to(pts[0]);
  } else {
    path.move_to(pts[0]);
  }
  for (std::size_t i = 1; i + 2 < pts.size(); i += 3) path.cubic_to(pts[i], pts[i + 1], pts[i + 2]);
}

// ---- construction ----

Canvas::Canvas(Image& target) : impl_(std::make_unique<Impl>(&target, nullptr, target.width, target.height)) {}
Canvas::Canvas(Image16& target) : impl_(std::make_unique<Impl>(nullptr, &target, target.width, target.height)) {}
Canvas::Canvas(Scene& recording) {
  check_image_size(recording.width, recording.height);
  impl_ = std::make_unique<Impl>(nullptr, nullptr, recording.width, recording.height);
  impl_->recording = &recording;
}
Canvas::~Canvas() = default;
Canvas::Canvas(Canvas&&) noexcept = default;
Canvas& Canvas::operator=(Canvas&&) noexcept = default;

int Canvas::width() const { return impl_->width; }
int Canvas::height() const { return impl_->height; }

// ---- state ----

void Canvas::save() { impl_->stack.push_back(impl_->state); }
void Canvas::restore() { impl_->restore(); }

void Canvas::translate(double x, double y) {
  if (finite({x, y})) transform(Affine::translate(x, y));
}
void Canvas::scale(double sx, double sy) {
  if (finite({sx, sy})) transform(Affine::scale(sx, sy));
}
void Canvas::rotate(double radians) {
  if (!std::isfinite(radians)) return;
  const double c = std::cos(radians), s = std::sin(radians);
  transform(Affine{c, s, -s, c, 0, 0});
}
void Canvas::transform(const Affine& m) {
  if (!m.is_finite()) return;
  const Affine product = impl_->state.transform * m;
  if (product.is_finite()) impl_->state.transform = product;
}
void Canvas::set_transform(const Affine& m) {
  if (m.is_finite()) impl_->state.transform = m;
}
void Canvas::reset_transform() { impl_->state.transform = Affine{}; }
Affine Canvas::get_transform() const { return impl_->state.transform; }

void Canvas::set_fill_paint(const Paint& paint) { impl_->state.fill_paint = paint; }
void Canvas::set_stroke_paint(const Paint& paint) { impl_->state.stroke_paint = paint; }
namespace {
bool finite_color(Color c) { return finite({c.r, c.g, c.b, c.a}); }
}  // namespace
void Canvas::set_fill_color(Color color) {
  if (finite_color(color)) impl_->state.fill_paint = Paint::solid(color);
}
void Canvas::set_stroke_color(Color color) {
  if (finite_color(color)) impl_->state.stroke_paint = Paint::solid(color);
}
const Paint& Canvas::fill_paint() const { return impl_->state.fill_paint; }
const Paint& Canvas::stroke_paint() const { return impl_->state.stroke_paint; }

void Canvas::set_line_width(double width) {
  if (std::isfinite(width) && width > 0) impl_->state.line.width = width;
}
void Canvas::set_line_cap(LineCap cap) { impl_->state.line.cap = cap; }
void Canvas::set_line_join(LineJoin join) { impl_->state.line.join = join; }
void Canvas::set_miter_limit(double limit) {
  if (std::isfinite(limit) && limit > 0) impl_->state.line.miter_limit = limit;
}
void Canvas::set_line_dash(std::span<const double> dashes) {
  for (double d : dashes) {
    if (!std::isfinite(d) || d < 0) return;
  }
  auto& out = impl_->state.line.dashes;
  out.assign(dashes.begin(), dashes.end());
  // As setLineDash: an odd list is stored twice over (what getLineDash returns).
  if (dashes.size() % 2 == 1) out.insert(out.end(), dashes.begin(), dashes.end());
}
void Canvas::set_line_dash_offset(double offset) {
  if (std::isfinite(offset)) impl_->state.line.dash_offset = offset;
}
const StrokeStyle& Canvas::line_style() const { return impl_->state.line; }

void Canvas::set_global_alpha(double alpha) {
  if (std::isfinite(alpha) && alpha >= 0 && alpha <= 1) impl_->state.global_alpha = static_cast<float>(alpha);
}
void Canvas::set_composite(CompositeOp op) {
  if (static_cast<int>(op) < kCompositeOpCount) impl_->state.op = op;
}
void Canvas::set_fill_rule(FillRule rule) { impl_->state.rule = rule; }
void Canvas::set_anti_alias(AntiAlias aa) {
  // Every value is a coverage mode (FXAA is a post-filter: apply_fxaa()); out-of-range values are ignored.
  if (static_cast<int>(aa) <= static_cast<int>(AntiAlias::Msaa16)) impl_->state.aa = aa;
}
void Canvas::set_tolerance(double device_pixels) {
  if (std::isfinite(device_pixels) && device_pixels > 0) impl_->state.tolerance = device_pixels;
}
void Canvas::set_image_smoothing(bool on) { impl_->state.smoothing = on; }
void Canvas::set_image_filter(ImageFilter filter) { impl_->state.filter = filter; }
void Canvas::set_z(double z) {
  if (std::isfinite(z)) impl_->state.z = z;
}
void Canvas::set_shadow(const Shadow& shadow) {
  if (!finite_color(shadow.color) || !finite({shadow.offset_x, shadow.offset_y, shadow.blur}) || shadow.blur < 0) {
    return;
  }
  impl_->state.shadow = shadow;
}

// ---- the current path ----

void Canvas::begin_path() { impl_->path.clear(); }

void Canvas::move_to(double x, double y) {
  if (!finite({x, y})) return;
  const Point p = impl_->state.transform.apply({x, y});
  if (is_finite(p)) impl_->path.move_to(p);
}

void Canvas::line_to(double x, double y) {
  if (!finite({x, y})) return;
  const Point p = impl_->state.transform.apply({x, y});
  if (!is_finite(p)) return;
  // "Ensure there is a subpath": a line with no subpath only starts one.
  if (impl_->has_subpath()) {
    impl_->path.line_to(p);
  } else {
    impl_->path.move_to(p);
  }
}

void Canvas::quad_to(double cx, double cy, double x, double y) {
  if (!finite({cx, cy, x, y})) return;
  const Affine& m = impl_->state.transform;
  const Point c = m.apply({cx, cy}), p = m.apply({x, y});
  if (!is_finite(c) || !is_finite(p)) return;
  if (!impl_->has_subpath()) impl_->path.move_to(c);
  impl_->path.quad_to(c, p);
}

void Canvas::cubic_to(double x1, double y1, double x2, double y2, double x, double y) {
  if (!finite({x1, y1, x2, y2, x, y})) return;
  const Affine& m = impl_->state.transform;
  const Point c1 = m.apply({x1, y1}), c2 = m.apply({x2, y2}), p = m.apply({x, y});
  if (!is_finite(c1) || !is_finite(c2) || !is_finite(p)) return;
  if (!impl_->has_subpath()) impl_->path.move_to(c1);
  impl_->path.cubic_to(c1, c2, p);
}

void Canvas::arc(double cx, double cy, double r, double a0, double a1, bool ccw) {
  ellipse(cx, cy, r, r, 0, a0, a1, ccw);
}

void Canvas::ellipse(double cx, double cy, double rx, double ry, double rotation, double a0, double a1, bool ccw) {
  if (!finite({cx, cy, rx, ry, rotation, a0, a1})) return;
  if (rx < 0 || ry < 0) return;  // the spec throws IndexSizeError; drawing calls here never throw
  auto& arc_points = impl_->arc;
  arc_points.clear();
  canvas_detail::append_ellipse_arc({cx, cy}, rx, ry, rotation, a0, canvas_detail::canvas_arc_sweep(a0, a1, ccw),
                                    arc_points);
  impl_->add_arc_points();
}

void Canvas::arc_to(double x1, double y1, double x2, double y2, double r) {
  if (!finite({x1, y1, x2, y2, r}) || r < 0) return;
  Impl& s = *impl_;
  const Affine& m = s.state.transform;
  if (!s.has_subpath()) {
    move_to(x1, y1);
    return;  // the path now ends at p1 == p0: the spec's "line to p1", which adds nothing
  }
  if (!m.invertible()) return;
  const Point p0 = m.inverse().apply(s.path.current_point());
  const Point p1{x1, y1}, p2{x2, y2};
  s.arc.clear();
  if (p0 == p1 || p1 == p2 || r == 0 || cross(p1 - p0, p2 - p1) == 0 ||
      !canvas_detail::append_arc_to(p0, p1, p2, r, s.arc)) {
    line_to(x1, y1);
    return;
  }
  s.add_arc_points();
}

void Canvas::rect(double x, double y, double w, double h) {
  if (!finite({x, y, w, h})) return;
  const Affine& m = impl_->state.transform;
  const Point p[4] = {m.apply({x, y}), m.apply({x + w, y}), m.apply({x + w, y + h}), m.apply({x, y + h})};
  for (const Point& q : p) {
    if (!is_finite(q)) return;
  }
  Path& path = impl_->path;
  path.move_to(p[0]).line_to(p[1]).line_to(p[2]).line_to(p[3]).close();
  path.move_to(p[0]);  // "a new subpath with the point (x, y)"
}

void Canvas::round_rect(double x, double y, double w, double h, double radius) {
  if (!finite({x, y, w, h, radius}) || radius < 0) return;
  constexpr double kPi = 3.14159265358979323846;
  // One radius for every corner, scaled down as the spec scales radii that do not fit. The outline is built for
  // |w| x |h| (clockwise on screen from the top edge), then mirrored where w or h is negative, so it starts at
  // (x + r, y) and runs towards x + w like rect().
  const double aw = std::abs(w), ah = std::abs(h);
  const double r = std::min({radius, aw / 2, ah / 2});
  const double sx = w < 0 ? -1 : 1, sy = h < 0 ? -1 : 1;
  auto& a = impl_->arc;
  a.clear();
  const Point centres[4] = {{aw - r, r}, {aw - r, ah - r}, {r, ah - r}, {r, r}};
  for (int k = 0; k < 4; ++k) {
    canvas_detail::append_ellipse_arc(centres[k], r, r, 0, -kPi / 2 + k * kPi / 2, r > 0 ? kPi / 2 : 0, a);
  }
  const std::size_t per_corner = a.points.size() / 4;
  const Affine to_device = impl_->state.transform * Affine{sx, 0, 0, sy, x, y};
  for (Point& p : a.points) {
    p = to_device.apply(p);
    if (!is_finite(p)) return;
  }
  const Point start = to_device.apply({r, 0}), origin = to_device.apply({0, 0});
  if (!is_finite(start) || !is_finite(origin)) return;
  Path& path = impl_->path;
  path.move_to(start);
  for (std::size_t k = 0; k < 4; ++k) {
    const Point* corner = a.points.data() + k * per_corner;
    path.line_to(corner[0]);
    for (std::size_t i = 1; i + 2 < per_corner; i += 3) path.cubic_to(corner[i], corner[i + 1], corner[i + 2]);
  }
  path.close();
  path.move_to(origin);  // "a new subpath with the point (x, y)"
}

void Canvas::close_path() {
  if (impl_->has_subpath()) impl_->path.close();
}

// ---- drawing entry points (the work is in draw.cpp) ----

void Canvas::fill() { fill(impl_->state.rule); }
void Canvas::fill(FillRule rule) { impl_->fill_path(impl_->path, Affine{}, rule, impl_->state.fill_paint); }
void Canvas::fill(const Path& path) { fill(path, impl_->state.rule); }
void Canvas::fill(const Path& path, FillRule rule) {
  impl_->fill_path(path, impl_->state.transform, rule, impl_->state.fill_paint);
}

void Canvas::draw_mesh(const Mesh& mesh, const MeshOptions& options) {
  impl_->draw_mesh(mesh, impl_->state.transform, options);
}

void Canvas::stroke() {
  const Affine& m = impl_->state.transform;
  if (!m.invertible()) return;  // a singular transform squashes the stroke to nothing
  if (m.is_identity()) {
    impl_->stroke_user_path(impl_->path, m);
    return;
  }
  try {
    impl_->stroke_user_path(impl_->path.transformed(m.inverse()), m);
  } catch (const Error&) {
    // the path does not map back to user space with finite numbers: nothing to draw
  }
}
void Canvas::stroke(const Path& path) { impl_->stroke_user_path(path, impl_->state.transform); }

void Canvas::clip() { clip(impl_->state.rule); }
void Canvas::clip(FillRule rule) { impl_->clip_path(impl_->path, Affine{}, rule); }
void Canvas::clip(const Path& path, FillRule rule) { impl_->clip_path(path, impl_->state.transform, rule); }

namespace {
Path rect_path(double x, double y, double w, double h) {
  Path p;
  p.move_to(x, y).line_to(x + w, y).line_to(x + w, y + h).line_to(x, y + h).close();
  return p;
}
}  // namespace

void Canvas::fill_rect(double x, double y, double w, double h) {
  if (!finite({x, y, w, h}) || w == 0 || h == 0) return;
  impl_->fill_path(rect_path(x, y, w, h), impl_->state.transform, FillRule::NonZero, impl_->state.fill_paint);
}

void Canvas::stroke_rect(double x, double y, double w, double h) {
  if (!finite({x, y, w, h}) || (w == 0 && h == 0)) return;
  if (w == 0 || h == 0) {
    // The spec: one straight line from (x, y) to (x + w, y + h).
    Path line;
    line.move_to(x, y).line_to(x + w, y + h);
    impl_->stroke_user_path(line, impl_->state.transform);
    return;
  }
  impl_->stroke_user_path(rect_path(x, y, w, h), impl_->state.transform);
}

void Canvas::clear_rect(double x, double y, double w, double h) {
  if (!finite({x, y, w, h}) || w == 0 || h == 0) return;
  // Destination-out with opaque black: transparent where covered, antialiased edges, bounded by the shape (a plain
  // "clear" operator would wipe the whole clip region). Global alpha, operator and shadow do not apply.
  const Path p = rect_path(x, y, w, h);
  Impl& s = *impl_;
  const float alpha = s.state.global_alpha;
  const CompositeOp op = s.state.op;
  const Shadow shadow = s.state.shadow;
  s.state.global_alpha = 1;
  s.state.op = CompositeOp::DestinationOut;
  s.state.shadow = Shadow{};
  s.fill_path(p, s.state.transform, FillRule::NonZero, Paint::solid({0, 0, 0, 1}));
  s.state.global_alpha = alpha;
  s.state.op = op;
  s.state.shadow = shadow;
}

void Canvas::draw_image(const Image& image, double dx, double dy) {
  draw_image(image, 0, 0, image.width, image.height, dx, dy, image.width, image.height);
}

void Canvas::draw_image(const Image& image, double dx, double dy, double dw, double dh) {
  draw_image(image, 0, 0, image.width, image.height, dx, dy, dw, dh);
}

void Canvas::draw_image(const Image& image, double sx, double sy, double sw, double sh, double dx, double dy,
                        double dw, double dh) {
  if (!finite({sx, sy, sw, sh, dx, dy, dw, dh})) return;
  if (image.width <= 0 || image.height <= 0 || sw == 0 || sh == 0 || dw == 0 || dh == 0) return;
  impl_->draw_image(image, Rect{sx, sy, sx + sw, sy + sh}, Rect{dx, dy, dx + dw, dy + dh});
}

void Canvas::draw_image(std::shared_ptr<const Image> image, double dx, double dy, double dw, double dh) {
  if (!image || !finite({dx, dy, dw, dh})) return;
  if (image->width <= 0 || image->height <= 0 || dw == 0 || dh == 0) return;
  const Rect src{0, 0, double(image->width), double(image->height)};
  const Image& pixels = *image;  // before the pointer moves (argument order is unspecified)
  impl_->draw_image(pixels, src, Rect{dx, dy, dx + dw, dy + dh}, std::move(image));
}

void Canvas::begin_layer(const LayerOptions& options) { impl_->begin_layer(options); }
void Canvas::end_layer() { impl_->end_layer(); }

// ---- pixels ----

Image Canvas::get_pixels(int x, int y, int w, int h) const {
  Image out(w, h);
  std::fill(out.data.begin(), out.data.end(), std::uint8_t{0});
  const Impl& s = *impl_;
  if (s.recording) return out;
  const IntRect area = IntRect{x, y, x + w, y + h}.intersect({0, 0, s.width, s.height});
  for (int py = area.y0; py < area.y1; ++py) {
    std::uint8_t* dst = out.pixel(area.x0 - x, py - y);
    const std::size_t n = static_cast<std::size_t>(area.width()) * 4;
    if (s.image8) {
      std::memcpy(dst, s.image8->pixel(area.x0, py), n);
    } else {
      const std::uint16_t* src = s.image16->pixel(area.x0, py);
      for (std::size_t i = 0; i < n; ++i) dst[i] = static_cast<std::uint8_t>((src[i] * 255u + 32767u) / 65535u);
    }
  }
  return out;
}

void Canvas::put_pixels(const Image& pixels, int x, int y) {
  Impl& s = *impl_;
  if (s.recording) {
    SceneCommand& c = s.record(SceneCommand::Kind::PutPixels);
    c.image = std::make_shared<const Image>(pixels);
    c.x = x;
    c.y = y;
    return;
  }
  const IntRect area =
      IntRect{x, y, x + pixels.width, y + pixels.height}.intersect({0, 0, s.width, s.height});
  for (int py = area.y0; py < area.y1; ++py) {
    const std::uint8_t* src = pixels.pixel(area.x0 - x, py - y);
    const std::size_t n = static_cast<std::size_t>(area.width()) * 4;
    if (s.image8) {
      std::memcpy(s.image8->pixel(area.x0, py), src, n);
    } else {
      std::uint16_t* dst = s.image16->pixel(area.x0, py);
      for (std::size_t i = 0; i < n; ++i) dst[i] = static_cast<std::uint16_t>(src[i] * 257u);
    }
  }
}

std::int64_t Canvas::flood_fill(int x, int y, Color fill, const SeedFillOptions& options) {
  if (!finite({fill.r, fill.g, fill.b, fill.a})) return 0;
  Impl& s = *impl_;
  if (s.recording) {
    if (!(options.tolerance >= 0 && options.tolerance <= 1)) throw Error("flood_fill: the tolerance must be in [0, 1]");
    SceneCommand& c = s.record(SceneCommand::Kind::FloodFill);
    c.state.fill_paint = Paint::solid(fill);
    c.x = x;
    c.y = y;
    c.seed = options;
    return 0;
  }
  return s.image8 ? vraster::flood_fill(*s.image8, x, y, fill, options)
                  : vraster::flood_fill(*s.image16, x, y, fill, options);
}
std::uint64_t Canvas::exact_fallbacks() const { return impl_->renderer.rasterizer().exact_fallbacks(); }
void Canvas::set_threads(int threads) { impl_->renderer.set_threads(threads); }
int Canvas::threads() const { return impl_->renderer.threads(); }

void Canvas::apply_fxaa() {
  if (impl_->recording) {
    impl_->record(SceneCommand::Kind::Fxaa);
  } else if (impl_->image8) {
    fxaa(*impl_->image8);
  } else {
    fxaa(*impl_->image16);
  }
}

// ---- hit testing ----

namespace {

// Records whether the single pixel of a 1 x 1 aliased fill is covered.
class HitSink final : public CoverageSink {
 public:
  bool hit = false;
  void span(int, int, int, float coverage) override { hit = hit || coverage > 0; }
  void row(int, int x0, int x1, const float* coverage) override {
    for (int i = 0; i < x1 - x0; ++i) hit = hit || coverage[i] > 0;
  }
};

}  // namespace

bool Canvas::Impl::point_in(const Path& device_path, Point p, FillRule rule) {
  if (!is_finite(p) || device_path.empty()) return false;
  // Flatten with the pixel whose centre is p as the whole "image": the rasterizer's own rules decide (every fill
  // rule, NonExterior included), so hit testing agrees with what fill() draws.
  lines.clear();
  const Affine to_pixel = Affine::translate(0.5 - p.x, 0.5 - p.y);
  const Rect unit{0, 0, 1, 1};
  FlattenOptions options;
  options.tolerance = state.tolerance;
  options.clip = &unit;
  try {
    flatten(device_path, to_pixel, options, lines);
  } catch (const Error&) {
    return false;
  }
  // Points on the outline itself count as inside (the spec), whatever side the sampling rule gives them.
  bool on_edge = false;
  const Point centre{0.5, 0.5};
  lines.for_each_segment([&](Point a, Point b) {
    if (on_edge) return;
    const double c = cross(b - a, centre - a);
    if (std::abs(c) <= 1e-12 * (length(b - a) + 1) && centre.x >= std::min(a.x, b.x) &&
        centre.x <= std::max(a.x, b.x) && centre.y >= std::min(a.y, b.y) && centre.y <= std::max(a.y, b.y)) {
      on_edge = true;
    }
  });
  if (on_edge) return true;
  HitSink sink;
  renderer.rasterizer().fill(lines, rule, AntiAlias::None, 1, 1, sink);
  return sink.hit;
}

bool Canvas::is_point_in_path(double x, double y) const { return is_point_in_path(x, y, impl_->state.rule); }

bool Canvas::is_point_in_path(double x, double y, FillRule rule) const {
  if (!finite({x, y})) return false;
  return impl_->point_in(impl_->path, impl_->state.transform.apply({x, y}), rule);
}

bool Canvas::is_point_in_path(const Path& path, double x, double y, FillRule rule) const {
  if (!finite({x, y})) return false;
  const Affine& m = impl_->state.transform;
  try {
    return impl_->point_in(path.transformed(m), m.apply({x, y}), rule);
  } catch (const Error&) {
    return false;
  }
}

bool Canvas::is_point_in_stroke(double x, double y) const {
  const Affine& m = impl_->state.transform;
  if (!finite({x, y}) || !m.invertible()) return false;
  try {
    return is_point_in_stroke(impl_->path.transformed(m.inverse()), x, y);
  } catch (const Error&) {
    return false;
  }
}

bool Canvas::is_point_in_stroke(const Path& path, double x, double y) const {
  if (!finite({x, y})) return false;
  const Affine& m = impl_->state.transform;
  const Path outline = stroke_to_path(path, impl_->state.line, user_tolerance(m, impl_->state.tolerance));
  try {
    return impl_->point_in(outline.transformed(m), m.apply({x, y}), FillRule::NonZero);
  } catch (const Error&) {
    return false;
  }
}

}  // namespace vraster
