// The mesh renderer (include/vraster/mesh.hpp has the data flow).
//
//   1. order the triangles (as given, farthest first for the painter's algorithm, or nearest first when the planner
//      asks for front to back: hidden fragments then fail the depth test before they are shaded)
//   2. prepare each triangle: reject the invalid, cull, barycentric planes in double, vertex colours (lit once per
//      triangle for flat shading, per vertex for Gouraud, kept unlit for Phong)
//   3. aliased: the covered pixel centres (triangle_setup.hpp) span by span -> depth test -> shade -> blend_row
//      antialiased: [depth pre-pass] -> each triangle's analytic coverage x its colour summed into a mesh buffer
//      -> the buffer composited row by row with blend_row
#include <algorithm>
#include <cmath>
#include <numeric>

#include "mesh/triangle_setup.hpp"
#include "vraster/composite.hpp"
#include "vraster/error.hpp"
#include "vraster/flatten.hpp"
#include "vraster/mesh.hpp"
#include "vraster/raster.hpp"

namespace vraster {

using mesh_detail::cover_triangle;

void rasterize_triangle(Point a, Point b, Point c, int width, int height,
                        const std::function<void(int, int, int)>& span) {
  const Point v[3] = {a, b, c};
  cover_triangle(v, width, height, false, span);
}

void rasterize_triangle_bbox(Point a, Point b, Point c, int width, int height,
                             const std::function<void(int, int, int)>& span) {
  const Point v[3] = {a, b, c};
  cover_triangle(v, width, height, true, span);
}

namespace {

constexpr std::uint32_t kNoOwner = 0xFFFFFFFFu;

// One triangle ready to shade: positions in view pixels, barycentric planes, depths, colours.
struct Prepared {
  Point p[3];
  double z[3];
  double q[3];           // 1 / w
  bool perspective = false;
  // lambda_1 = l1x * dx + l1y * dy, lambda_2 likewise, lambda_0 = 1 - lambda_1 - lambda_2, with (dx, dy) = (x, y) - p0
  double l1x, l1y, l2x, l2y;
  double depth_bias = 0;
  double depth_slope = 0;  // largest depth change per pixel along x or y
  double dzdx = 0;         // depth change per pixel along x
  bool linear_color = false;  // colours affine on screen (not Phong, not perspective): dcdx is their step along x
  float dcdx[4] = {0, 0, 0, 0};
  Color color[3];          // straight; flat: all three the same
  Vec3 n[3], eye[3];       // Phong only

