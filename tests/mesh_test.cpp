// Triangle meshes: the top-left rule (fans and strips cover every centre once), the incremental form against the
// bounding-box form and against the aliased path rasterizer, barycentric and perspective-correct interpolation, the
// z-buffer, the painter's algorithm, depth offsets, 2.5D order, seamless antialiasing, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "vraster/composite.hpp"
#include "vraster/error.hpp"
#include "vraster/mesh.hpp"
#include "vraster/renderer.hpp"

namespace vraster {
namespace {

// Every covered centre of a triangle, counted into a grid.
void count_cover(std::vector<int>& counts, int w, int h, Point a, Point b, Point c, bool bbox = false) {
  auto span = [&](int y, int x0, int x1) {
    for (int x = x0; x < x1; ++x) ++counts[static_cast<std::size_t>(y) * w + x];
  };
  if (bbox) {
    rasterize_triangle_bbox(a, b, c, w, h, span);
  } else {
    rasterize_triangle(a, b, c, w, h, span);
  }
}

MeshVertex vertex(double x, double y, Color c = Color{1, 1, 1, 1}, double z = 0) {
  MeshVertex v;
  v.position = Point{x, y};
  v.color = c;
  v.depth = z;
  return v;
}

// A fan around an interior point and a strip, with vertices on pixel corners and centres, so that many centres lie
// exactly on shared edges: every pixel is covered at most once, and every centre strictly inside the outline once.
TEST(MeshRaster, FanAndStripCoverEveryCentreExactlyOnce) {
  const int w = 40, h = 40;
  {
    std::vector<int> counts(w * h, 0);
    const Point centre{20.5, 20.5};
    const int n = 24;
    std::vector<Point> ring;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      ring.push_back(Point{std::round(20 + 15 * std::cos(a)) + 0.5 * (i % 2), std::round(20 + 15 * std::sin(a))});
    }
    for (int i = 0; i < n; ++i) {
      count_cover(counts, w, h, centre, ring[i], ring[(i + 1) % n]);
    }
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_LE(counts[y * w + x], 1) << "pixel " << x << "," << y << " covered twice";
        const double dx = x + 0.5 - 20, dy = y + 0.5 - 20;
        if (dx * dx + dy * dy < 12 * 12) {
          EXPECT_EQ(counts[y * w + x], 1) << "gap at " << x << "," << y;
        }
        if (dx * dx + dy * dy > 17 * 17) {
          EXPECT_EQ(counts[y * w + x], 0) << x << "," << y;
        }
      }
    }
  }
  {
    // A strip over [2, 38] x [5, 30], zig-zagging with vertices on exact centres and corners.
    std::vector<int> counts(w * h, 0);
    std::vector<Point> top, bottom;
    for (int i = 0; i <= 12; ++i) {
      top.push_back(Point{2.0 + 3 * i, 5.0 + (i % 3) * 0.5});
      bottom.push_back(Point{2.0 + 3 * i + (i % 2) * 0.5, 30.5});
    }
    for (int i = 0; i < 12; ++i) {
      count_cover(counts, w, h, top[i], bottom[i], top[i + 1]);
      count_cover(counts, w, h, top[i + 1], bottom[i], bottom[i + 1]);
    }
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_LE(counts[y * w + x], 1) << "pixel " << x << "," << y << " covered twice";
        if (x >= 3 && x < 37 && y >= 7 && y < 30) {
          EXPECT_EQ(counts[y * w + x], 1) << "gap at " << x << "," << y;
        }
      }
    }
  }
}

