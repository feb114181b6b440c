// Lighting (Blinn-Phong), names of the shading and depth modes, the depth buffer and 2.5D depth order.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "vraster/error.hpp"
#include "vraster/mesh.hpp"

namespace vraster {

namespace {

Vec3 normalized(Vec3 v) {
  const float len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (!(len > 0) || !std::isfinite(len)) return Vec3{0, 0, -1};  // no direction: faces the viewer
  return Vec3{v.x / len, v.y / len, v.z / len};
}
float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

}  // namespace

Color shade(const Lighting& lighting, Color color, Vec3 normal, Vec3 eye) {
  if (!lighting.enabled) return color;
  const Vec3 n = normalized(normal), l = normalized(lighting.to_light);
  const Vec3 v = lighting.perspective_view ? normalized(Vec3{-eye.x, -eye.y, -eye.z}) : Vec3{0, 0, -1};
  const Vec3 h = normalized(Vec3{l.x + v.x, l.y + v.y, l.z + v.z});
  const float diffuse = lighting.diffuse * std::max(0.f, dot(n, l));
  const float n_dot_h = std::max(0.f, dot(n, h));
  // No highlight on the side turned away from the light.
  const float specular = dot(n, l) > 0 ? lighting.specular * std::pow(n_dot_h, lighting.shininess) : 0.f;
  const float k = lighting.ambient + diffuse;
  auto channel = [&](float c) { return std::clamp(k * c + specular, 0.f, 1.f); };
  return Color{channel(color.r), channel(color.g), channel(color.b), color.a};
}

bool parse_shading(std::string_view name, Shading& out) {
  if (name == "flat") return out = Shading::Flat, true;
  if (name == "gouraud") return out = Shading::Gouraud, true;
  if (name == "phong") return out = Shading::Phong, true;
  return false;
}

bool parse_depth_mode(std::string_view name, DepthMode& out) {
  if (name == "none") return out = DepthMode::None, true;
  if (name == "zbuffer") return out = DepthMode::ZBuffer, true;
  if (name == "painter") return out = DepthMode::Painter, true;
  return false;
}

DepthBuffer::DepthBuffer(int width, int height) : width_(width), height_(height) {
  check_image_size(width, height);
  values_.assign(static_cast<std::size_t>(width) * height, kFar);
}

void DepthBuffer::clear(float value) { std::fill(values_.begin(), values_.end(), value); }

std::vector<std::size_t> depth_order(std::span<const double> z) {
  std::vector<std::size_t> order(z.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t i) { return std::isfinite(z[i]) ? z[i] : std::numeric_limits<double>::infinity(); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return key(i) > key(j); });
  return order;
}

}  // namespace vraster