  void weights(double x, double y, double lambda[3]) const {
    const double dx = x - p[0].x, dy = y - p[0].y;
    lambda[1] = l1x * dx + l1y * dy;
    lambda[2] = l2x * dx + l2y * dy;
    lambda[0] = 1 - lambda[1] - lambda[2];
  }
  double depth_at(const double lambda[3]) const {
    return lambda[0] * z[0] + lambda[1] * z[1] + lambda[2] * z[2] + depth_bias;
  }
  // Perspective-correct attribute weights (the seeds' f = sum(lambda_i f_i / w_i) / sum(lambda_i / w_i)).
  void attribute_weights(const double lambda[3], double out[3]) const {
    if (!perspective) {
      std::copy(lambda, lambda + 3, out);
      return;
    }
    const double s0 = lambda[0] * q[0], s1 = lambda[1] * q[1], s2 = lambda[2] * q[2], sum = s0 + s1 + s2;
    if (!(sum != 0)) {
      std::copy(lambda, lambda + 3, out);
      return;
    }
    out[0] = s0 / sum, out[1] = s1 / sum, out[2] = s2 / sum;
  }
};

bool finite_vertex(const MeshVertex& v) {
  return std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.depth) &&
         std::isfinite(v.w) && v.w > 0 && std::isfinite(v.color.r) && std::isfinite(v.color.g) &&
         std::isfinite(v.color.b) && std::isfinite(v.color.a) && std::isfinite(v.normal.x) &&
         std::isfinite(v.normal.y) && std::isfinite(v.normal.z) && std::isfinite(v.eye.x) && std::isfinite(v.eye.y) &&
         std::isfinite(v.eye.z);
}

Vec3 mean(Vec3 a, Vec3 b, Vec3 c) { return Vec3{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3, (a.z + b.z + c.z) / 3}; }

// Flat shading's normal: the plane's, from the eye-space positions when they span a triangle, turned to the side of
// the vertex normals; else the mean vertex normal.
Vec3 face_normal(const MeshVertex& a, const MeshVertex& b, const MeshVertex& c) {
  const Vec3 m = mean(a.normal, b.normal, c.normal);
  const double ux = b.eye.x - a.eye.x, uy = b.eye.y - a.eye.y, uz = b.eye.z - a.eye.z;
  const double vx = c.eye.x - a.eye.x, vy = c.eye.y - a.eye.y, vz = c.eye.z - a.eye.z;
  double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
  const double uu = ux * ux + uy * uy + uz * uz, vv = vx * vx + vy * vy + vz * vz;
  if (!(len > 1e-9 * std::sqrt(uu * vv))) return m;  // no plane (2D meshes have all eye positions at 0)
  if (nx * m.x + ny * m.y + nz * m.z < 0) nx = -nx, ny = -ny, nz = -nz;
  return Vec3{static_cast<float>(nx / len), static_cast<float>(ny / len), static_cast<float>(nz / len)};
}

// Step 2: false when the triangle draws nothing.
bool prepare(const Mesh& mesh, const std::array<std::uint32_t, 3>& tri, const MeshOptions& o, Point origin,
             Prepared& t) {
  const MeshVertex* v[3];
  for (int i = 0; i < 3; ++i) {
    if (tri[static_cast<std::size_t>(i)] >= mesh.vertices.size()) return false;
    v[i] = &mesh.vertices[tri[static_cast<std::size_t>(i)]];
    if (!finite_vertex(*v[i])) return false;
    t.p[i] = Point{v[i]->position.x - origin.x, v[i]->position.y - origin.y};
    if (!(std::abs(t.p[i].x) <= mesh_detail::kMeshCoordLimit && std::abs(t.p[i].y) <= mesh_detail::kMeshCoordLimit)) {
      return false;
    }
    t.z[i] = v[i]->depth;
    t.q[i] = 1 / v[i]->w;
  }
  const double ax = t.p[1].x - t.p[0].x, ay = t.p[1].y - t.p[0].y;
  const double bx = t.p[2].x - t.p[0].x, by = t.p[2].y - t.p[0].y;
  const double det = ax * by - ay * bx;  // > 0: clockwise on screen (y down)
  if (!(det != 0) || !std::isfinite(det)) return false;
  if (o.cull_back_faces && det > 0) return false;
  t.l1x = by / det, t.l1y = -bx / det;
  t.l2x = -ay / det, t.l2y = ax / det;
  t.perspective = !(v[0]->w == v[1]->w && v[1]->w == v[2]->w);
  const double dzdx = (t.z[1] - t.z[0]) * t.l1x + (t.z[2] - t.z[0]) * t.l2x;
  const double dzdy = (t.z[1] - t.z[0]) * t.l1y + (t.z[2] - t.z[0]) * t.l2y;
  t.depth_slope = std::max(std::abs(dzdx), std::abs(dzdy));
  t.depth_bias = o.depth_offset + o.depth_slope_offset * t.depth_slope;

  const float opacity = std::clamp(std::isfinite(o.opacity) ? o.opacity : 0.f, 0.f, 1.f);
  switch (o.shading) {
    case Shading::Flat: {
      const Color c{(v[0]->color.r + v[1]->color.r + v[2]->color.r) / 3,
                    (v[0]->color.g + v[1]->color.g + v[2]->color.g) / 3,
                    (v[0]->color.b + v[1]->color.b + v[2]->color.b) / 3,
                    (v[0]->color.a + v[1]->color.a + v[2]->color.a) / 3};
      const Color lit = shade(o.lighting, c, face_normal(*v[0], *v[1], *v[2]), mean(v[0]->eye, v[1]->eye, v[2]->eye));
      for (Color& out : t.color) out = lit;
      break;
    }
    case Shading::Gouraud:
      for (int i = 0; i < 3; ++i) t.color[i] = shade(o.lighting, v[i]->color, v[i]->normal, v[i]->eye);
      break;
    case Shading::Phong:
      for (int i = 0; i < 3; ++i) {
        t.color[i] = v[i]->color;
        t.n[i] = v[i]->normal;
        t.eye[i] = v[i]->eye;
      }
      break;
  }
  for (Color& c : t.color) c.a = std::clamp(c.a, 0.f, 1.f) * opacity;
  t.dzdx = dzdx;
  t.linear_color = !t.perspective && o.shading != Shading::Phong;
  if (t.linear_color) {
    auto step = [&](float Color::*ch) {
      return static_cast<float>(t.l1x * (t.color[1].*ch - t.color[0].*ch) + t.l2x * (t.color[2].*ch - t.color[0].*ch));
    };
    t.dcdx[0] = step(&Color::r), t.dcdx[1] = step(&Color::g), t.dcdx[2] = step(&Color::b), t.dcdx[3] = step(&Color::a);
  }
  return true;
}

// The straight colour of a fragment with attribute weights w.
Color fragment_color(const Prepared& t, const MeshOptions& o, const double w[3]) {
  auto mix = [&](float Color::*ch) {
    return static_cast<float>(w[0] * (t.color[0].*ch) + w[1] * (t.color[1].*ch) + w[2] * (t.color[2].*ch));
  };
  Color c{mix(&Color::r), mix(&Color::g), mix(&Color::b), mix(&Color::a)};
  if (o.shading == Shading::Phong) {
    auto mix3 = [&](const Vec3* v) {
      return Vec3{static_cast<float>(w[0] * v[0].x + w[1] * v[1].x + w[2] * v[2].x),
                  static_cast<float>(w[0] * v[0].y + w[1] * v[1].y + w[2] * v[2].y),
                  static_cast<float>(w[0] * v[0].z + w[1] * v[1].z + w[2] * v[2].z)};
    };
    c = shade(o.lighting, c, mix3(t.n), mix3(t.eye));
  }
  return c;
}

template <class T>
void store_premultiplied(Color c, float coverage, T* out) {
  constexpr float kMax = static_cast<float>(BasicImage<T>::kMax);
  const float a = std::clamp(c.a, 0.f, 1.f) * coverage;
  out[0] = static_cast<T>(std::clamp(c.r, 0.f, 1.f) * a * kMax + 0.5f);
  out[1] = static_cast<T>(std::clamp(c.g, 0.f, 1.f) * a * kMax + 0.5f);
  out[2] = static_cast<T>(std::clamp(c.b, 0.f, 1.f) * a * kMax + 0.5f);
  out[3] = static_cast<T>(a * kMax + 0.5f);
}

}  // namespace

