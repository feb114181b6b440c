// Slow references for compositing and paint (see paint_reference.hpp). Written from the spec text, in double.
#include "support/paint_reference.hpp"

#include <algorithm>
#include <cmath>

namespace vraster::test {
namespace {

double clamp01(double v) { return std::min(1.0, std::max(0.0, v)); }

// W3C Compositing Level 1, 9.1: Fa and Fb of each Porter-Duff operator.
void factors(CompositeOp op, double as, double ab, double& fa, double& fb) {
  switch (op) {
    case CompositeOp::Clear: fa = 0; fb = 0; return;
    case CompositeOp::Copy: fa = 1; fb = 0; return;
    case CompositeOp::SourceOver: fa = 1; fb = 1 - as; return;
    case CompositeOp::DestinationOver: fa = 1 - ab; fb = 1; return;
    case CompositeOp::SourceIn: fa = ab; fb = 0; return;
    case CompositeOp::DestinationIn: fa = 0; fb = as; return;
    case CompositeOp::SourceOut: fa = 1 - ab; fb = 0; return;
    case CompositeOp::DestinationOut: fa = 0; fb = 1 - as; return;
    case CompositeOp::SourceAtop: fa = ab; fb = 1 - as; return;
    case CompositeOp::DestinationAtop: fa = 1 - ab; fb = as; return;
    case CompositeOp::Xor: fa = 1 - ab; fb = 1 - as; return;
    default: fa = 1; fb = 1; return;  // lighter (plus-lighter): clamped afterwards
  }
}

// 10.1: separable blend functions B(Cb, Cs).
double separable(CompositeOp op, double cb, double cs) {
  auto multiply = [](double b, double s) { return b * s; };
  auto screen = [](double b, double s) { return b + s - b * s; };
  auto hard_light = [&](double b, double s) { return s <= 0.5 ? multiply(b, 2 * s) : screen(b, 2 * s - 1); };
  switch (op) {
    case CompositeOp::Multiply: return multiply(cb, cs);
    case CompositeOp::Screen: return screen(cb, cs);
    case CompositeOp::Overlay: return hard_light(cs, cb);
    case CompositeOp::Darken: return std::min(cb, cs);
    case CompositeOp::Lighten: return std::max(cb, cs);
    case CompositeOp::ColorDodge:
      if (cb == 0) return 0;
      if (cs == 1) return 1;
      return std::min(1.0, cb / (1 - cs));
    case CompositeOp::ColorBurn:
      if (cb == 1) return 1;
      if (cs == 0) return 0;
      return 1 - std::min(1.0, (1 - cb) / cs);
    case CompositeOp::HardLight: return hard_light(cb, cs);
    case CompositeOp::SoftLight: {
      if (cs <= 0.5) return cb - (1 - 2 * cs) * cb * (1 - cb);
      const double d = cb <= 0.25 ? ((16 * cb - 12) * cb + 4) * cb : std::sqrt(cb);
      return cb + (2 * cs - 1) * (d - cb);
    }
    case CompositeOp::Difference: return std::abs(cb - cs);
    default: return cb + cs - 2 * cb * cs;  // exclusion
  }
}

// 10.2: the non-separable helpers, written as the spec's pseudo-code.
using Rgb = std::array<double, 3>;
double lum(const Rgb& c) { return 0.3 * c[0] + 0.59 * c[1] + 0.11 * c[2]; }
Rgb clip_color(Rgb c) {
  const double l = lum(c);
  const double n = std::min({c[0], c[1], c[2]}), x = std::max({c[0], c[1], c[2]});
  if (n < 0) {
    for (double& v : c) v = l + (v - l) * l / (l - n);
  }
  if (x > 1) {
    for (double& v : c) v = l + (v - l) * (1 - l) / (x - l);
  }
  return c;
}
Rgb set_lum(Rgb c, double l) {
  const double d = l - lum(c);
  for (double& v : c) v += d;
  return clip_color(c);
}
double sat(const Rgb& c) { return std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]}); }
Rgb set_sat(Rgb c, double s) {
  // Sort channel indices by value: max, mid, min.
  int idx[3] = {0, 1, 2};
  std::sort(idx, idx + 3, [&](int a, int b) { return c[static_cast<std::size_t>(a)] > c[static_cast<std::size_t>(b)]; });
  double& cmax = c[static_cast<std::size_t>(idx[0])];
  double& cmid = c[static_cast<std::size_t>(idx[1])];
  double& cmin = c[static_cast<std::size_t>(idx[2])];
  if (cmax > cmin) {
    cmid = (cmid - cmin) * s / (cmax - cmin);
    cmax = s;
  } else {
    cmid = cmax = 0;
  }
  cmin = 0;
  return c;
}
Rgb non_separable(CompositeOp op, const Rgb& cb, const Rgb& cs) {
  switch (op) {
    case CompositeOp::Hue: return set_lum(set_sat(cs, sat(cb)), lum(cb));
    case CompositeOp::Saturation: return set_lum(set_sat(cb, sat(cs)), lum(cb));
    case CompositeOp::Color: return set_lum(cs, lum(cb));
    default: return set_lum(cb, lum(cs));  // luminosity
  }
}

