// vraster: triangle meshes: edge-function rasterization, per-vertex attributes, flat / Gouraud / Phong shading,
// the z-buffer, the painter's algorithm and 2.5D depth order.
//
//   Mesh (device-space vertices: position, depth, w, colour, normal)
//     -> per triangle: reject non-finite, degenerate and culled triangles; snap to 1/256 px; clip to a guard band
//     -> edge functions: the pixel centres inside, owned by the top-left rule (rasterize_triangle)
//     -> per pixel: barycentric weights -> depth test (z-buffer) -> shading -> a row of premultiplied colours
//     -> vraster::blend_row (composite.hpp), the compositing every other draw call uses
//   Antialiased meshes accumulate every triangle's analytic coverage (vraster's Rasterizer) times its colour into
//   one buffer per mesh and composite that once, so neighbouring triangles add up to full coverage (no seams).
//
// Conventions: device space (x right, y down, pixel centres at +0.5). Depth: smaller is nearer (the seeds' z-buffer
// convention), +infinity is "nothing drawn yet". Lighting space: device axes with z pointing away from the viewer, so
// a normal that faces the viewer is (0, 0, -1). A triangle is front-facing when it runs counterclockwise on screen.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"

namespace vraster {

/// A 3-vector of floats (normals, light directions, eye-space positions).
struct Vec3 {
  float x = 0, y = 0, z = 0;
};

/// One mesh vertex, in device space.
struct MeshVertex {
  Point position;                  ///< device pixels
  double depth = 0;                ///< window depth (interpolated linearly on screen); smaller is nearer
  double w = 1;                    ///< clip-space w of a perspective camera, > 0; 1 for affine (2D) meshes
  Color color{1, 1, 1, 1};         ///< straight colour
  Vec3 normal{0, 0, -1};           ///< lighting-space normal (need not be unit length)
  Vec3 eye{0, 0, 0};               ///< lighting-space position relative to the viewer (perspective view vectors)
};

/// A triangle mesh: vertices and triangles as index triples.
struct Mesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// How colour varies across a triangle (the seeds' shading frequencies).
enum class Shading : std::uint8_t {
  Flat,     ///< one colour per triangle: the mean vertex colour, lit once with the plane's normal (from the `eye`
            ///< positions, turned to the vertex normals' side; the mean vertex normal when they are all equal)
  Gouraud,  ///< lit at each vertex, the colours interpolated with barycentric weights
  Phong,    ///< colour and normal interpolated, the normal renormalized and lit at every pixel
};

/// How hidden surfaces are resolved inside a draw call.
enum class DepthMode : std::uint8_t {
  None,     ///< triangles drawn in the order given
  ZBuffer,  ///< per pixel: drawn when its depth is smaller than the depth buffer's, which it then replaces
  Painter,  ///< triangles sorted by mean vertex depth, farthest first (wrong where triangles interpenetrate)
};

/// Parses "flat" / "gouraud" / "phong" and "none" / "zbuffer" / "painter"; false for an unknown name.
bool parse_shading(std::string_view name, Shading& out);
bool parse_depth_mode(std::string_view name, DepthMode& out);

/// One directional light, Blinn-Phong model:
///   colour = ambient * C + diffuse * max(0, N.L) * C + specular * max(0, N.H)^shininess * white
/// with N the unit normal, L the unit direction towards the light, V the unit direction towards the viewer
/// ((0, 0, -1), or from the vertex's `eye` position with `perspective_view`), H = normalize(L + V), C the surface
/// colour. Alpha is C's. Results are clamped to [0, 1].
struct Lighting {
  bool enabled = false;  ///< off: colours are used as given
  Vec3 to_light{-0.45f, -0.55f, -0.70f};
  float ambient = 0.18f, diffuse = 0.72f, specular = 0.45f, shininess = 40;
  bool perspective_view = false;
};

/// Evaluates `lighting` for a surface colour and a (not necessarily unit) normal; `eye` is used with
/// perspective_view. Returns `color` unchanged when lighting is off.
Color shade(const Lighting& lighting, Color color, Vec3 normal, Vec3 eye);

/// How a mesh is drawn.
struct MeshOptions {
  Shading shading = Shading::Gouraud;
  DepthMode depth = DepthMode::ZBuffer;
  Lighting lighting;
  /// Analytic coverage, accumulated over the whole mesh before compositing (no seams between triangles). With the
  /// z-buffer, a triangle contributes to a pixel when its depth at the pixel centre passes the test against the
  /// mesh's own depth there (an aliased depth pre-pass); silhouette pixels whose centre no triangle covers take every
  /// triangle's coverage, summed and capped at 1.
  bool antialias = false;
  float opacity = 1;  ///< multiplies every colour's alpha
  /// Added to every fragment's depth before the test (negative: nearer), against z-fighting of coplanar surfaces.
  double depth_offset = 0;
  /// Times the triangle's largest depth change per pixel, also added (glPolygonOffset's factor).
  double depth_slope_offset = 0;
  bool cull_back_faces = false;  ///< skip triangles that run clockwise on screen
  bool write_depth = true;       ///< ZBuffer: whether passing fragments store their depth
  /// ZBuffer, aliased, write_depth, and an opaque mesh (every vertex alpha 1, opacity 1): triangles are drawn nearest
  /// first, so that hidden fragments fail the depth test before they are shaded, and depth ties go to the triangle
  /// given first, so the picture is exactly the one of the given order. Ignored (the given order is drawn) when
  /// one of those conditions does not hold. The scene planner sets it (vraster/scene.hpp).
  bool front_to_back = false;
};

/// A float depth per pixel, cleared to +infinity (far).
class DepthBuffer {
 public:
  DepthBuffer() = default;
  /// Throws vraster::Error for sizes out of the image limits.
  DepthBuffer(int width, int height);
  void clear(float value = kFar);
  int width() const { return width_; }
  int height() const { return height_; }
  float at(int x, int y) const { return values_[static_cast<std::size_t>(y) * width_ + x]; }
  float* row(int y) { return values_.data() + static_cast<std::size_t>(y) * width_; }
  static constexpr float kFar = std::numeric_limits<float>::infinity();

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> values_;
};

/// What the last draw did (for tests and tools).
struct MeshStats {
  std::int64_t triangles_drawn = 0;
  std::int64_t triangles_skipped = 0;  ///< non-finite, degenerate (zero area after snapping), culled or off-canvas
  std::int64_t fragments = 0;          ///< pixel centres covered (aliased) or pixels touched (antialiased)
  std::int64_t depth_rejected = 0;     ///< fragments that failed the depth test
  std::int64_t fragments_shaded = 0;   ///< fragments whose colour was computed
  bool drew_front_to_back = false;     ///< MeshOptions::front_to_back applied
};

/// Whether every fragment of `mesh` drawn with `options` is opaque (every vertex alpha >= 1, opacity >= 1), so that
/// the last fragment at a pixel decides it whatever was under it.
bool mesh_is_opaque(const Mesh& mesh, const MeshOptions& options);

/// Vertex positions are snapped to this grid (1/256 px) before the edge functions are evaluated, exactly, in 64-bit
/// integers; triangles reaching beyond +-kMeshGuard pixels are clipped to that band first, so nothing overflows.
inline constexpr int kMeshSubpixelBits = 8;
inline constexpr double kMeshGuard = 1 << 20;

/// Calls span(y, x0, x1) for the pixels [x0, x1) of row y whose centres (x + 0.5, y + 0.5) lie inside the
/// triangle, rows in increasing order, for pixels inside [0, width) x [0, height). A centre exactly on an edge is
/// inside when the edge is a left edge or a top edge (the top-left rule), so triangles that share an edge cover every
/// centre along it exactly once. Degenerate triangles cover nothing; non-finite coordinates cover nothing. Large
/// triangles take the incremental form (each row's span solved from the edge functions); small ones scan their
/// bounding box; both give the same pixels.
void rasterize_triangle(Point a, Point b, Point c, int width, int height,
                        const std::function<void(int y, int x0, int x1)>& span);
/// The plain form for tests: every pixel centre of the clipped bounding box tested against the three edge functions.
void rasterize_triangle_bbox(Point a, Point b, Point c, int width, int height,
                             const std::function<void(int y, int x0, int x1)>& span);

/// The order in which to draw objects of constant depth (2.5D: windows, cartoon cels, VLSI layers): indices into
/// `z`, farthest (largest z) first; equal depths keep their given order. Non-finite depths sort first (farthest).
std::vector<std::size_t> depth_order(std::span<const double> z);

/// Draws meshes. Keeps its buffers between calls: one MeshRenderer per thread allocates nothing in steady state.
class MeshRenderer {
 public:
  MeshRenderer();
  ~MeshRenderer();
  MeshRenderer(MeshRenderer&&) noexcept;
  MeshRenderer& operator=(MeshRenderer&&) noexcept;

  /// Draws `mesh` onto `target` through vraster::blend_row (source-over). With DepthMode::ZBuffer, `depth` is the
  /// depth buffer to test and update (its size must be the view's, else vraster::Error); null: a buffer of the
  /// renderer's own, cleared for this call. Triangles with a non-finite coordinate, depth, w <= 0 or an index out of
  /// range are skipped (as the canvas ignores non-finite arguments).
  template <class T>
  void draw(ImageView<T> target, const Mesh& mesh, const MeshOptions& options, DepthBuffer* depth = nullptr);
  template <class T>
  void draw(BasicImage<T>& target, const Mesh& mesh, const MeshOptions& options, DepthBuffer* depth = nullptr) {
    draw(ImageView<T>::of(target), mesh, options, depth);
  }

  const MeshStats& stats() const { return stats_; }

 private:
  struct Buffers;  // src/mesh/
  std::unique_ptr<Buffers> buffers_;
  MeshStats stats_;
};

}  // namespace vraster