bool mesh_is_opaque(const Mesh& mesh, const MeshOptions& options) {
  if (!(options.opacity >= 1)) return false;
  return std::all_of(mesh.vertices.begin(), mesh.vertices.end(), [](const MeshVertex& v) { return v.color.a >= 1; });
}

struct MeshRenderer::Buffers {
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> owner;  // front to back: the triangle whose depth each pixel holds (kNoOwner: none)
  std::vector<double> keys;
  DepthBuffer own_depth;
  std::vector<float> coverage;
  std::vector<std::uint8_t> src8;
  std::vector<std::uint16_t> src16;
  // Antialiased meshes: premultiplied colour sums and coverage sums over the mesh's box, and its own depth.
  std::vector<float> sum_rgba, sum_coverage, mesh_depth;
  Polylines lines;
  Rasterizer rasterizer;

  template <class T>
  std::vector<T>& src() {
    if constexpr (sizeof(T) == 1) {
      return src8;
    } else {
      return src16;
    }
  }
};

MeshRenderer::MeshRenderer() : buffers_(std::make_unique<Buffers>()) {}
MeshRenderer::~MeshRenderer() = default;
MeshRenderer::MeshRenderer(MeshRenderer&&) noexcept = default;
MeshRenderer& MeshRenderer::operator=(MeshRenderer&&) noexcept = default;