bool is_blend(CompositeOp op) { return static_cast<int>(op) >= static_cast<int>(CompositeOp::Multiply); }

}  // namespace

Rgba reference_composite(CompositeOp op, const Rgba& s, const Rgba& d) {
  const double as = s[3], ab = d[3];
  Rgba r{};
  if (!is_blend(op)) {
    double fa, fb;
    factors(op, as, ab, fa, fb);
    for (int c = 0; c < 4; ++c) r[static_cast<std::size_t>(c)] = std::min(1.0, s[static_cast<std::size_t>(c)] * fa + d[static_cast<std::size_t>(c)] * fb);
    return r;
  }
  // Straight colours; a transparent layer's colour does not matter (its weight is 0).
  Rgb cs{}, cb{};
  for (std::size_t c = 0; c < 3; ++c) {
    cs[c] = as > 0 ? std::min(1.0, s[c] / as) : 0;
    cb[c] = ab > 0 ? std::min(1.0, d[c] / ab) : 0;
  }
  Rgb b{};
  if (op < CompositeOp::Hue) {
    for (std::size_t c = 0; c < 3; ++c) b[c] = separable(op, cb[c], cs[c]);
  } else {
    b = non_separable(op, cb, cs);
  }
  // Cs' = (1 - ab) Cs + ab B(Cb, Cs), then source-over: co = as Cs' + (1 - as) cb (premultiplied).
  for (std::size_t c = 0; c < 3; ++c) {
    const double blended = (1 - ab) * cs[c] + ab * b[c];
    r[c] = as * blended + (1 - as) * d[c];
  }
  r[3] = as + ab * (1 - as);
  return r;
}

Rgba reference_draw(CompositeOp op, const Rgba& s, const Rgba& d, double coverage, double clip) {
  Rgba scaled;
  for (std::size_t c = 0; c < 4; ++c) scaled[c] = s[c] * coverage;
  const Rgba r = reference_composite(op, scaled, d);
  Rgba out;
  for (std::size_t c = 0; c < 4; ++c) out[c] = d[c] + (r[c] - d[c]) * clip;
  return out;
}

Rgba reference_gradient_color(const Paint& paint, double t) {
  const auto& stops = paint.stops();
  if (stops.empty()) return {0, 0, 0, 0};
  // Extend (conic: t is already in [0, 1)).
  switch (paint.extend_x()) {
    case Extend::Repeat: t -= std::floor(t); break;
    case Extend::Reflect: {
      const double m = t - 2 * std::floor(t / 2);  // [0, 2)
      t = m <= 1 ? m : 2 - m;
      break;
    }
    default: t = clamp01(t); break;
  }
  // HTML canvas: straight RGBA interpolated between the stops around t; before the first stop its colour,
  // after the last its colour; equal offsets make a step (the later stop wins from its offset on).
  Color c;
  if (t < stops.front().offset) {
    c = stops.front().color;
  } else if (t >= stops.back().offset) {
    c = stops.back().color;
  } else {
    std::size_t i = 0;
    while (!(stops[i].offset <= t && t < stops[i + 1].offset)) ++i;
    const double u = (t - stops[i].offset) / (stops[i + 1].offset - stops[i].offset);
    const Color& a = stops[i].color;
    const Color& b = stops[i + 1].color;
    c = {static_cast<float>(a.r + (b.r - a.r) * u), static_cast<float>(a.g + (b.g - a.g) * u),
         static_cast<float>(a.b + (b.b - a.b) * u), static_cast<float>(a.a + (b.a - a.a) * u)};
  }
  const double alpha = clamp01(c.a) * paint.opacity();
  return {clamp01(c.r) * alpha, clamp01(c.g) * alpha, clamp01(c.b) * alpha, alpha};
}

namespace {

// Texel index along one axis under an extend mode; -1 for "transparent" (Extend::None outside the tile).
long texel_index(long i, long size, Extend extend) {
  switch (extend) {
    case Extend::None: return i >= 0 && i < size ? i : -1;
    case Extend::Pad: return std::min(size - 1, std::max(0L, i));
    case Extend::Repeat: return ((i % size) + size) % size;
    case Extend::Reflect: {
      const long period = 2 * size;
      const long m = ((i % period) + period) % period;
      return m < size ? m : period - 1 - m;
    }
  }
  return -1;
}

Rgba texel(const Paint& paint, long i, long j) {
  const bool wide = paint.image16() != nullptr;
  const long w = wide ? paint.image16()->width : paint.image8()->width;
  const long h = wide ? paint.image16()->height : paint.image8()->height;
  const long x = texel_index(i, w, paint.extend_x()), y = texel_index(j, h, paint.extend_y());
  if (x < 0 || y < 0) return {0, 0, 0, 0};
  Rgba r;
  for (std::size_t c = 0; c < 4; ++c) {
    r[c] = wide ? paint.image16()->pixel(static_cast<int>(x), static_cast<int>(y))[c] / 65535.0
                : paint.image8()->pixel(static_cast<int>(x), static_cast<int>(y))[c] / 255.0;
  }
  return r;
}

// Catmull-Rom cubic (B = 0, C = 1/2), the interpolating cubic.
double catmull_rom(double x) {
  x = std::abs(x);
  if (x < 1) return (1.5 * x - 2.5) * x * x + 1;
  if (x < 2) return ((-0.5 * x + 2.5) * x - 4) * x + 2;
  return 0;
}

}  // namespace

