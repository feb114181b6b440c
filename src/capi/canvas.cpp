// vraster C API: the canvas. Each function checks its handle and its enum values, then calls vraster::Canvas
// inside guard() (no exception reaches C). Bad numbers are the canvas's business: it ignores them.
#include <algorithm>
#include <cmath>
#include <span>

#include "capi/handles.hpp"
#include "vraster/fxaa.hpp"
#include "vraster/mesh_io.hpp"

using vraster::capi::guard;
using vraster::capi::present;
using vraster::capi::raw;
using vraster::capi::set_error;

namespace vraster::capi {
namespace {

// Runs `body(canvas)` for a present canvas; 0 on success, -1 on failure.
template <class Handle, class F>
int with_canvas(Handle* c, const char* function, F&& body) {
  if (!present(c, function, "canvas")) return -1;
  return guard(-1, [&] {
    body(*c);
    return 0;
  });
}

int bad_enum(const char* function, const char* what, int value) {
  char message[160];
  std::snprintf(message, sizeof message, "%s: %d is not a valid %s", function, value, what);
  set_error(message);
  return -1;
}

bool to_rule(int i, FillRule& out) {
  static constexpr FillRule kRules[] = {FillRule::NonZero,  FillRule::EvenOdd,  FillRule::NonExterior,
                                        FillRule::Positive, FillRule::Negative, FillRule::AbsGeq2};
  if (i < 0 || i >= static_cast<int>(std::size(kRules))) return false;
  out = kRules[i];
  return true;
}

bool to_op(int i, CompositeOp& out) {
  static_assert(VR_COMPOSITE_LUMINOSITY + 1 == kCompositeOpCount);
  static_assert(static_cast<int>(CompositeOp::Luminosity) == VR_COMPOSITE_LUMINOSITY);
  static_assert(static_cast<int>(CompositeOp::Multiply) == VR_COMPOSITE_MULTIPLY);
  if (i < 0 || i >= kCompositeOpCount) return false;
  out = static_cast<CompositeOp>(i);
  return true;
}

bool to_filter(int i, ImageFilter& out) {
  if (i < 0 || i > 2) return false;
  out = static_cast<ImageFilter>(i);
  return true;
}

// A straight colour from C doubles; false (the call does nothing) when one is not finite. Channels are clamped.
bool to_color(double r, double g, double b, double a, Color& out) {
  if (!finite({r, g, b, a})) return false;
  auto channel = [](double v) { return static_cast<float>(std::clamp(v, 0.0, 1.0)); };
  out = {channel(r), channel(g), channel(b), channel(a)};
  return true;
}

// The mirrored state follows the canvas's stack (see handles.hpp).
void mirror_save(vr_canvas& c) { c.saved.push_back(c.state); }
void mirror_restore(vr_canvas& c) {
  const std::size_t floor = c.layer_floors.empty() ? 0 : c.layer_floors.back();
  if (c.saved.size() <= floor) return;
  c.state = std::move(c.saved.back());
  c.saved.pop_back();
}

}  // namespace
}  // namespace vraster::capi

using namespace vraster;
using namespace vraster::capi;

extern "C" {

vr_canvas* vr_canvas_create(vr_image* target) {
  if (!present(target, "vr_canvas_create", "target image")) return nullptr;
  return guard<vr_canvas*>(nullptr, [&] { return new vr_canvas(target->image); });
}

void vr_canvas_destroy(vr_canvas* c) { delete c; }

int vr_canvas_save(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) {
    s.canvas.save();
    mirror_save(s);
  });
}
int vr_canvas_restore(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) {
    s.canvas.restore();
    mirror_restore(s);
  });
}