// The same property through the renderer: alpha 0.5 blended once gives one level everywhere, never two.
TEST(MeshRaster, HalfAlphaFanAndStripAreBlendedOnce) {
  Image img(32, 32);
  Mesh mesh;
  mesh.vertices.push_back(vertex(16, 16, Color{0, 0, 1, 0.5f}));
  const int n = 16;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    mesh.vertices.push_back(vertex(std::round(16 + 14 * std::cos(a)), std::round(16 + 14 * std::sin(a)),
                                   Color{0, 0, 1, 0.5f}));
  }
  for (std::uint32_t i = 0; i < n; ++i) mesh.triangles.push_back({0, 1 + i, 1 + (i + 1) % n});
  MeshRenderer r;
  MeshOptions o;
  o.depth = DepthMode::None;
  r.draw(img, mesh, o);
  int half = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const int a = img.pixel(x, y)[3];
      ASSERT_TRUE(a == 0 || a == 128) << "alpha " << a << " at " << x << "," << y;
      const double dx = x + 0.5 - 16, dy = y + 0.5 - 16;
      if (dx * dx + dy * dy < 11 * 11) {
        EXPECT_EQ(a, 128) << "gap at " << x << "," << y;
      }
      half += a == 128;
    }
  }
  EXPECT_EQ(half, r.stats().fragments);

  // A strip of 24 triangles with vertices on pixel centres and corners: inside it every pixel is blended once.
  Image strip(40, 20);
  Mesh s;
  for (int i = 0; i <= 12; ++i) {
    s.vertices.push_back(vertex(2.0 + 3 * i, 2.0 + (i % 2) * 0.5, Color{1, 0, 0, 0.5f}));
    s.vertices.push_back(vertex(2.0 + 3 * i + (i % 3) * 0.5, 17.5, Color{1, 0, 0, 0.5f}));
  }
  for (std::uint32_t i = 0; i < 12; ++i) {
    s.triangles.push_back({2 * i, 2 * i + 1, 2 * i + 2});
    s.triangles.push_back({2 * i + 2, 2 * i + 1, 2 * i + 3});
  }
  r.draw(strip, s, o);
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 40; ++x) {
      const int a = strip.pixel(x, y)[3];
      ASSERT_TRUE(a == 0 || a == 128) << "alpha " << a << " at " << x << "," << y;
      if (x >= 3 && x < 37 && y >= 3 && y < 17) {
        EXPECT_EQ(a, 128) << "gap at " << x << "," << y;
      }
    }
  }
}

// Incremental spans and the bounding-box scan give the same pixels; both agree with vraster's aliased path
// rasterizer (an independent scan converter with the same ownership rule) except at centres exactly on an edge,
// where the path rasterizer's floating-point crossings may round either way.
TEST(MeshRaster, IncrementalMatchesBoundingBoxAndPathRasterizer) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-20, 120);
  const int w = 100, h = 90;
  Rasterizer raster;
  int compared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Point p[3];
    for (Point& q : p) q = Point{std::round(coord(rng) * 256) / 256, std::round(coord(rng) * 256) / 256};
    if (trial % 4 == 0) {  // a sliver: the third vertex a grid step off the midpoint of the other two
      p[2] = Point{std::round((p[0].x + p[1].x) * 128) / 256, std::round((p[0].y + p[1].y) * 128 + 1) / 256};
    }
    std::vector<int> inc(w * h, 0), box(w * h, 0);
    count_cover(inc, w, h, p[0], p[1], p[2]);
    count_cover(box, w, h, p[0], p[1], p[2], true);
    ASSERT_EQ(inc, box) << "trial " << trial;

    Polylines lines;
    lines.points = {p[0], p[1], p[2]};
    lines.ends = {3};
    lines.closed = {1};
    std::vector<int> path(w * h, 0);
    struct Sink final : CoverageSink {
      std::vector<int>* out;
      int w;
      void span(int y, int x0, int x1, float) override {
        for (int x = x0; x < x1; ++x) ++(*out)[static_cast<std::size_t>(y) * w + x];
      }
      void row(int y, int x0, int x1, const float* c) override {
        for (int x = x0; x < x1; ++x) (*out)[static_cast<std::size_t>(y) * w + x] += c[x - x0] > 0;
      }
    } sink;
    sink.out = &path;
    sink.w = w;
    raster.fill(lines, FillRule::NonZero, AntiAlias::None, w, h, sink);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (inc[y * w + x] == path[y * w + x]) continue;
        // Allowed only on an edge: some edge function is exactly 0 at the centre (exact in double on this grid).
        bool on_edge = false;
        for (int i = 0; i < 3; ++i) {
          const Point a = p[i], b = p[(i + 1) % 3];
          on_edge = on_edge || (b.x - a.x) * (y + 0.5 - a.y) - (b.y - a.y) * (x + 0.5 - a.x) == 0;
        }
        EXPECT_TRUE(on_edge) << "trial " << trial << " pixel " << x << "," << y << " mesh " << inc[y * w + x]
                             << " path " << path[y * w + x] << " tri " << p[0].x << "," << p[0].y << " " << p[1].x
                             << "," << p[1].y << " " << p[2].x << "," << p[2].y;
      }
    }
    ++compared;
  }
  EXPECT_EQ(compared, 400);
}

