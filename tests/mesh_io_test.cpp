// Mesh input: OBJ (polygons fanned, negative indices, corner normals), .vmesh, errors with positions, the camera,
// and the built-in sphere and torus.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "vraster/error.hpp"
#include "vraster/mesh_io.hpp"

namespace vraster {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ObjReader, PolygonsAreFannedAndNegativeIndicesCountBack) {
  const MeshModel m = parse_obj(
      "# a square and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nv 2 0 0\nf -1 -4 -3\n", "t.obj");
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  // -1 is the fifth vertex (2, 0, 0), -4 the second, -3 the third.
  const auto& t = m.triangles[2];
  EXPECT_EQ(m.positions[t[0]].x, 2);
  EXPECT_EQ(m.positions[t[1]].x, 1);
  EXPECT_EQ(m.positions[t[1]].y, 0);
  EXPECT_EQ(m.positions[t[2]].y, 1);
  EXPECT_TRUE(m.normals.empty());
}

TEST(ObjReader, CornerNormalsSplitVertices) {
  const MeshModel m = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 1/7/2 3//2 2//2\n",
                                "n.obj");
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 6u);  // each position with two different normals
  ASSERT_EQ(m.normals.size(), 6u);
  EXPECT_EQ(m.normals[m.triangles[0][0]].z, 1);
  EXPECT_EQ(m.normals[m.triangles[1][0]].z, -1);
}

TEST(ObjReader, ErrorsNameLineAndColumn) {
  EXPECT_EQ(error_of([] { parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "a.obj"); }),
            "a.obj:4:7: vertex index -4 out of range (3 defined so far)");
  EXPECT_EQ(error_of([] { parse_obj("v 0 0 nan\n", "b.obj"); }), "b.obj:1:7: 'nan' is not finite");
  EXPECT_EQ(error_of([] { parse_obj("v 0 0\n", "c.obj"); }), "c.obj:1:6: 'v' needs 3 values");
  EXPECT_EQ(error_of([] { parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "d.obj"); }),
            "d.obj:4:6: a face needs at least 3 corners");
  EXPECT_EQ(error_of([] { parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3//x\n", "e.obj"); }),
            "e.obj:4:7: '3//x' is not a face corner (v, v/t, v//n or v/t/n)");
}

TEST(VmeshReader, ReadsADocument) {
  const MeshDocument d = parse_vmesh(
      "# comment\nvmesh 1\nsize 40 30\nbackground transparent\nlight on\nv 1 2 0.5 #ff000080 0 0 -1 # red\n"
      "v 5 2 0.5 #0f0\nv 1 9 0.25 #0000ff\nt 0 1 2\n",
      "d.vmesh");
  EXPECT_EQ(d.width, 40);
  EXPECT_EQ(d.height, 30);
  EXPECT_EQ(d.background.a, 0);
  EXPECT_TRUE(d.lit);
  ASSERT_EQ(d.mesh.vertices.size(), 3u);
  EXPECT_NEAR(d.mesh.vertices[0].color.a, 128 / 255.0, 1e-6);
  EXPECT_EQ(d.mesh.vertices[1].color.g, 1);
  EXPECT_EQ(d.mesh.vertices[2].depth, 0.25);
  EXPECT_EQ(d.mesh.triangles.size(), 1u);
  EXPECT_EQ(error_of([] { parse_vmesh("vmesh 1\nquad 1 2 3 4\n", "q.vmesh"); }),
            "q.vmesh:2:1: unknown statement 'quad' (size, background, light, v, t)");
  EXPECT_EQ(error_of([] { parse_vmesh("", "e.vmesh"); }), "e.vmesh:1:1: empty file (a mesh file starts with 'vmesh 1')");
}

// The camera: an orthographic view of the unit sphere fills the image less the margin; nearer points have smaller
// depth; a perspective camera makes the near side larger than the far side.
TEST(Camera, ProjectsAndFits) {
  const MeshModel sphere = make_sphere(8, 12);
  Camera camera;
  camera.yaw = camera.pitch = 0;
  camera.margin = 0.1;
  const Mesh m = project(sphere, camera, 100, 80, Color{1, 1, 1, 1});
  double min_x = 1e9, max_x = -1e9;
  for (const MeshVertex& v : m.vertices) min_x = std::min(min_x, v.position.x), max_x = std::max(max_x, v.position.x);
  EXPECT_NEAR(max_x - min_x, 64, 0.5);  // 80 * (1 - 2 * 0.1)
  // Vertex on +z (towards the viewer in model space) is nearest, with its normal facing the viewer.
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    if (m.vertices[i].depth < m.vertices[nearest].depth) nearest = i;
  }
  EXPECT_GT(sphere.positions[nearest].z, 0.9);
  EXPECT_LT(m.vertices[nearest].normal.z, -0.9);
  camera.perspective = true;
  camera.distance = 2;
  const MeshModel box = parse_obj("v -1 -1 1\nv 1 -1 1\nv 1 -1 -1\nv -1 -1 -1\nf 1 2 3 4\n", "b.obj");
  const Mesh p = project(box, camera, 100, 100, Color{1, 1, 1, 1});
  const double near_width = p.vertices[1].position.x - p.vertices[0].position.x;
  const double far_width = p.vertices[2].position.x - p.vertices[3].position.x;
  EXPECT_GT(near_width, far_width * 1.5);
  EXPECT_LT(p.vertices[0].depth, p.vertices[3].depth);
  EXPECT_GT(p.vertices[3].w, p.vertices[0].w);
  camera.distance = 0.5;
  EXPECT_THROW(project(box, camera, 10, 10, Color{}), Error);
}

// The built-in models are closed surfaces with outward normals and counterclockwise triangles.
TEST(Camera, SphereAndTorusAreOutwardFacing) {
  for (const MeshModel& m : {make_sphere(6, 9), make_torus(1, 0.3, 12, 8)}) {
    ASSERT_FALSE(m.triangles.empty());
    for (const auto& t : m.triangles) {
      const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
      const double nx = (b.y - a.y) * (c.z - a.z) - (b.z - a.z) * (c.y - a.y);
      const double ny = (b.z - a.z) * (c.x - a.x) - (b.x - a.x) * (c.z - a.z);
      const double nz = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      const Vec3 n = m.normals[t[0]];
      EXPECT_GT(nx * n.x + ny * n.y + nz * n.z, 0);
    }
  }
  EXPECT_THROW(make_torus(1, 2, 8, 8), Error);
  EXPECT_THROW(make_sphere(1, 8), Error);
}

}  // namespace
}  // namespace vraster