Rgba reference_pattern(const Paint& paint, const Affine& user_to_device, double x, double y) {
  const Affine m = user_to_device * paint.transform();
  if (!m.invertible() || (!paint.image8() && !paint.image16())) return {0, 0, 0, 0};
  const Point p = m.inverse().apply({x, y});
  Rgba out{0, 0, 0, 0};
  if (paint.filter() == ImageFilter::Nearest) {
    out = texel(paint, static_cast<long>(std::floor(p.x)), static_cast<long>(std::floor(p.y)));
  } else {
    // Texel centres are at i + 0.5: sample relative to them.
    const double u = p.x - 0.5, v = p.y - 0.5;
    const long i0 = static_cast<long>(std::floor(u)), j0 = static_cast<long>(std::floor(v));
    const double fx = u - static_cast<double>(i0), fy = v - static_cast<double>(j0);
    const bool cubic = paint.filter() == ImageFilter::Bicubic;
    const long lo = cubic ? -1 : 0, hi = cubic ? 2 : 1;
    for (long j = lo; j <= hi; ++j) {
      const double wy = cubic ? catmull_rom(static_cast<double>(j) - fy) : (j == 0 ? 1 - fy : fy);
      for (long i = lo; i <= hi; ++i) {
        const double wx = cubic ? catmull_rom(static_cast<double>(i) - fx) : (i == 0 ? 1 - fx : fx);
        const Rgba t = texel(paint, i0 + i, j0 + j);
        for (std::size_t c = 0; c < 4; ++c) out[c] += wx * wy * t[c];
      }
    }
    out[3] = clamp01(out[3]);
    for (std::size_t c = 0; c < 3; ++c) out[c] = std::min(out[3], std::max(0.0, out[c]));
  }
  const double o = paint.opacity();
  for (double& c : out) c *= o;
  return out;
}

bool reference_gradient_t(const Paint& paint, const Affine& user_to_device, double x, double y, double& t) {
  const Affine m = user_to_device * paint.transform();
  if (!m.invertible()) return false;
  const Point p = m.inverse().apply({x, y});
  switch (paint.kind()) {
    case Paint::Kind::Linear: {
      const Point d = paint.p1() - paint.p0();
      const double len2 = dot(d, d);
      if (len2 == 0) return false;
      t = dot(p - paint.p0(), d) / len2;
      return true;
    }
    case Paint::Kind::Radial: {
      const Point c0 = paint.p0(), c1 = paint.p1();
      const double r0 = paint.r0(), r1 = paint.r1();
      if (c0 == c1 && r0 == r1) return false;
      // |p - c(w)| = r(w) with c(w) = c0 + w (c1 - c0), r(w) = r0 + w (r1 - r0): a w^2 - 2 b w + c = 0.
      const Point cd = c1 - c0, pd = p - c0;
      const double dr = r1 - r0;
      const double a = dot(cd, cd) - dr * dr, b = dot(pd, cd) + r0 * dr, c = dot(pd, pd) - r0 * r0;
      bool found = false;
      auto consider = [&](double w) {
        if (std::isfinite(w) && r0 + w * dr >= 0 && (!found || w > t)) {
          t = w;
          found = true;
        }
      };
      if (a == 0) {
        if (b != 0) consider(c / (2 * b));
      } else {
        const double disc = b * b - a * c;
        if (disc >= 0) {
          const double sq = std::sqrt(disc);
          consider((b + sq) / a);
          consider((b - sq) / a);
        }
      }
      return found;
    }
    case Paint::Kind::Conic: {
      const Point d = p - paint.p0();
      double turn = (std::atan2(d.y, d.x) - paint.angle()) / (2 * M_PI);
      t = turn - std::floor(turn);
      return true;
    }
    default: return false;
  }
}

Rgba reference_paint(const Paint& paint, const Affine& user_to_device, double x, double y) {
  if (paint.kind() == Paint::Kind::Solid) {
    const Color c = paint.color();
    const double a = clamp01(c.a) * paint.opacity();
    return {clamp01(c.r) * a, clamp01(c.g) * a, clamp01(c.b) * a, a};
  }
  if (paint.kind() == Paint::Kind::Pattern) return reference_pattern(paint, user_to_device, x, y);
  double t;
  if (!reference_gradient_t(paint, user_to_device, x, y, t)) return {0, 0, 0, 0};
  return reference_gradient_color(paint, t);
}

}  // namespace vraster::test