TEST(MeshRaster, DegenerateAndNonFiniteTrianglesCoverNothing) {
  std::vector<int> counts(16 * 16, 0);
  count_cover(counts, 16, 16, Point{1, 1}, Point{8, 8}, Point{15, 15});      // collinear
  count_cover(counts, 16, 16, Point{3, 3}, Point{3, 3}, Point{9, 2});        // repeated vertex
  count_cover(counts, 16, 16, Point{NAN, 1}, Point{8, 8}, Point{1, 15});     // NaN
  count_cover(counts, 16, 16, Point{INFINITY, 1}, Point{8, 8}, Point{1, 15});
  count_cover(counts, 16, 16, Point{1e300, 1}, Point{-1e300, 8}, Point{1, 15});  // beyond the coordinate limit
  for (int c : counts) {
    ASSERT_EQ(c, 0);
  }
  // A sliver a thousandth of a pixel wide covers the centres it passes exactly through, or none.
  count_cover(counts, 16, 16, Point{4.5, 0}, Point{4.5, 16}, Point{4.501, 16});
  int total = 0;
  for (int c : counts) total += c;
  EXPECT_LE(total, 16);
}

// Two huge triangles (vertices a million pixels away, clipped to the guard band) sharing a diagonal through the
// canvas: every pixel exactly once.
TEST(MeshRaster, HugeTrianglesAreClippedAndStillShareEdges) {
  const int w = 50, h = 40;
  std::vector<int> counts(w * h, 0);
  const Point a{-3e6, -2e6}, b{4e6, 3.1e6}, c{-3e6, 5e6}, d{5e6, -4e6};
  count_cover(counts, w, h, a, b, c);
  count_cover(counts, w, h, a, d, b);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ASSERT_EQ(counts[y * w + x], 1) << x << "," << y;
    }
  }
}

// Barycentric (Gouraud) colour at a pixel centre, worked by hand: triangle (0,0) red, (8,0) green, (0,8) blue; the
// centre (1.5, 1.5) has weights 1 - 3/16 - 3/16 = 0.625 (red), 0.1875 (green), 0.1875 (blue).
TEST(MeshShading, GouraudInterpolatesWithBarycentricWeights) {
  Mesh mesh;
  mesh.vertices = {vertex(0, 0, Color{1, 0, 0, 1}), vertex(8, 0, Color{0, 1, 0, 1}), vertex(0, 8, Color{0, 0, 1, 1})};
  mesh.triangles = {{0, 1, 2}};
  MeshRenderer r;
  Image img(8, 8);
  r.draw(img, mesh, MeshOptions{});
  const std::uint8_t* p = img.pixel(1, 1);
  EXPECT_NEAR(p[0], 0.625 * 255, 1);
  EXPECT_NEAR(p[1], 0.1875 * 255, 1);
  EXPECT_NEAR(p[2], 0.1875 * 255, 1);
  EXPECT_EQ(p[3], 255);
  Image16 img16(8, 8);
  r.draw(img16, mesh, MeshOptions{});
  EXPECT_NEAR(img16.pixel(1, 1)[0], 0.625 * 65535, 1);
  EXPECT_NEAR(img16.pixel(1, 1)[2], 0.1875 * 65535, 1);
  // Flat: one colour, the mean of the three, everywhere.
  MeshOptions flat;
  flat.shading = Shading::Flat;
  Image f(8, 8);
  r.draw(f, mesh, flat);
  EXPECT_NEAR(f.pixel(1, 1)[0], 85, 1);
  EXPECT_EQ(f.pixel(1, 1)[0], f.pixel(4, 2)[0]);
  EXPECT_EQ(f.pixel(1, 1)[2], f.pixel(2, 4)[2]);
}