int vr_canvas_translate(vr_canvas* c, double x, double y) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.translate(x, y); });
}
int vr_canvas_scale(vr_canvas* c, double sx, double sy) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.scale(sx, sy); });
}
int vr_canvas_rotate(vr_canvas* c, double radians) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.rotate(radians); });
}
int vr_canvas_transform(vr_canvas* canvas, double a, double b, double c, double d, double e, double f) {
  return with_canvas(canvas, __func__, [&](vr_canvas& s) { s.canvas.transform(Affine{a, b, c, d, e, f}); });
}
int vr_canvas_set_transform(vr_canvas* canvas, double a, double b, double c, double d, double e, double f) {
  return with_canvas(canvas, __func__, [&](vr_canvas& s) { s.canvas.set_transform(Affine{a, b, c, d, e, f}); });
}
int vr_canvas_reset_transform(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) { s.canvas.reset_transform(); });
}
int vr_canvas_get_transform(const vr_canvas* c, double m[6]) {
  if (!present(m, __func__, "matrix")) return -1;
  return with_canvas(c, __func__, [&](const vr_canvas& s) {
    const Affine t = s.canvas.get_transform();
    const double values[6] = {t.a, t.b, t.c, t.d, t.e, t.f};
    std::copy(values, values + 6, m);
  });
}

// ---- path ----

int vr_canvas_begin_path(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) { s.canvas.begin_path(); });
}
int vr_canvas_move_to(vr_canvas* c, double x, double y) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.move_to(x, y); });
}
int vr_canvas_line_to(vr_canvas* c, double x, double y) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.line_to(x, y); });
}
int vr_canvas_quad_to(vr_canvas* c, double cx, double cy, double x, double y) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.quad_to(cx, cy, x, y); });
}
int vr_canvas_cubic_to(vr_canvas* c, double x1, double y1, double x2, double y2, double x, double y) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.cubic_to(x1, y1, x2, y2, x, y); });
}
int vr_canvas_arc(vr_canvas* c, double cx, double cy, double r, double a0, double a1, int ccw) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.arc(cx, cy, r, a0, a1, ccw != 0); });
}
int vr_canvas_arc_to(vr_canvas* c, double x1, double y1, double x2, double y2, double r) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.arc_to(x1, y1, x2, y2, r); });
}
int vr_canvas_ellipse(vr_canvas* c, double cx, double cy, double rx, double ry, double rotation, double a0,
                      double a1, int ccw) {
  return with_canvas(c, __func__,
                     [&](vr_canvas& s) { s.canvas.ellipse(cx, cy, rx, ry, rotation, a0, a1, ccw != 0); });
}
int vr_canvas_rect(vr_canvas* c, double x, double y, double w, double h) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.rect(x, y, w, h); });
}
int vr_canvas_round_rect(vr_canvas* c, double x, double y, double w, double h, double radius) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.round_rect(x, y, w, h, radius); });
}
int vr_canvas_close_path(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) { s.canvas.close_path(); });
}

// ---- drawing ----

int vr_canvas_fill(vr_canvas* c, vr_fill_rule rule) {
  FillRule r;
  if (!to_rule(raw(rule), r)) return bad_enum(__func__, "vr_fill_rule", raw(rule));
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.fill(r); });
}
int vr_canvas_stroke(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) { s.canvas.stroke(); });
}
int vr_canvas_clip(vr_canvas* c, vr_fill_rule rule) {
  FillRule r;
  if (!to_rule(raw(rule), r)) return bad_enum(__func__, "vr_fill_rule", raw(rule));
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.clip(r); });
}
int vr_canvas_fill_rect(vr_canvas* c, double x, double y, double w, double h) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.fill_rect(x, y, w, h); });
}
int vr_canvas_stroke_rect(vr_canvas* c, double x, double y, double w, double h) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.stroke_rect(x, y, w, h); });
}
int vr_canvas_clear_rect(vr_canvas* c, double x, double y, double w, double h) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.clear_rect(x, y, w, h); });
}