namespace {

// Antialiased accumulation of one triangle: coverage from the rasterizer, colour and depth at each pixel centre.
class AccumulateSink final : public CoverageSink {
 public:
  AccumulateSink(const Prepared& t, const MeshOptions& o, int box_x0, int box_y0, int box_w, float* rgba,
                 float* coverage, const float* depth, MeshStats& stats)
      : t_(t), o_(o), bx_(box_x0), by_(box_y0), bw_(box_w), rgba_(rgba), cov_(coverage), depth_(depth),
        stats_(stats) {}

  void span(int y, int x0, int x1, float coverage) override {
    for (int x = x0; x < x1; ++x) add(y, x, coverage);
  }
  void row(int y, int x0, int x1, const float* coverage) override {
    for (int x = x0; x < x1; ++x) {
      if (coverage[x - x0] > 0) add(y, x, coverage[x - x0]);
    }
  }

 private:
  void add(int y, int x, float coverage) {
    const std::size_t i = static_cast<std::size_t>(y - by_) * bw_ + static_cast<std::size_t>(x - bx_);
    double lambda[3];
    t_.weights(x + 0.5, y + 0.5, lambda);
    ++stats_.fragments;
    if (depth_ != nullptr && std::isfinite(depth_[i])) {
      // The plane's depth at this centre against the nearest surface there; one pixel's worth of this triangle's
      // slope is allowed, so the neighbour of the triangle that owns the centre still fills its share.
      const double z = t_.depth_at(lambda);
      if (!(z <= depth_[i] + t_.depth_slope + 1e-9 * std::abs(depth_[i]))) {
        ++stats_.depth_rejected;
        return;
      }
    }
    ++stats_.fragments_shaded;
    // Colours from weights clamped to the triangle, so centres outside it do not extrapolate.
    double sum = 0;
    for (double& l : lambda) sum += (l = std::max(0.0, l));
    for (double& l : lambda) l /= sum;
    double w[3];
    t_.attribute_weights(lambda, w);
    const Color c = fragment_color(t_, o_, w);
    const float a = std::clamp(c.a, 0.f, 1.f) * coverage;
    rgba_[4 * i + 0] += std::clamp(c.r, 0.f, 1.f) * a;
    rgba_[4 * i + 1] += std::clamp(c.g, 0.f, 1.f) * a;
    rgba_[4 * i + 2] += std::clamp(c.b, 0.f, 1.f) * a;
    rgba_[4 * i + 3] += a;
    cov_[i] += coverage;
  }

  const Prepared& t_;
  const MeshOptions& o_;
  int bx_, by_, bw_;
  float* rgba_;
  float* cov_;
  const float* depth_;
  MeshStats& stats_;
};

}  // namespace

