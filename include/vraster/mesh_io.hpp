// vraster: mesh input: 3D models (Wavefront OBJ), cameras that project them to device-space meshes, and the
// vraster mesh text format (.vmesh, documented in README.md).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vraster/image.hpp"
#include "vraster/mesh.hpp"

namespace vraster {

/// A 3D triangle model in model space (y up, as in OBJ). `normals` and `colors` are per vertex, or empty.
struct MeshModel {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Color> colors;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Caps on what a file may ask for (bigger inputs are errors, not memory exhaustion).
inline constexpr std::size_t kMaxMeshVertices = std::size_t{1} << 22;
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 23;
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{256} << 20;

/// How a model is looked at. The model is centred on its bounding box and scaled so its bounding sphere fits the
/// image (less the margin); then turned by `yaw` around its vertical axis and tilted by `pitch` towards the viewer.
/// A perspective camera sits `distance` bounding radii from the centre, its field of view just holding the sphere.
struct Camera {
  bool perspective = false;
  double yaw = 0.6, pitch = 0.4;  ///< radians
  double distance = 3;            ///< perspective: eye distance from the centre in bounding radii, in (1, 1000]
  double margin = 0.06;           ///< share of the smaller image side left free on each side
};

/// Projects a model onto a width x height device: positions, depths (smaller nearer; for perspective a + b / w, so
/// linear on screen), w (perspective: the eye distance), lighting-space normals and eye positions. Missing normals
/// are the normalized sums of the faces' normals at each vertex; missing colours are `color`.
/// Throws vraster::Error for a camera out of range.
Mesh project(const MeshModel& model, const Camera& camera, int width, int height, Color color);

/// A unit sphere of `rings` x `segments` quads (two triangles each; 2 <= rings, 3 <= segments, both <= 2048), with
/// its exact normals; triangles run counterclockwise seen from outside.
MeshModel make_sphere(int rings, int segments);
/// A torus around the y axis: tube centre radius `major`, tube radius `minor` (0 < minor < major), `around` x `tube`
/// quads (each 3 to 2048), exact normals, counterclockwise seen from outside.
MeshModel make_torus(double major, double minor, int around, int tube);

/// Reads Wavefront OBJ text: `v x y z [r g b]`, `vn`, `f` with `v`, `v/t`, `v//n` or `v/t/n` corners (polygons are
/// fanned from their first corner; negative indices count back from the last vertex read); other statements are
/// ignored. A corner's normal, when given, overrides the vertex normal. Throws vraster::Error
/// "NAME:LINE:COLUMN: message" for malformed numbers, bad indices, non-finite values or inputs beyond the caps.
MeshModel parse_obj(std::string_view text, const std::string& name);

/// A .vmesh document: a device-space mesh with its canvas.
struct MeshDocument {
  int width = 256, height = 256;
  Color background{1, 1, 1, 1};
  bool lit = false;  ///< `light on`: the normals are lit (Lighting defaults)
  Mesh mesh;
};

/// Reads the vraster mesh text format (README.md, "Mesh files"). Same errors as parse_obj.
MeshDocument parse_vmesh(std::string_view text, const std::string& name);

/// Reads a whole file (at most kMaxMeshFileBytes); throws vraster::Error naming the file when it cannot.
std::string read_mesh_file(const std::string& path);

}  // namespace vraster
