// libFuzzer target: the canvas through the C API (vraster/vraster.h): random call sequences with random numbers,
// NaN, infinities and huge values included, null handles and enum values out of range.
//
// Input: byte 0 sets the canvas side (1 .. 64 px); then records of one opcode byte followed by the numbers that
// call takes. A number is one byte: below 16 it picks a special value (NaN, +-inf, 0, +-1e300, ...); otherwise
// it and the next byte give ((b - 16) * 256 + next - 30720) / 64 (-480 .. 480 in steps of 1/64).
// What must hold: no crash, no sanitizer report, no exception escaping, every return value in its range, and
// premultiplied pixels (each colour channel <= alpha) after every call.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "vraster/vraster.h"

namespace {

class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}
  bool more() const { return p_ < end_; }
  std::uint8_t byte() { return p_ < end_ ? *p_++ : 0; }
  double number() {
    static constexpr double kSpecial[16] = {
        std::numeric_limits<double>::quiet_NaN(), INFINITY, -INFINITY, 0.0, 1e300, -1e300, 1e-300, -0.0,
        0.5, 1.0, -1.0, 1e6, -1e6, 3.14159265358979, 1e-7, 2.0};
    const std::uint8_t b = byte();
    if (b < 16) return kSpecial[b];
    const int raw = (b - 16) << 8 | byte();  // 0 .. 61439
    return (raw - 30720) / 64.0;
  }
  int small(int n) { return byte() % n; }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

void check_premultiplied(const vr_image* img) {
  int stride = 0;
  const unsigned char* p = vr_image_pixels(img, &stride);
  const int w = vr_image_width(img), h = vr_image_height(img);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const unsigned char* q = p + y * stride + x * 4;
      if (q[0] > q[3] || q[1] > q[3] || q[2] > q[3]) std::abort();
    }
  }
}