// Perspective-correct interpolation against ray casting: a triangle in 3D, projected with w = its eye depth; at every
// covered centre the colour must be the 3D barycentric mix at the point where the pixel's ray meets the triangle.
TEST(MeshShading, PerspectiveCorrectMatchesRayCasting) {
  const double f = 60, cx = 32, cy = 32;
  const double P[3][3] = {{-1.0, -0.8, 2.0}, {1.2, -0.5, 6.0}, {-0.4, 1.0, 3.5}};
  Mesh mesh;
  for (int i = 0; i < 3; ++i) {
    MeshVertex v = vertex(cx + f * P[i][0] / P[i][2], cy + f * P[i][1] / P[i][2], Color{i == 0 ? 1.f : 0.f, 0, 0, 1});
    v.w = P[i][2];
    mesh.vertices.push_back(v);
  }
  mesh.triangles = {{0, 1, 2}};
  Image img(64, 64);
  MeshRenderer r;
  r.draw(img, mesh, MeshOptions{});
  auto sub = [](const double* a, const double* b, double* o) {
    for (int k = 0; k < 3; ++k) o[k] = a[k] - b[k];
  };
  auto cross = [](const double* a, const double* b, double* o) {
    o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  double e1[3], e2[3], n[3];
  sub(P[1], P[0], e1);
  sub(P[2], P[0], e2);
  cross(e1, e2, n);
  int checked = 0, affine_far = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (img.pixel(x, y)[3] == 0) continue;
      const double d[3] = {(x + 0.5 - cx) / f, (y + 0.5 - cy) / f, 1};
      const double t = dot(n, P[0]) / dot(n, d);
      const double hit[3] = {d[0] * t, d[1] * t, d[2] * t};
      double rel[3], c1[3], c2[3];
      sub(hit, P[0], rel);
      cross(rel, e2, c1);
      cross(e1, rel, c2);
      const double b1 = dot(c1, n) / dot(n, n), b2 = dot(c2, n) / dot(n, n), b0 = 1 - b1 - b2;
      EXPECT_NEAR(img.pixel(x, y)[0], std::clamp(b0, 0.0, 1.0) * 255, 1.5) << x << "," << y;
      ++checked;
      // How far plain screen-space interpolation would be (to show the test can tell them apart).
      const double ax = mesh.vertices[1].position.x - mesh.vertices[0].position.x;
      const double ay = mesh.vertices[1].position.y - mesh.vertices[0].position.y;
      const double bx = mesh.vertices[2].position.x - mesh.vertices[0].position.x;
      const double by = mesh.vertices[2].position.y - mesh.vertices[0].position.y;
      const double px = x + 0.5 - mesh.vertices[0].position.x, py = y + 0.5 - mesh.vertices[0].position.y;
      const double det = ax * by - ay * bx;
      const double s0 = 1 - (px * by - py * bx) / det - (ax * py - ay * px) / det;
      affine_far += std::abs(s0 - b0) * 255 > 10;
    }
  }
  EXPECT_GT(checked, 200);
  EXPECT_GT(affine_far, 20);
}

// Phong lights each pixel with the interpolated normal: a highlight between the vertices, which Gouraud (lit at the
// vertices only) misses. Flat is one colour.
TEST(MeshShading, PhongFindsTheHighlightGouraudMisses) {
  Mesh mesh;
  mesh.vertices = {vertex(2, 2, Color{0.2f, 0.3f, 0.8f, 1}), vertex(62, 2, Color{0.2f, 0.3f, 0.8f, 1}),
                   vertex(32, 62, Color{0.2f, 0.3f, 0.8f, 1})};
  mesh.vertices[0].normal = Vec3{-0.7f, -0.7f, -0.4f};
  mesh.vertices[1].normal = Vec3{0.7f, -0.7f, -0.4f};
  mesh.vertices[2].normal = Vec3{0.0f, 0.9f, -0.4f};
  mesh.triangles = {{0, 1, 2}};
  MeshOptions o;
  o.lighting.enabled = true;
  o.lighting.to_light = Vec3{0, 0, -1};  // from the viewer: the highlight is where the normal faces the viewer
  MeshRenderer r;
  Image phong(64, 64), gouraud(64, 64);
  o.shading = Shading::Phong;
  r.draw(phong, mesh, o);
  o.shading = Shading::Gouraud;
  r.draw(gouraud, mesh, o);
  // The interpolated normal is (0, 0, -0.4) at the weights (0.28125, 0.28125, 0.4375): there Phong reaches
  // (ambient + diffuse) * 0.2 + specular in red; Gouraud's vertices are lit at N.L = 0.37, with no highlight.
  int phong_max = 0, gouraud_max = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      phong_max = std::max<int>(phong_max, phong.pixel(x, y)[0]);
      gouraud_max = std::max<int>(gouraud_max, gouraud.pixel(x, y)[0]);
    }
  }
  EXPECT_GE(phong_max, ((o.lighting.ambient + o.lighting.diffuse) * 0.2 + o.lighting.specular) * 255 - 4);
  EXPECT_LT(gouraud_max, phong_max - 60);
  // shade() itself: ambient + diffuse + specular for a normal facing the light and the viewer.
  const Color lit = shade(o.lighting, Color{0.5f, 0.5f, 0.5f, 1}, Vec3{0, 0, -2}, Vec3{});
  EXPECT_NEAR(lit.r, std::min(1.f, (o.lighting.ambient + o.lighting.diffuse) * 0.5f + o.lighting.specular), 1e-5);
}

