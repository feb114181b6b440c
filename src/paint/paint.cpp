// Paint: the description of a paint source (setters, validity, opacity tests). Shading is in shade.cpp.
#include "vraster/paint.hpp"

#include <algorithm>
#include <cmath>

namespace vraster {
namespace {

bool finite_color(const Color& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && std::isfinite(c.a);
}

bool is_gradient(Paint::Kind kind) {
  return kind == Paint::Kind::Linear || kind == Paint::Kind::Radial || kind == Paint::Kind::Conic;
}

}  // namespace

Paint::Paint() = default;

Paint Paint::solid(Color color) {
  Paint p;
  p.color_ = color;
  return p;
}

Paint Paint::linear(Point p0, Point p1) {
  Paint p;
  p.kind_ = Kind::Linear;
  p.p0_ = p0;
  p.p1_ = p1;
  return p;
}

Paint Paint::radial(Point c0, double r0, Point c1, double r1) {
  Paint p;
  p.kind_ = Kind::Radial;
  p.p0_ = c0;
  p.p1_ = c1;
  p.r0_ = r0;
  p.r1_ = r1;
  return p;
}

Paint Paint::conic(double start_angle, Point center) {
  Paint p;
  p.kind_ = Kind::Conic;
  p.p0_ = center;
  p.angle_ = start_angle;
  return p;
}

Paint Paint::pattern(std::shared_ptr<const Image> tile) {
  Paint p;
  p.kind_ = Kind::Pattern;
  p.image8_ = std::move(tile);
  p.extend_x_ = p.extend_y_ = Extend::Repeat;  // the canvas default ("repeat")
  return p;
}

Paint Paint::pattern(std::shared_ptr<const Image16> tile) {
  Paint p;
  p.kind_ = Kind::Pattern;
  p.image16_ = std::move(tile);
  p.extend_x_ = p.extend_y_ = Extend::Repeat;
  return p;
}

bool Paint::add_stop(double offset, Color color) {
  if (!is_gradient(kind_) || !std::isfinite(offset) || offset < 0 || offset > 1 || !finite_color(color)) return false;
  // After every stop with offset <= this one: equal offsets keep the order they were added in.
  const auto at = std::upper_bound(stops_.begin(), stops_.end(), offset,
                                   [](double o, const ColorStop& s) { return o < s.offset; });
  stops_.insert(at, ColorStop{offset, color});
  return true;
}

void Paint::set_extend(Extend both) { set_extend(both, both); }

void Paint::set_extend(Extend x, Extend y) {
  // Gradients have no "none": it means pad for them.
  if (kind_ != Kind::Pattern) {
    if (x == Extend::None) x = Extend::Pad;
    if (y == Extend::None) y = Extend::Pad;
  }
  extend_x_ = x;
  extend_y_ = y;
}

void Paint::set_filter(ImageFilter filter) { filter_ = filter; }
void Paint::set_transform(const Affine& paint_to_user) { transform_ = paint_to_user; }
void Paint::set_dither(bool on) { dither_ = on; }
void Paint::set_opacity(float opacity) { opacity_ = std::isfinite(opacity) ? std::clamp(opacity, 0.f, 1.f) : 0.f; }

bool Paint::is_invisible() const {
  if (!(opacity_ > 0)) return true;
  if (kind_ == Kind::Solid) return !(color_.a > 0);
  if (!transform_.is_finite() || !transform_.invertible()) return true;
  switch (kind_) {
    case Kind::Linear:
      if (!is_finite(p0_) || !is_finite(p1_) || p0_ == p1_) return true;  // canvas: paints nothing
      break;
    case Kind::Radial:
      if (!is_finite(p0_) || !is_finite(p1_) || !std::isfinite(r0_) || !std::isfinite(r1_) || r0_ < 0 || r1_ < 0)
        return true;
      if (p0_ == p1_ && r0_ == r1_) return true;  // canvas: paints nothing
      break;
    case Kind::Conic:
      if (!is_finite(p0_) || !std::isfinite(angle_)) return true;
      break;
    case Kind::Pattern: {
      if (image8_) return image8_->width <= 0 || image8_->height <= 0;
      if (image16_) return image16_->width <= 0 || image16_->height <= 0;
      return true;
    }
    case Kind::Solid: break;
  }
  for (const ColorStop& s : stops_) {
    if (s.color.a > 0) return false;
  }
  return true;  // no stops, or all transparent
}

bool Paint::is_opaque() const {
  if (is_invisible() || opacity_ < 1) return false;
  switch (kind_) {
    case Kind::Solid: return color_.a >= 1;
    case Kind::Pattern: return false;  // would need a scan of the image; the blend loops store opaque pixels anyway
    case Kind::Radial: {
      // Every point of the plane gets a colour only when one circle lies strictly inside the other.
      const double d = length(p1_ - p0_);
      if (!(d + std::min(r0_, r1_) < std::max(r0_, r1_))) return false;
      break;
    }
    case Kind::Linear:
    case Kind::Conic: break;
  }
  for (const ColorStop& s : stops_) {
    if (!(s.color.a >= 1)) return false;
  }
  return !stops_.empty();
}

}  // namespace vraster