int vr_canvas_draw_image_part(vr_canvas* c, const vr_image* img, double sx, double sy, double sw, double sh,
                              double dx, double dy, double dw, double dh) {
  if (!present(img, __func__, "image")) return -1;
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    if (img->image == s.target) {
      const Image copy = *img->image;  // drawing an image onto itself reads the pixels as they were
      s.canvas.draw_image(copy, sx, sy, sw, sh, dx, dy, dw, dh);
    } else {
      s.canvas.draw_image(*img->image, sx, sy, sw, sh, dx, dy, dw, dh);
    }
  });
}
int vr_canvas_draw_image(vr_canvas* c, const vr_image* img, double dx, double dy, double dw, double dh) {
  if (!present(img, __func__, "image")) return -1;
  return vr_canvas_draw_image_part(c, img, 0, 0, img->image->width, img->image->height, dx, dy, dw, dh);
}

// ---- style ----

int vr_canvas_set_fill_rgba(vr_canvas* c, double r, double g, double b, double a) {
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    Color color;
    if (to_color(r, g, b, a, color)) s.canvas.set_fill_color(color);
  });
}
int vr_canvas_set_stroke_rgba(vr_canvas* c, double r, double g, double b, double a) {
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    Color color;
    if (to_color(r, g, b, a, color)) s.canvas.set_stroke_color(color);
  });
}
int vr_canvas_set_fill_paint(vr_canvas* c, const vr_paint* p) {
  if (!present(p, __func__, "paint")) return -1;
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_fill_paint(p->paint); });
}
int vr_canvas_set_stroke_paint(vr_canvas* c, const vr_paint* p) {
  if (!present(p, __func__, "paint")) return -1;
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_stroke_paint(p->paint); });
}
int vr_canvas_set_line_width(vr_canvas* c, double width) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_line_width(width); });
}
int vr_canvas_set_line_cap(vr_canvas* c, vr_line_cap cap) {
  const int v = raw(cap);
  if (v < VR_CAP_BUTT || v > VR_CAP_SQUARE) return bad_enum(__func__, "vr_line_cap", v);
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_line_cap(static_cast<LineCap>(v)); });
}
int vr_canvas_set_line_join(vr_canvas* c, vr_line_join join) {
  const int v = raw(join);
  if (v < VR_JOIN_MITER || v > VR_JOIN_BEVEL) return bad_enum(__func__, "vr_line_join", v);
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_line_join(static_cast<LineJoin>(v)); });
}
int vr_canvas_set_miter_limit(vr_canvas* c, double limit) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_miter_limit(limit); });
}
int vr_canvas_set_line_dash(vr_canvas* c, const double* dashes, int n, double offset) {
  if (n < 0) return bad_enum(__func__, "dash count", n);
  if (n > 0 && !present(dashes, __func__, "dash array")) return -1;
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    s.canvas.set_line_dash(std::span<const double>(dashes, static_cast<std::size_t>(n)));
    if (std::isfinite(offset)) s.canvas.set_line_dash_offset(offset);
  });
}
int vr_canvas_set_global_alpha(vr_canvas* c, double alpha) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_global_alpha(alpha); });
}
int vr_canvas_set_composite(vr_canvas* c, vr_composite op) {
  CompositeOp o;
  if (!to_op(raw(op), o)) return bad_enum(__func__, "vr_composite", raw(op));
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    s.canvas.set_composite(o);
    s.state.op = o;
  });
}
int vr_canvas_set_antialias(vr_canvas* c, vr_antialias aa) {
  static constexpr AntiAlias kModes[] = {AntiAlias::None, AntiAlias::Analytic, AntiAlias::Exact, AntiAlias::Ssaa4,
                                         AntiAlias::Msaa16};
  const int v = raw(aa);
  if (v < 0 || v >= static_cast<int>(std::size(kModes))) return bad_enum(__func__, "vr_antialias", v);
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_anti_alias(kModes[v]); });
}
int vr_canvas_set_tolerance(vr_canvas* c, double device_pixels) {
  return with_canvas(c, __func__, [&](vr_canvas& s) { s.canvas.set_tolerance(device_pixels); });
}
int vr_canvas_set_image_smoothing(vr_canvas* c, int on, vr_filter filter) {
  ImageFilter f;
  if (!to_filter(raw(filter), f)) return bad_enum(__func__, "vr_filter", raw(filter));
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    s.canvas.set_image_smoothing(on != 0);
    s.canvas.set_image_filter(f);
  });
}
int vr_canvas_set_shadow(vr_canvas* c, double r, double g, double b, double a, double offset_x, double offset_y,
                         double blur) {
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    Color color;
    if (!to_color(r, g, b, a, color) || !finite({offset_x, offset_y, blur}) || blur < 0) return;
    s.canvas.set_shadow(Shadow{color, offset_x, offset_y, blur});
  });
}