// Two triangles that pass through each other: the z-buffer shows, at each centre, the one nearer there (checked
// against the planes directly); the painter's algorithm (one order for whole triangles) gets part of it wrong.
TEST(MeshDepth, ZBufferResolvesInterpenetrationPainterDoesNot) {
  Mesh mesh;
  const Color red{1, 0, 0, 1}, blue{0, 0, 1, 1};
  // Red tilts from near (left) to far (right), blue the other way; the mean depths differ slightly.
  mesh.vertices = {vertex(4, 8, red, 0.1), vertex(60, 12, red, 0.9), vertex(30, 58, red, 0.5),
                   vertex(60, 6, blue, 0.15), vertex(4, 14, blue, 0.85), vertex(34, 60, blue, 0.45)};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  MeshRenderer r;
  Image z(64, 64), painter(64, 64);
  MeshOptions o;
  r.draw(z, mesh, o);
  o.depth = DepthMode::Painter;
  r.draw(painter, mesh, o);
  auto plane_depth = [&](int first, double x, double y, bool& inside) {
    const MeshVertex* v = &mesh.vertices[static_cast<std::size_t>(first)];
    const double ax = v[1].position.x - v[0].position.x, ay = v[1].position.y - v[0].position.y;
    const double bx = v[2].position.x - v[0].position.x, by = v[2].position.y - v[0].position.y;
    const double px = x - v[0].position.x, py = y - v[0].position.y, det = ax * by - ay * bx;
    const double l1 = (px * by - py * bx) / det, l2 = (ax * py - ay * px) / det, l0 = 1 - l1 - l2;
    inside = l0 > 1e-9 && l1 > 1e-9 && l2 > 1e-9;
    return l0 * v[0].depth + l1 * v[1].depth + l2 * v[2].depth;
  };
  int both = 0, painter_wrong = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      bool in_red, in_blue;
      const double zr = plane_depth(0, x + 0.5, y + 0.5, in_red), zb = plane_depth(3, x + 0.5, y + 0.5, in_blue);
      if (!in_red || !in_blue || std::abs(zr - zb) < 1e-6) continue;
      ++both;
      const bool red_wins = zr < zb;
      EXPECT_EQ(z.pixel(x, y)[0] == 255, red_wins) << x << "," << y;
      EXPECT_EQ(z.pixel(x, y)[2] == 255, !red_wins) << x << "," << y;
      painter_wrong += (painter.pixel(x, y)[0] == 255) != red_wins;
    }
  }
  EXPECT_GT(both, 300);
  EXPECT_GT(painter_wrong, 50);
  EXPECT_GT(r.stats().triangles_drawn, 0);
}

// Painter's order: farthest first, so the nearer (drawn later) wins where they overlap without interpenetrating.
TEST(MeshDepth, PainterDrawsFarthestFirst) {
  Mesh mesh;
  mesh.vertices = {vertex(0, 0, Color{1, 0, 0, 1}, 0.2), vertex(16, 0, Color{1, 0, 0, 1}, 0.2),
                   vertex(0, 16, Color{1, 0, 0, 1}, 0.2), vertex(0, 0, Color{0, 1, 0, 1}, 0.7),
                   vertex(16, 0, Color{0, 1, 0, 1}, 0.7), vertex(0, 16, Color{0, 1, 0, 1}, 0.7)};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};  // near red given first
  MeshOptions o;
  o.depth = DepthMode::Painter;
  MeshRenderer r;
  Image img(16, 16);
  r.draw(img, mesh, o);
  EXPECT_EQ(img.pixel(3, 3)[0], 255);
  o.depth = DepthMode::None;  // given order: the far green drawn last covers it
  r.draw(img, mesh, o);
  EXPECT_EQ(img.pixel(3, 3)[1], 255);
}

