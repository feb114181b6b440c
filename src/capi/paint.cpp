// vraster C API: paints and composite operator names.
#include <cmath>

#include "capi/handles.hpp"

using namespace vraster;
using vraster::capi::finite;
using vraster::capi::guard;
using vraster::capi::present;
using vraster::capi::raw;
using vraster::capi::set_error;

namespace {

// A new paint handle, or NULL with a message naming the function when the numbers are unusable.
template <class F>
vr_paint* make_paint(const char* function, bool numbers_ok, F&& build) {
  if (!numbers_ok) {
    char message[160];
    std::snprintf(message, sizeof message, "%s: arguments must be finite (and radii >= 0)", function);
    set_error(message);
    return nullptr;
  }
  return guard<vr_paint*>(nullptr, [&] { return new vr_paint{build()}; });
}

Color clamped(double r, double g, double b, double a) {
  auto channel = [](double v) { return static_cast<float>(v < 0 ? 0 : v > 1 ? 1 : v); };
  return {channel(r), channel(g), channel(b), channel(a)};
}

bool to_extend(int e, Extend& out) {
  switch (e) {
    case VR_EXTEND_PAD: out = Extend::Pad; return true;
    case VR_EXTEND_REPEAT: out = Extend::Repeat; return true;
    case VR_EXTEND_REFLECT: out = Extend::Reflect; return true;
    case VR_EXTEND_NONE: out = Extend::None; return true;
  }
  return false;
}

int fail(const char* function, const char* why) {
  char message[200];
  std::snprintf(message, sizeof message, "%s: %s", function, why);
  set_error(message);
  return -1;
}

}  // namespace

extern "C" {

vr_paint* vr_paint_solid(double r, double g, double b, double a) {
  return make_paint(__func__, finite({r, g, b, a}), [&] { return Paint::solid(clamped(r, g, b, a)); });
}

vr_paint* vr_paint_linear(double x0, double y0, double x1, double y1) {
  return make_paint(__func__, finite({x0, y0, x1, y1}), [&] { return Paint::linear({x0, y0}, {x1, y1}); });
}

vr_paint* vr_paint_radial(double x0, double y0, double r0, double x1, double y1, double r1) {
  return make_paint(__func__, finite({x0, y0, r0, x1, y1, r1}) && r0 >= 0 && r1 >= 0,
                    [&] { return Paint::radial({x0, y0}, r0, {x1, y1}, r1); });
}

vr_paint* vr_paint_conic(double angle, double x, double y) {
  return make_paint(__func__, finite({angle, x, y}), [&] { return Paint::conic(angle, {x, y}); });
}

vr_paint* vr_paint_pattern(const vr_image* img) {
  if (!present(img, __func__, "image")) return nullptr;
  return make_paint(__func__, true, [&] {
    // A copy: later drawing on the image does not change the pattern (as createPattern).
    Paint p = Paint::pattern(std::make_shared<const Image>(*img->image));
    p.set_extend(Extend::Repeat);
    return p;
  });
}

int vr_paint_add_stop(vr_paint* p, double offset, double r, double g, double b, double a) {
  if (!present(p, __func__, "paint")) return -1;
  if (p->paint.kind() == Paint::Kind::Solid || p->paint.kind() == Paint::Kind::Pattern) {
    return fail(__func__, "the paint is not a gradient");
  }
  if (!finite({offset, r, g, b, a}) || offset < 0 || offset > 1) {
    return fail(__func__, "the offset must be in [0, 1] and every value finite");
  }
  return guard(-1, [&] {
    return p->paint.add_stop(offset, clamped(r, g, b, a)) ? 0 : fail("vr_paint_add_stop", "stop refused");
  });
}

namespace {

int set_extend(vr_paint* p, int x, int y, const char* function) {
  if (!present(p, function, "paint")) return -1;
  Extend ex, ey;
  if (!to_extend(x, ex) || !to_extend(y, ey)) return fail(function, "not a valid vr_extend");
  if (p->paint.kind() != Paint::Kind::Pattern && (ex != ey || ex == Extend::None)) {
    return fail(function, "gradients take one extend mode, pad, repeat or reflect");
  }
  return guard(-1, [&] {
    p->paint.set_extend(ex, ey);
    return 0;
  });
}

}  // namespace

int vr_paint_set_extend_xy(vr_paint* p, vr_extend x, vr_extend y) { return set_extend(p, raw(x), raw(y), __func__); }
int vr_paint_set_extend(vr_paint* p, vr_extend e) { return set_extend(p, raw(e), raw(e), __func__); }

int vr_paint_set_filter(vr_paint* p, vr_filter filter) {
  if (!present(p, __func__, "paint")) return -1;
  const int v = raw(filter);
  if (v < VR_FILTER_NEAREST || v > VR_FILTER_BICUBIC) return fail(__func__, "not a valid vr_filter");
  return guard(-1, [&] {
    p->paint.set_filter(static_cast<ImageFilter>(v));
    return 0;
  });
}

int vr_paint_set_transform(vr_paint* p, double a, double b, double c, double d, double e, double f) {
  if (!present(p, __func__, "paint")) return -1;
  if (!finite({a, b, c, d, e, f})) return fail(__func__, "the matrix must be finite");
  return guard(-1, [&] {
    p->paint.set_transform(Affine{a, b, c, d, e, f});
    return 0;
  });
}

int vr_paint_set_dither(vr_paint* p, int on) {
  if (!present(p, __func__, "paint")) return -1;
  p->paint.set_dither(on != 0);
  return 0;
}

void vr_paint_destroy(vr_paint* p) { delete p; }

int vr_composite_from_name(const char* css_name, vr_composite* out) {
  if (!present(css_name, __func__, "name") || !present(out, __func__, "out")) return -1;
  return guard(-1, [&] {
    CompositeOp op;
    if (!parse_composite_op(css_name, op)) {
      char message[200];
      std::snprintf(message, sizeof message, "vr_composite_from_name: unknown composite operator '%.100s'",
                    css_name);
      set_error(message);
      return -1;
    }
    *out = static_cast<vr_composite>(op);
    return 0;
  });
}

const char* vr_composite_name(vr_composite op) {
  const int v = raw(op);
  if (v < 0 || v >= kCompositeOpCount) return "";
  // to_string returns views of string literals, which are NUL-terminated.
  return to_string(static_cast<CompositeOp>(v)).data();
}

}  // extern "C"