// ---- layers ----

int vr_canvas_begin_layer_masked(vr_canvas* c, float opacity, vr_composite op, const vr_image* mask, int mask_x,
                                 int mask_y, vr_mask_mode mode) {
  CompositeOp o;
  if (!to_op(raw(op), o)) return bad_enum(__func__, "vr_composite", raw(op));
  const int mask_mode = raw(mode);
  if (mask_mode != VR_MASK_ALPHA && mask_mode != VR_MASK_LUMINANCE) {
    return bad_enum(__func__, "vr_mask_mode", mask_mode);
  }
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    LayerOptions options;
    // A NaN or infinite opacity is a bad number like any other: the layer still opens (so end_layer pairs with
    // it) but draws nothing.
    options.opacity = std::isfinite(opacity) ? std::clamp(opacity, 0.f, 1.f) : 0.f;
    options.op = o;
    if (mask) {
      options.mask = std::make_shared<const Image>(*mask->image);
      options.mask_x = mask_x;
      options.mask_y = mask_y;
      options.mask_mode = mask_mode == VR_MASK_ALPHA ? MaskMode::Alpha : MaskMode::Luminance;
    }
    s.canvas.begin_layer(options);
    mirror_save(s);
    s.layer_floors.push_back(s.saved.size());
    s.state.op = CompositeOp::SourceOver;  // inside a layer drawing starts from source-over, as in the canvas
  });
}
int vr_canvas_begin_layer(vr_canvas* c, float opacity) {
  if (!present(c, __func__, "canvas")) return -1;
  return vr_canvas_begin_layer_masked(c, opacity, static_cast<vr_composite>(c->state.op), nullptr, 0, 0,
                                      VR_MASK_ALPHA);
}
int vr_canvas_end_layer(vr_canvas* c) {
  if (!present(c, __func__, "canvas")) return -1;
  if (c->layer_floors.empty()) {
    set_error("vr_canvas_end_layer: no layer is open");
    return -1;
  }
  return with_canvas(c, __func__, [](vr_canvas& s) {
    s.canvas.end_layer();
    s.saved.resize(s.layer_floors.back());
    s.layer_floors.pop_back();
    s.state = std::move(s.saved.back());
    s.saved.pop_back();
  });
}

// ---- pixels and hit testing ----