template <class T>
void MeshRenderer::draw(ImageView<T> target, const Mesh& mesh, const MeshOptions& options, DepthBuffer* depth) {
  stats_ = MeshStats{};
  Buffers& b = *buffers_;
  const int width = target.width, height = target.height;
  if (width <= 0 || height <= 0 || mesh.triangles.empty()) return;
  const bool use_depth = options.depth == DepthMode::ZBuffer;
  if (use_depth) {
    if (depth == nullptr) {
      if (b.own_depth.width() != width || b.own_depth.height() != height) b.own_depth = DepthBuffer(width, height);
      b.own_depth.clear();
      depth = &b.own_depth;
    } else if (depth->width() != width || depth->height() != height) {
      throw Error("mesh: the depth buffer is " + std::to_string(depth->width()) + "x" +
                  std::to_string(depth->height()) + ", the target " + std::to_string(width) + "x" +
                  std::to_string(height));
    }
  }
  const Point origin{static_cast<double>(target.x0), static_cast<double>(target.y0)};

  // 1. Order.
  b.order.resize(mesh.triangles.size());
  std::iota(b.order.begin(), b.order.end(), 0u);
  const bool front_to_back = options.front_to_back && use_depth && options.write_depth && !options.antialias &&
                             mesh.triangles.size() < kNoOwner && mesh_is_opaque(mesh, options);
  stats_.drew_front_to_back = front_to_back;
  if (front_to_back) {
    // Nearest vertex first. Only the amount of shading depends on this order: ties are settled by index below.
    b.keys.resize(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::uint32_t k : mesh.triangles[i]) {
        if (k < mesh.vertices.size()) nearest = std::min(nearest, mesh.vertices[k].depth);
      }
      b.keys[i] = std::isfinite(nearest) ? nearest : std::numeric_limits<double>::infinity();
    }
    std::stable_sort(b.order.begin(), b.order.end(),
                     [&](std::uint32_t i, std::uint32_t j) { return b.keys[i] < b.keys[j]; });
    b.owner.assign(static_cast<std::size_t>(width) * height, kNoOwner);
  } else if (options.depth == DepthMode::Painter) {
    b.keys.resize(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      double sum = 0;
      for (std::uint32_t k : mesh.triangles[i]) {
        sum += k < mesh.vertices.size() ? mesh.vertices[k].depth : 0;
      }
      b.keys[i] = std::isfinite(sum) ? sum : 0;
    }
    std::stable_sort(b.order.begin(), b.order.end(),
                     [&](std::uint32_t i, std::uint32_t j) { return b.keys[i] > b.keys[j]; });
  }

  std::vector<T>& src = b.template src<T>();
  if (src.size() < static_cast<std::size_t>(width) * 4) src.resize(static_cast<std::size_t>(width) * 4);
  if (b.coverage.size() < static_cast<std::size_t>(width)) b.coverage.resize(static_cast<std::size_t>(width));
  Prepared t;

  if (!options.antialias) {
    // 3. Aliased: centres by edge functions, then depth, shading and compositing one span at a time.
    for (const std::uint32_t index : b.order) {
      if (!prepare(mesh, mesh.triangles[index], options, origin, t)) {
        ++stats_.triangles_skipped;
        continue;
      }
      bool any = false;
      cover_triangle(t.p, width, height, false, [&](int y, int x0, int x1) {
        any = true;
        float* zrow = use_depth ? depth->row(y) : nullptr;
        std::uint32_t* owners = front_to_back ? b.owner.data() + static_cast<std::size_t>(y) * width : nullptr;
        T* s = src.data();
        bool all_pass = true;
        // Depth, and colours when they are affine on screen, step along the span from its first centre.
        double start[3];
        t.weights(x0 + 0.5, y + 0.5, start);
        const double z_start = t.depth_at(start);
        const Color c_start = t.linear_color ? fragment_color(t, options, start) : Color{};
        for (int x = x0; x < x1; ++x, s += 4) {
          const int i = x - x0;
          float& cov = b.coverage[static_cast<std::size_t>(i)];
          cov = 1;
          if (zrow != nullptr) {
            const float z = static_cast<float>(z_start + i * t.dzdx);
            // Drawn in the given order, the first of equally near triangles would keep the pixel (strict test):
            // front to back, a tie goes to the smaller index of this mesh (a depth from before it keeps its pixel).
            const bool wins_tie = owners != nullptr && z == zrow[x] && owners[x] != kNoOwner && index < owners[x];
            if (!(z < zrow[x]) && !wins_tie) {
              cov = 0, all_pass = false;
              ++stats_.depth_rejected;
              s[0] = s[1] = s[2] = s[3] = 0;
              continue;
            }
            if (options.write_depth) zrow[x] = z;
            if (owners != nullptr) owners[x] = index;
          }
          ++stats_.fragments_shaded;
          if (t.linear_color) {
            const float k = static_cast<float>(i);
            store_premultiplied(Color{c_start.r + k * t.dcdx[0], c_start.g + k * t.dcdx[1],
                                      c_start.b + k * t.dcdx[2], c_start.a + k * t.dcdx[3]},
                                1.f, s);
            continue;
          }
          double lambda[3], w[3];
          t.weights(x + 0.5, y + 0.5, lambda);
          t.attribute_weights(lambda, w);
          store_premultiplied(fragment_color(t, options, w), 1.f, s);
        }
        stats_.fragments += x1 - x0;
        if (all_pass) {
          blend_row(CompositeOp::SourceOver, target.pixels + y * target.stride + static_cast<std::ptrdiff_t>(x0) * 4,
                    src.data(), nullptr, nullptr, x1 - x0);
          return;
        }
        // Only the run between the first and the last fragment that passed (hidden spans blend nothing).
        int first = 0, last = x1 - x0 - 1;
        while (first <= last && b.coverage[static_cast<std::size_t>(first)] == 0) ++first;
        while (last >= first && b.coverage[static_cast<std::size_t>(last)] == 0) --last;
        if (first > last) return;
        blend_row(CompositeOp::SourceOver,
                  target.pixels + y * target.stride + static_cast<std::ptrdiff_t>(x0 + first) * 4,
                  src.data() + static_cast<std::size_t>(first) * 4, b.coverage.data() + first, nullptr,
                  last - first + 1);
      });
      if (any) {
        ++stats_.triangles_drawn;
      } else {
        ++stats_.triangles_skipped;
      }
    }
    return;
  }

  // 3'. Antialiased: the mesh's box, clipped to the view.
  double bx0 = width, by0 = height, bx1 = 0, by1 = 0;
  for (const MeshVertex& v : mesh.vertices) {
    if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y)) continue;
    bx0 = std::min(bx0, v.position.x - origin.x), bx1 = std::max(bx1, v.position.x - origin.x);
    by0 = std::min(by0, v.position.y - origin.y), by1 = std::max(by1, v.position.y - origin.y);
  }
  const int box_x0 = static_cast<int>(std::clamp(std::floor(bx0), 0.0, double(width)));
  const int box_x1 = static_cast<int>(std::clamp(std::ceil(bx1) + 1, 0.0, double(width)));
  const int box_y0 = static_cast<int>(std::clamp(std::floor(by0), 0.0, double(height)));
  const int box_y1 = static_cast<int>(std::clamp(std::ceil(by1) + 1, 0.0, double(height)));
  if (box_x0 >= box_x1 || box_y0 >= box_y1) {
    stats_.triangles_skipped = static_cast<std::int64_t>(mesh.triangles.size());
    return;
  }
  const int bw = box_x1 - box_x0, bh = box_y1 - box_y0;
  const std::size_t cells = static_cast<std::size_t>(bw) * bh;
  b.sum_rgba.assign(cells * 4, 0.f);
  b.sum_coverage.assign(cells, 0.f);
  const float* mesh_depth = nullptr;
  if (use_depth) {
    // Depth pre-pass: the nearest surface at every covered centre (earlier draws' depths included).
    b.mesh_depth.resize(cells);
    for (int y = box_y0; y < box_y1; ++y) {
      std::copy(depth->row(y) + box_x0, depth->row(y) + box_x1,
                b.mesh_depth.begin() + static_cast<std::ptrdiff_t>(y - box_y0) * bw);
    }
    for (const std::uint32_t index : b.order) {
      if (!prepare(mesh, mesh.triangles[index], options, origin, t)) continue;
      cover_triangle(t.p, width, height, false, [&](int y, int x0, int x1) {
        float* zrow = b.mesh_depth.data() + static_cast<std::size_t>(y - box_y0) * bw - box_x0;
        for (int x = x0; x < x1; ++x) {
          double lambda[3];
          t.weights(x + 0.5, y + 0.5, lambda);
          zrow[x] = std::min(zrow[x], static_cast<float>(t.depth_at(lambda)));
        }
      });
    }
    mesh_depth = b.mesh_depth.data();
  }
  for (const std::uint32_t index : b.order) {
    if (!prepare(mesh, mesh.triangles[index], options, origin, t)) {
      ++stats_.triangles_skipped;
      continue;
    }
    b.lines.clear();
    // Counterclockwise on screen for every triangle, so coverage of neighbours adds (non-zero of one winding).
    const bool clockwise = (t.p[1].x - t.p[0].x) * (t.p[2].y - t.p[0].y) -
                               (t.p[1].y - t.p[0].y) * (t.p[2].x - t.p[0].x) > 0;
    b.lines.points = {t.p[0], clockwise ? t.p[2] : t.p[1], clockwise ? t.p[1] : t.p[2]};
    b.lines.ends = {3};
    b.lines.closed = {1};
    AccumulateSink sink(t, options, box_x0, box_y0, bw, b.sum_rgba.data(), b.sum_coverage.data(), mesh_depth, stats_);
    b.rasterizer.fill(b.lines, FillRule::NonZero, AntiAlias::Analytic, width, height, sink);
    ++stats_.triangles_drawn;
  }
  if (use_depth && options.write_depth) {
    for (int y = box_y0; y < box_y1; ++y) {
      std::copy(b.mesh_depth.begin() + static_cast<std::ptrdiff_t>(y - box_y0) * bw,
                b.mesh_depth.begin() + static_cast<std::ptrdiff_t>(y - box_y0 + 1) * bw, depth->row(y) + box_x0);
    }
  }
  // Composite the sums: where triangles overlap (coverage above 1), the colour is their coverage-weighted mean.
  constexpr float kMax = static_cast<float>(BasicImage<T>::kMax);
  for (int y = box_y0; y < box_y1; ++y) {
    const float* rgba = b.sum_rgba.data() + static_cast<std::size_t>(y - box_y0) * bw * 4;
    const float* cov = b.sum_coverage.data() + static_cast<std::size_t>(y - box_y0) * bw;
    int first = -1, last = -1;
    for (int i = 0; i < bw; ++i) {
      if (cov[i] > 0) {
        if (first < 0) first = i;
        last = i;
      }
    }
    if (first < 0) continue;
    T* s = src.data();
    for (int i = first; i <= last; ++i, s += 4) {
      const float scale = cov[i] > 1 ? kMax / cov[i] : kMax;
      for (int c = 0; c < 4; ++c) s[c] = static_cast<T>(std::min(rgba[4 * i + c] * scale + 0.5f, kMax));
      s[0] = std::min(s[0], s[3]), s[1] = std::min(s[1], s[3]), s[2] = std::min(s[2], s[3]);
    }
    blend_row(CompositeOp::SourceOver,
              target.pixels + y * target.stride + static_cast<std::ptrdiff_t>(box_x0 + first) * 4, src.data(),
              nullptr, nullptr, last - first + 1);
  }
}

template void MeshRenderer::draw(ImageView<std::uint8_t>, const Mesh&, const MeshOptions&, DepthBuffer*);
template void MeshRenderer::draw(ImageView<std::uint16_t>, const Mesh&, const MeshOptions&, DepthBuffer*);

}  // namespace vraster