// Coplanar surfaces: the second one is rejected where its depth is not strictly smaller; a negative depth offset
// brings it in front everywhere (the polygon-offset cure for z-fighting). A shared depth buffer carries across draws.
TEST(MeshDepth, DepthOffsetSettlesCoplanarSurfaces) {
  const Color red{1, 0, 0, 1}, blue{0, 0, 1, 1};
  auto quad = [&](Color c, bool other_diagonal) {
    Mesh m;
    // The plane z = 0.3 + 0.01 x + 0.007 y, split along one diagonal or the other (different round-off).
    for (const Point p : {Point{1, 1}, Point{30, 2}, Point{31, 29}, Point{2, 30}}) {
      m.vertices.push_back(vertex(p.x, p.y, c, 0.3 + 0.01 * p.x + 0.007 * p.y));
    }
    if (other_diagonal) {
      m.triangles = {{0, 1, 3}, {1, 2, 3}};
    } else {
      m.triangles = {{0, 1, 2}, {0, 2, 3}};
    }
    return m;
  };
  Image img(32, 32);
  DepthBuffer depth(32, 32);
  MeshRenderer r;
  MeshOptions o;
  r.draw(img, quad(red, false), o, &depth);
  r.draw(img, quad(red, false), MeshOptions{}, &depth);  // the same surface again: never strictly nearer
  EXPECT_EQ(r.stats().depth_rejected, r.stats().fragments);
  o.depth_offset = -1e-4;
  r.draw(img, quad(blue, true), o, &depth);
  EXPECT_EQ(r.stats().depth_rejected, 0);
  int red_left = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) red_left += img.pixel(x, y)[0] == 255;
  }
  EXPECT_EQ(red_left, 0);
  EXPECT_LT(depth.at(10, 10), 0.3 + 0.01 * 10.5 + 0.007 * 10.5);
  DepthBuffer wrong(16, 16);
  EXPECT_THROW(r.draw(img, quad(blue, true), o, &wrong), Error);
}

// 2.5D: objects of constant depth drawn in depth order (farthest first, ties in given order), as windows are.
TEST(MeshDepth, DepthOrderFor2_5DObjects) {
  const std::vector<double> z = {0.5, 0.9, 0.1, 0.5, NAN};
  EXPECT_EQ(depth_order(z), (std::vector<std::size_t>{4, 1, 0, 3, 2}));
  // Three overlapping "windows" given in the wrong order; drawn by depth, the nearest shows on top.
  struct Window {
    double x, y, z;
    Color c;
  };
  const Window windows[3] = {{4, 4, 0.1, Color{1, 0, 0, 1}}, {8, 8, 0.5, Color{0, 1, 0, 1}},
                             {12, 12, 0.9, Color{0, 0, 1, 1}}};
  std::vector<double> depths;
  for (const Window& w : windows) depths.push_back(w.z);
  Image img(32, 32);
  Renderer renderer;
  for (const std::size_t i : depth_order(depths)) {
    Path p;
    p.move_to(windows[i].x, windows[i].y);
    p.line_to(windows[i].x + 14, windows[i].y);
    p.line_to(windows[i].x + 14, windows[i].y + 14);
    p.line_to(windows[i].x, windows[i].y + 14);
    p.close();
    renderer.fill(img, p, Affine{}, windows[i].c, FillOptions{});
  }
  EXPECT_EQ(img.pixel(13, 13)[0], 255);  // all three overlap: red (nearest)
  EXPECT_EQ(img.pixel(20, 20)[1], 255);  // green over blue
  EXPECT_EQ(img.pixel(24, 24)[2], 255);  // blue alone
}