vr_image* vr_canvas_get_pixels(const vr_canvas* c, int x, int y, int w, int h) {
  if (!present(c, __func__, "canvas")) return nullptr;
  return guard<vr_image*>(nullptr, [&] {
    check_image_size(w, h);
    return new vr_image{std::make_shared<Image>(c->canvas.get_pixels(x, y, w, h))};
  });
}
int vr_canvas_put_pixels(vr_canvas* c, const vr_image* img, int x, int y) {
  if (!present(img, __func__, "image")) return -1;
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    if (img->image == s.target) {
      const Image copy = *img->image;  // the source must not change while it is written
      s.canvas.put_pixels(copy, x, y);
    } else {
      s.canvas.put_pixels(*img->image, x, y);
    }
  });
}
int vr_canvas_is_point_in_path(const vr_canvas* c, double x, double y, vr_fill_rule rule) {
  FillRule r;
  if (!to_rule(raw(rule), r)) return bad_enum(__func__, "vr_fill_rule", raw(rule));
  if (!present(c, __func__, "canvas")) return -1;
  return guard(-1, [&] { return c->canvas.is_point_in_path(x, y, r) ? 1 : 0; });
}
int vr_canvas_is_point_in_stroke(const vr_canvas* c, double x, double y) {
  if (!present(c, __func__, "canvas")) return -1;
  return guard(-1, [&] { return c->canvas.is_point_in_stroke(x, y) ? 1 : 0; });
}
namespace {
long long flood(vr_canvas* c, const char* function, int x, int y, Color fill, int connectivity,
                SeedFillOptions options) {
  if (!vraster::capi::present(c, function, "canvas")) return -1;
  if (connectivity != 4 && connectivity != 8) {
    char message[128];
    std::snprintf(message, sizeof message, "%s: connectivity must be 4 or 8, not %d", function, connectivity);
    set_error(message);
    return -1;
  }
  options.connectivity = connectivity == 4 ? Connectivity::Four : Connectivity::Eight;
  return guard(-1LL, [&] { return static_cast<long long>(c->canvas.flood_fill(x, y, fill, options)); });
}
}  // namespace

long long vr_canvas_flood_fill(vr_canvas* c, int x, int y, double r, double g, double b, double a, int connectivity,
                               double tolerance) {
  SeedFillOptions options;
  options.tolerance = tolerance;
  return flood(c, __func__, x, y, Color{float(r), float(g), float(b), float(a)}, connectivity, options);
}

long long vr_canvas_flood_fill_to_boundary(vr_canvas* c, int x, int y, double r, double g, double b, double a,
                                           double br, double bg, double bb, double ba, int connectivity,
                                           double tolerance) {
  SeedFillOptions options;
  options.region = SeedRegion::Boundary;
  options.boundary = Color{float(br), float(bg), float(bb), float(ba)};
  options.tolerance = tolerance;
  if (!std::isfinite(br) || !std::isfinite(bg) || !std::isfinite(bb) || !std::isfinite(ba)) return 0;
  return flood(c, __func__, x, y, Color{float(r), float(g), float(b), float(a)}, connectivity, options);
}

int vr_canvas_draw_triangles(vr_canvas* c, const double* vertices, size_t vertex_count, const unsigned* indices,
                             size_t triangle_count, int gouraud, int zbuffer, int antialias) {
  if ((vertex_count > 0 && vertices == nullptr) || (triangle_count > 0 && indices == nullptr)) {
    set_error("vr_canvas_draw_triangles: a null array with a non-zero count");
    return -1;
  }
  if (vertex_count > kMaxMeshVertices || triangle_count > kMaxMeshTriangles) {
    set_error("vr_canvas_draw_triangles: more than 2^22 vertices or 2^23 triangles");
    return -1;
  }
  return with_canvas(c, __func__, [&](vr_canvas& s) {
    Mesh mesh;
    mesh.vertices.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
      const double* v = vertices + 7 * i;
      MeshVertex& out = mesh.vertices[i];
      out.position = {v[0], v[1]};
      out.depth = v[2];
      out.color = Color{float(v[3]), float(v[4]), float(v[5]), float(v[6])};
    }
    mesh.triangles.resize(triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t) {
      for (std::size_t k = 0; k < 3; ++k) mesh.triangles[t][k] = indices[3 * t + k];
    }
    MeshOptions options;
    options.shading = gouraud ? Shading::Gouraud : Shading::Flat;
    options.depth = zbuffer ? DepthMode::ZBuffer : DepthMode::None;
    options.antialias = antialias != 0;
    s.canvas.draw_mesh(mesh, options);
  });
}

int vr_canvas_apply_fxaa(vr_canvas* c) {
  return with_canvas(c, __func__, [](vr_canvas& s) { s.canvas.apply_fxaa(); });
}

}  // extern "C"