void check_status(int status) {
  if (status != 0 && status != -1) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 || size > 3600) return 0;
  Input in(data, size);
  const int side = 1 + in.byte() % 64;
  vr_image* img = vr_image_create(side, side);
  vr_canvas* c = vr_canvas_create(img);
  vr_image* tile = vr_image_create(3, 2);
  {
    int stride = 0;
    unsigned char* t = vr_image_pixels_mutable(tile, &stride);
    for (int i = 0; i < 6; ++i) {
      const int a = 40 * i + 40;
      t[(i / 3) * stride + (i % 3) * 4 + 0] = static_cast<unsigned char>(a * (i % 2));
      t[(i / 3) * stride + (i % 3) * 4 + 3] = static_cast<unsigned char>(a);
    }
  }
  vr_paint* paint = nullptr;
  int segments = 0;  // path commands since the last begin_path (bounded: the exact sweep is quadratic)
  for (int calls = 0; calls < 200 && in.more(); ++calls) {
    const int op = in.byte() % 49;
    if (op >= 7 && op <= 16 && ++segments > 64) {
      check_status(vr_canvas_begin_path(c));
      segments = 0;
    }
    int s = 0;
    switch (op) {
      case 0: s = vr_canvas_save(c); break;
      case 1: s = vr_canvas_restore(c); break;
      case 2: s = vr_canvas_translate(c, in.number(), in.number()); break;
      case 3: s = vr_canvas_scale(c, in.number(), in.number()); break;
      case 4: s = vr_canvas_rotate(c, in.number()); break;
      case 5: {
        const double a = in.number(), b = in.number(), cc = in.number(), d = in.number(), e = in.number();
        s = vr_canvas_transform(c, a, b, cc, d, e, in.number());
        break;
      }
      case 6: {
        const double a = in.number(), b = in.number(), cc = in.number(), d = in.number(), e = in.number();
        s = vr_canvas_set_transform(c, a, b, cc, d, e, in.number());
        break;
      }
      case 7: s = vr_canvas_move_to(c, in.number(), in.number()); break;
      case 8: s = vr_canvas_line_to(c, in.number(), in.number()); break;
      case 9: {
        const double x1 = in.number(), y1 = in.number(), x = in.number();
        s = vr_canvas_quad_to(c, x1, y1, x, in.number());
        break;
      }
      case 10: {
        const double x1 = in.number(), y1 = in.number(), x2 = in.number(), y2 = in.number(), x = in.number();
        s = vr_canvas_cubic_to(c, x1, y1, x2, y2, x, in.number());
        break;
      }
      case 11: {
        const double cx = in.number(), cy = in.number(), r = in.number(), a0 = in.number(), a1 = in.number();
        s = vr_canvas_arc(c, cx, cy, r, a0, a1, in.small(2));
        break;
      }
      case 12: {
        const double x1 = in.number(), y1 = in.number(), x2 = in.number(), y2 = in.number();
        s = vr_canvas_arc_to(c, x1, y1, x2, y2, in.number());
        break;
      }
      case 13: {
        const double cx = in.number(), cy = in.number(), rx = in.number(), ry = in.number(), rot = in.number();
        const double a0 = in.number(), a1 = in.number();
        s = vr_canvas_ellipse(c, cx, cy, rx, ry, rot, a0, a1, in.small(2));
        break;
      }
      case 14: {
        const double x = in.number(), y = in.number(), w = in.number();
        s = vr_canvas_rect(c, x, y, w, in.number());
        break;
      }
      case 15: {
        const double x = in.number(), y = in.number(), w = in.number(), h = in.number();
        s = vr_canvas_round_rect(c, x, y, w, h, in.number());
        break;
      }
      case 16: s = vr_canvas_close_path(c); break;
      case 17:
        s = vr_canvas_begin_path(c);
        segments = 0;
        break;
      case 18: s = vr_canvas_fill(c, static_cast<vr_fill_rule>(in.small(7))); break;  // 6: out of range
      case 19: s = vr_canvas_stroke(c); break;
      case 20: s = vr_canvas_clip(c, static_cast<vr_fill_rule>(in.small(7))); break;
      case 21: case 22: case 23: {
        const double x = in.number(), y = in.number(), w = in.number(), h = in.number();
        s = op == 21 ? vr_canvas_fill_rect(c, x, y, w, h)
                     : op == 22 ? vr_canvas_stroke_rect(c, x, y, w, h) : vr_canvas_clear_rect(c, x, y, w, h);
        break;
      }
      case 24: case 25: {
        const double r = in.number(), g = in.number(), b = in.number(), a = in.number();
        s = op == 24 ? vr_canvas_set_fill_rgba(c, r, g, b, a) : vr_canvas_set_stroke_rgba(c, r, g, b, a);
        break;
      }
      case 26: {  // a new paint: linear, radial, conic or pattern, with stops
        vr_paint_destroy(paint);
        const int kind = in.small(4);
        const double x0 = in.number(), y0 = in.number(), r0 = in.number(), x1 = in.number(), y1 = in.number();
        paint = kind == 0   ? vr_paint_linear(x0, y0, x1, y1)
                : kind == 1 ? vr_paint_radial(x0, y0, r0, x1, y1, in.number())
                : kind == 2 ? vr_paint_conic(r0, x0, y0)
                            : vr_paint_pattern(tile);
        for (int i = in.small(4); i > 0; --i) {
          const double o = in.number(), r = in.number(), g = in.number(), b = in.number();
          check_status(vr_paint_add_stop(paint, o, r, g, b, in.number()));
        }
        check_status(vr_paint_set_extend_xy(paint, static_cast<vr_extend>(in.small(5)),
                                            static_cast<vr_extend>(in.small(5))));
        check_status(vr_paint_set_filter(paint, static_cast<vr_filter>(in.small(4))));
        break;
      }
      case 27: {
        const double a = in.number(), b = in.number(), cc = in.number(), d = in.number(), e = in.number();
        s = vr_paint_set_transform(paint, a, b, cc, d, e, in.number());
        break;
      }
      case 28: s = in.small(2) ? vr_canvas_set_fill_paint(c, paint) : vr_canvas_set_stroke_paint(c, paint); break;
      case 29: s = vr_canvas_set_line_width(c, in.number()); break;
      case 30: s = vr_canvas_set_line_cap(c, static_cast<vr_line_cap>(in.small(4))); break;
      case 31: s = vr_canvas_set_line_join(c, static_cast<vr_line_join>(in.small(4))); break;
      case 32: s = vr_canvas_set_miter_limit(c, in.number()); break;
      case 33: {
        double dashes[5];
        const int n = in.small(6);
        for (int i = 0; i < n; ++i) dashes[i] = in.number();
        s = vr_canvas_set_line_dash(c, dashes, n, in.number());
        break;
      }
      case 34: s = vr_canvas_set_global_alpha(c, in.number()); break;
      case 35: s = vr_canvas_set_composite(c, static_cast<vr_composite>(in.small(28))); break;
      case 36: s = vr_canvas_set_antialias(c, static_cast<vr_antialias>(in.small(6))); break;
      case 37: s = vr_canvas_begin_layer(c, static_cast<float>(in.number())); break;
      case 38: {
        const double opacity = in.number();
        const auto composite = static_cast<vr_composite>(in.small(28));
        const int mx = static_cast<int>(in.small(16)) - 8, my = static_cast<int>(in.small(16)) - 8;
        s = vr_canvas_begin_layer_masked(c, static_cast<float>(opacity), composite, in.small(2) ? tile : nullptr,
                                         mx, my, static_cast<vr_mask_mode>(in.small(3)));
        break;
      }
      case 39: s = vr_canvas_end_layer(c); break;
      case 40: {
        const double x = in.number(), y = in.number(), w = in.number(), h = in.number();
        s = vr_canvas_draw_image(c, in.small(2) ? tile : img, x, y, w, h);
        break;
      }
      case 41: {
        const double sx = in.number(), sy = in.number(), sw = in.number(), sh = in.number();
        const double dx = in.number(), dy = in.number(), dw = in.number(), dh = in.number();
        s = vr_canvas_draw_image_part(c, tile, sx, sy, sw, sh, dx, dy, dw, dh);
        break;
      }
      case 42: {
        const int x = in.small(80) - 8, y = in.small(80) - 8, w = in.small(70), h = in.small(70);
        vr_image* part = vr_canvas_get_pixels(c, x, y, w, h);
        if (part) check_premultiplied(part);
        s = vr_canvas_put_pixels(c, part, in.small(80) - 8, in.small(80) - 8);
        vr_image_destroy(part);
        break;
      }
      case 43: {
        const double x = in.number(), y = in.number();
        const int inside = vr_canvas_is_point_in_path(c, x, y, static_cast<vr_fill_rule>(in.small(7)));
        const int on_stroke = vr_canvas_is_point_in_stroke(c, x, y);
        if (inside < -1 || inside > 1 || on_stroke < -1 || on_stroke > 1) std::abort();
        break;
      }
      case 44: {
        const double r = in.number(), g = in.number(), b = in.number(), a = in.number();
        const double ox = in.number(), oy = in.number();
        s = vr_canvas_set_shadow(c, r, g, b, a, ox, oy, std::fmod(std::fabs(in.number()), 64.0));
        break;
      }
      case 45: s = vr_canvas_set_image_smoothing(c, in.small(2), static_cast<vr_filter>(in.small(4))); break;
      case 46: s = vr_canvas_set_tolerance(c, in.number()); break;
      case 47: {  // calls on null handles must fail cleanly
        check_status(vr_canvas_fill(nullptr, VR_FILL_NONZERO));
        check_status(vr_canvas_set_fill_paint(c, nullptr));
        if (vr_canvas_get_pixels(nullptr, 0, 0, 1, 1) != nullptr) std::abort();
        break;
      }
      case 48: {  // a small mesh: hostile numbers, indices out of range, every mode
        double vertices[6 * 7];
        const std::size_t n = in.small(7);
        for (std::size_t i = 0; i < n * 7; ++i) vertices[i] = in.number();
        unsigned indices[4 * 3];
        const std::size_t t = in.small(5);
        for (std::size_t i = 0; i < t * 3; ++i) indices[i] = in.small(8);
        s = vr_canvas_draw_triangles(c, vertices, n, indices, t, in.small(2), in.small(2), in.small(2));
        break;
      }
    }
    check_status(s);
    check_premultiplied(img);
  }
  vr_paint_destroy(paint);
  vr_image_destroy(tile);
  vr_canvas_destroy(c);
  vr_image_destroy(img);
  return 0;
}