// A square split into many triangles, antialiased, against the same square filled as one path: no seams. Drawing each
// triangle as a mesh of its own (per-triangle coverage, composited one by one) shows the classic conflation seams.
TEST(MeshAntialias, SplitSquareMatchesOnePathWithoutSeams) {
  const double x0 = 5.3, y0 = 4.7, x1 = 58.6, y1 = 57.2;
  const int n = 9;
  Mesh mesh;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const double x = x0 + (x1 - x0) * i / n + (border ? 0 : jitter(rng));
      const double y = y0 + (y1 - y0) * j / n + (border ? 0 : jitter(rng));
      mesh.vertices.push_back(vertex(x, y, Color{0.1f, 0.4f, 0.8f, 1}));
    }
  }
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  }
  const Color white{1, 1, 1, 1};
  Image meshed(64, 64), reference(64, 64), separate(64, 64);
  meshed.clear(white), reference.clear(white), separate.clear(white);
  MeshRenderer r;
  MeshOptions o;
  o.antialias = true;
  o.depth = DepthMode::None;
  r.draw(meshed, mesh, o);
  for (const auto& tri : mesh.triangles) {
    Mesh one;
    one.vertices = mesh.vertices;
    one.triangles = {tri};
    r.draw(separate, one, o);
  }
  Path square;
  square.move_to(x0, y0);
  square.line_to(x1, y0);
  square.line_to(x1, y1);
  square.line_to(x0, y1);
  square.close();
  Renderer renderer;
  renderer.fill(reference, square, Affine{}, Color{0.1f, 0.4f, 0.8f, 1}, FillOptions{});
  int worst = 0, worst_separate = 0;
  for (std::size_t i = 0; i < meshed.data.size(); ++i) {
    worst = std::max(worst, std::abs(int(meshed.data[i]) - int(reference.data[i])));
    worst_separate = std::max(worst_separate, std::abs(int(separate.data[i]) - int(reference.data[i])));
  }
  EXPECT_LE(worst, 1);
  EXPECT_GT(worst_separate, 10);  // the seams a per-triangle approach leaves (this test can tell)
}

// Antialiased meshes with depth: a near triangle in front of a far one that covers it; the far one must not show
// through inside the near one, only its own antialiased edges blend.
TEST(MeshAntialias, DepthPrePassHidesSurfacesBehind) {
  Mesh mesh;
  mesh.vertices = {vertex(2, 2, Color{1, 0, 0, 1}, 0.2), vertex(60, 5, Color{1, 0, 0, 1}, 0.2),
                   vertex(20, 60, Color{1, 0, 0, 1}, 0.2), vertex(0, 0, Color{0, 0, 1, 1}, 0.8),
                   vertex(64, 0, Color{0, 0, 1, 1}, 0.8), vertex(0, 64, Color{0, 0, 1, 1}, 0.8)};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  MeshOptions o;
  o.antialias = true;
  Image img(64, 64);
  MeshRenderer r;
  r.draw(img, mesh, o);
  EXPECT_EQ(img.pixel(20, 20)[0], 255);
  EXPECT_EQ(img.pixel(20, 20)[2], 0);
  EXPECT_EQ(img.pixel(3, 40)[2], 255);
  EXPECT_GT(r.stats().depth_rejected, 100);
}

TEST(MeshInput, BadTrianglesAreSkipped) {
  Mesh mesh;
  mesh.vertices = {vertex(0, 0), vertex(16, 0), vertex(0, 16), vertex(NAN, 3), vertex(5, 5)};
  mesh.vertices[4].w = 0;
  mesh.triangles = {{0, 1, 2}, {0, 3, 2}, {0, 1, 9}, {0, 1, 4}, {0, 0, 1}};
  Image img(16, 16);
  MeshRenderer r;
  MeshOptions o;
  r.draw(img, mesh, o);
  EXPECT_EQ(r.stats().triangles_drawn, 1);
  EXPECT_EQ(r.stats().triangles_skipped, 4);
  o.antialias = true;
  r.draw(img, mesh, o);
  EXPECT_EQ(r.stats().triangles_drawn, 1);
  // Back faces: the triangle runs clockwise on screen (y down), so culling removes it.
  o.antialias = false;
  o.cull_back_faces = true;
  r.draw(img, mesh, o);
  EXPECT_EQ(r.stats().triangles_drawn, 0);
}

// A view that covers part of the canvas is addressed in canvas coordinates.
TEST(MeshInput, ImageViewOffset) {
  Image img(32, 32);
  ImageView<std::uint8_t> view{img.pixel(8, 8), 8, 8, 16, 16, 32 * 4};
  Mesh mesh;
  mesh.vertices = {vertex(0, 0, Color{0, 1, 0, 1}), vertex(40, 0, Color{0, 1, 0, 1}), vertex(0, 40, Color{0, 1, 0, 1})};
  mesh.triangles = {{0, 1, 2}};
  MeshRenderer r;
  r.draw(view, mesh, MeshOptions{});
  EXPECT_EQ(img.pixel(4, 4)[1], 0);   // outside the view
  EXPECT_EQ(img.pixel(9, 9)[1], 255);
  EXPECT_EQ(img.pixel(23, 8)[1], 255);
  EXPECT_EQ(img.pixel(24, 24)[1], 0);  // outside the triangle (x + y > 40)
}

}  // namespace
}  // namespace vraster
