// Classic line, circle and ellipse scan conversion: exact pixel lists, symmetry, tie rules, clipping.
//
// "Equal" here means the exact same set of pixels (and, for walks, the same order). References are brute-force
// definitions computed independently of the incremental algorithms: the pixel nearest the exact rational line
// position (ties to the smaller coordinate), the midpoint criterion of the circle evaluated directly, etc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "vraster/lines.hpp"

namespace vraster {
namespace {

using Pixels = std::vector<IPoint>;
using i128 = __int128;

Pixels sorted(Pixels v) {
  std::sort(v.begin(), v.end());
  return v;
}

std::string show(const Pixels& v) {
  std::string s;
  for (IPoint p : v) {  // appended piece by piece: GCC 12's -Wrestrict misfires on "literal" + std::string&&
    s += '(';
    s += std::to_string(p.x);
    s += ',';
    s += std::to_string(p.y);
    s += ')';
  }
  return s;
}

// Brute-force reference: the pixel nearest to the exact line at every major coordinate, halves to the smaller
// minor coordinate. Returns the minor coordinate for major offset t in [0, du] from endpoint (u0, v0).
std::int64_t nearest_minor(std::int64_t u0, std::int64_t v0, std::int64_t u1, std::int64_t v1, std::int64_t u) {
  const i128 du = u1 - u0;
  if (du == 0) return v0;
  // Exact position v = N / D with D > 0.
  i128 n = i128{v0} * du + i128{v1 - v0} * (u - u0), d = du;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  i128 c = n / d;
  if (n % d != 0 && n < 0) --c;  // floor
  // Candidates c and c+1: distances |c*d - n| and |(c+1)*d - n|.
  const i128 dist0 = n - c * d, dist1 = (c + 1) * d - n;
  return static_cast<std::int64_t>(dist1 < dist0 ? c + 1 : c);  // tie -> c (smaller)
}

Pixels reference_line(IPoint p, IPoint q) {
  Pixels out;
  const bool x_major = std::llabs(std::int64_t{q.x} - p.x) >= std::llabs(std::int64_t{q.y} - p.y);
  const int u0 = x_major ? p.x : p.y, u1 = x_major ? q.x : q.y;
  const int v0 = x_major ? p.y : p.x, v1 = x_major ? q.y : q.x;
  for (int u = std::min(u0, u1); u <= std::max(u0, u1); ++u) {
    const int v = static_cast<int>(nearest_minor(u0, v0, u1, v1, u));
    out.push_back(x_major ? IPoint{u, v} : IPoint{v, u});
  }
  return out;
}

TEST(Bresenham, SeedWorkedExample_3_4_to_8_7) {
  // The course notes' table: p0 = 1 -> (4,5), -3 -> (5,5), 3 -> (6,6), -1 -> (7,6), 5 -> (8,7).
  const Pixels expected = {{3, 4}, {4, 5}, {5, 5}, {6, 6}, {7, 6}, {8, 7}};
  EXPECT_EQ(show(bresenham_pixels({3, 4}, {8, 7})), show(expected));
}

TEST(Bresenham, ExactPixelsInEachOctant) {
  // Slope 2/5 (no ties): y = 0, .4, .8, 1.2, 1.6, 2 rounds to 0 0 1 1 2 2. Mirrored and transposed by hand.
  struct Case {
    IPoint q;
    Pixels expected;
  };
  const Case cases[] = {
      {{5, 2}, {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}}},
      {{2, 5}, {{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}, {2, 5}}},
      {{-2, 5}, {{0, 0}, {0, 1}, {-1, 2}, {-1, 3}, {-2, 4}, {-2, 5}}},
      {{-5, 2}, {{0, 0}, {-1, 0}, {-2, 1}, {-3, 1}, {-4, 2}, {-5, 2}}},
      {{-5, -2}, {{0, 0}, {-1, 0}, {-2, -1}, {-3, -1}, {-4, -2}, {-5, -2}}},
      {{-2, -5}, {{0, 0}, {0, -1}, {-1, -2}, {-1, -3}, {-2, -4}, {-2, -5}}},
      {{2, -5}, {{0, 0}, {0, -1}, {1, -2}, {1, -3}, {2, -4}, {2, -5}}},
      {{5, -2}, {{0, 0}, {1, 0}, {2, -1}, {3, -1}, {4, -2}, {5, -2}}},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(show(sorted(bresenham_pixels({0, 0}, c.q))), show(sorted(c.expected))) << "to " << c.q.x << "," << c.q.y;
    // Walks are 8-connected and one pixel per major step.
    const Pixels w = bresenham_pixels({0, 0}, c.q);
    for (std::size_t i = 1; i < w.size(); ++i) {
      EXPECT_LE(std::abs(w[i].x - w[i - 1].x), 1);
      EXPECT_LE(std::abs(w[i].y - w[i - 1].y), 1);
    }
  }
}

TEST(Bresenham, MatchesNearestPixelReferenceOnRandomLines) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coord(-60, 60);
  for (int i = 0; i < 3000; ++i) {
    const IPoint p{coord(rng), coord(rng)}, q{coord(rng), coord(rng)};
    ASSERT_EQ(show(sorted(bresenham_pixels(p, q))), show(sorted(reference_line(p, q))))
        << p.x << "," << p.y << " -> " << q.x << "," << q.y;
  }
}

TEST(Bresenham, SymmetricUnderReversal) {
  std::mt19937 rng(6);
  std::uniform_int_distribution<int> coord(-100, 100);
  int ties_seen = 0;
  for (int i = 0; i < 3000; ++i) {
    const IPoint p{coord(rng), coord(rng)}, q{coord(rng), coord(rng)};
    const Pixels a = sorted(bresenham_pixels(p, q)), b = sorted(bresenham_pixels(q, p));
    ASSERT_EQ(show(a), show(b));
    if (sorted(dda_pixels(p, q)) != a) ++ties_seen;
  }
  EXPECT_GT(ties_seen, 0);  // the random set does exercise ties
}

TEST(Bresenham, TieBreakRoundsHalfDownOnAbsoluteCoordinates) {
  // (0,0)-(2,1) passes through (1, 0.5): Bresenham picks (1,0) in both directions.
  EXPECT_EQ(show(sorted(bresenham_pixels({0, 0}, {2, 1}))), show(sorted({{0, 0}, {1, 0}, {2, 1}})));
  EXPECT_EQ(show(sorted(bresenham_pixels({2, 1}, {0, 0}))), show(sorted({{0, 0}, {1, 0}, {2, 1}})));
  // Going up-right: (0,1)-(2,0) passes (1, 0.5) -> (1,0) again (smaller y), also reversed.
  EXPECT_EQ(show(sorted(bresenham_pixels({0, 1}, {2, 0}))), show(sorted({{0, 1}, {1, 0}, {2, 0}})));
  EXPECT_EQ(show(sorted(bresenham_pixels({2, 0}, {0, 1}))), show(sorted({{0, 1}, {1, 0}, {2, 0}})));
  // Steep: (0,0)-(1,2) passes (0.5, 1) -> (0,1).
  EXPECT_EQ(show(sorted(bresenham_pixels({0, 0}, {1, 2}))), show(sorted({{0, 0}, {0, 1}, {1, 2}})));
}

TEST(Dda, DiffersFromBresenhamExactlyAtTies) {
  // The documented difference: DDA rounds halves up.
  EXPECT_EQ(show(sorted(dda_pixels({0, 0}, {2, 1}))), show(sorted({{0, 0}, {1, 1}, {2, 1}})));
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(-80, 80);
  int differing = 0;
  for (int i = 0; i < 3000; ++i) {
    const IPoint p{coord(rng), coord(rng)}, q{coord(rng), coord(rng)};
    const Pixels b = bresenham_pixels(p, q), d = dda_pixels(p, q);
    ASSERT_EQ(b.size(), d.size());
    const bool x_major = std::abs(q.x - p.x) >= std::abs(q.y - p.y);
    std::map<int, int> bres;  // major -> minor
    for (IPoint px : b) bres[x_major ? px.x : px.y] = x_major ? px.y : px.x;
    for (IPoint px : d) {
      const int u = x_major ? px.x : px.y, v = x_major ? px.y : px.x;
      ASSERT_TRUE(bres.count(u));
      // Exact position at u: v_exact = v0 + dv * (u - u0) / du.
      const std::int64_t u0 = x_major ? p.x : p.y;
      const std::int64_t du = x_major ? q.x - p.x : q.y - p.y, dv = x_major ? q.y - p.y : q.x - p.x;
      const bool tie = du != 0 && (2 * dv * (u - u0)) % (2 * du) != 0 && ((2 * dv * (u - u0)) % du) == 0;
      if (tie) {
        EXPECT_EQ(v, bres[u] + 1) << "at a tie DDA takes the larger coordinate";
        ++differing;
      } else {
        EXPECT_EQ(v, bres[u]) << "away from ties DDA and Bresenham agree";
      }
    }
  }
  EXPECT_GT(differing, 0);
}

TEST(Bresenham, HalfOpenDrawsPolylineJointsOnce) {
  const IPoint pts[] = {{1, 1}, {12, 5}, {14, 17}, {3, 9}, {1, 1}};
  std::map<std::pair<int, int>, int> count;
  for (int i = 0; i + 1 < 5; ++i) {
    bresenham_line(pts[i], pts[i + 1], 32, 32, LineEnd::HalfOpen, [&](int x, int y) { ++count[{x, y}]; });
  }
  for (auto& [p, c] : count) EXPECT_EQ(c, 1) << p.first << "," << p.second;
  for (int i = 0; i < 4; ++i) EXPECT_EQ((count[{pts[i].x, pts[i].y}]), 1);
  // Half-open = closed minus the end pixel.
  Pixels closed = bresenham_pixels({12, 5}, {14, 17}), open = bresenham_pixels({12, 5}, {14, 17}, LineEnd::HalfOpen);
  closed.erase(std::remove(closed.begin(), closed.end(), IPoint{14, 17}), closed.end());
  EXPECT_EQ(show(sorted(open)), show(sorted(closed)));
  EXPECT_TRUE(bresenham_pixels({4, 4}, {4, 4}, LineEnd::HalfOpen).empty());
  EXPECT_EQ(bresenham_pixels({4, 4}, {4, 4}).size(), 1u);
  EXPECT_TRUE(dda_pixels({4, 4}, {4, 4}, LineEnd::HalfOpen).empty());
  EXPECT_EQ(show(dda_pixels({4, 4}, {4, 4})), show({{4, 4}}));
}

TEST(Bresenham, ClippedEqualsUnclippedInsideCanvas) {
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> coord(-3000, 3000);
  const int w = 64, h = 48;
  for (int i = 0; i < 2000; ++i) {
    IPoint p{coord(rng), coord(rng)}, q{coord(rng), coord(rng)};
    if (i % 3 == 0) q = {std::uniform_int_distribution<int>(0, w - 1)(rng), std::uniform_int_distribution<int>(0, h - 1)(rng)};
    for (LineEnd end : {LineEnd::Closed, LineEnd::HalfOpen}) {
      Pixels expected;
      for (IPoint px : bresenham_pixels(p, q, end)) {
        if (px.x >= 0 && px.x < w && px.y >= 0 && px.y < h) expected.push_back(px);
      }
      Pixels got;
      bresenham_line(p, q, w, h, end, [&](int x, int y) { got.push_back({x, y}); });
      ASSERT_EQ(show(got), show(expected)) << p.x << "," << p.y << " -> " << q.x << "," << q.y;
      Pixels dgot, dexp;
      for (IPoint px : dda_pixels(p, q, end)) {
        if (px.x >= 0 && px.x < w && px.y >= 0 && px.y < h) dexp.push_back(px);
      }
      dda_line(p, q, w, h, end, [&](int x, int y) { dgot.push_back({x, y}); });
      ASSERT_EQ(show(sorted(dgot)), show(sorted(dexp)));
    }
  }
}

TEST(Bresenham, FarEndpointsCostOnlyTheVisiblePart) {
  // Endpoints two billion pixels away: the walk visits only canvas pixels and they are exactly the reference
  // line's pixels on the canvas (reference evaluated column by column over the canvas only).
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> far(-2000000000, 2000000000);
  const int w = 50, h = 40;
  int visible = 0;
  for (int i = 0; i < 400; ++i) {
    IPoint p{far(rng), far(rng)}, q{far(rng), far(rng)};
    if (i % 2 == 0) {  // force the line through the canvas: q mirrored through a canvas point
      const std::int64_t cx = std::uniform_int_distribution<int>(0, w - 1)(rng), cy = std::uniform_int_distribution<int>(0, h - 1)(rng);
      const std::int64_t qx = 2 * cx - p.x, qy = 2 * cy - p.y;
      q = {static_cast<int>(std::clamp<std::int64_t>(qx, INT32_MIN, INT32_MAX)), static_cast<int>(std::clamp<std::int64_t>(qy, INT32_MIN, INT32_MAX))};
    }
    Pixels got;
    bresenham_line(p, q, w, h, LineEnd::Closed, [&](int x, int y) { got.push_back({x, y}); });
    ASSERT_LE(got.size(), static_cast<std::size_t>(std::max(w, h)));
    const bool x_major = std::llabs(std::int64_t{q.x} - p.x) >= std::llabs(std::int64_t{q.y} - p.y);
    Pixels expected;
    const int umax = x_major ? w : h;
    const std::int64_t u0 = x_major ? p.x : p.y, v0 = x_major ? p.y : p.x, u1 = x_major ? q.x : q.y, v1 = x_major ? q.y : q.x;
    for (int u = 0; u < umax; ++u) {
      if (u < std::min(u0, u1) || u > std::max(u0, u1)) continue;
      const std::int64_t v = nearest_minor(u0, v0, u1, v1, u);
      const IPoint px = x_major ? IPoint{u, static_cast<int>(std::clamp<std::int64_t>(v, -1, 1 << 20))}
                                : IPoint{static_cast<int>(std::clamp<std::int64_t>(v, -1, 1 << 20)), u};
      if (px.x >= 0 && px.x < w && px.y >= 0 && px.y < h) expected.push_back(px);
    }
    ASSERT_EQ(show(sorted(got)), show(sorted(expected))) << p.x << "," << p.y << " -> " << q.x << "," << q.y;
    visible += !got.empty();
  }
  EXPECT_GT(visible, 150);
}

// ---- circles and ellipses ----

// Reference octant of the midpoint circle: for x = 0, 1, ... while x <= y: y is the largest integer with
// x^2 + (y - 1/2)^2 < r^2 (the midpoint criterion "d >= 0 steps y", evaluated directly).
Pixels reference_circle(int r) {
  std::set<IPoint> s;
  for (std::int64_t x = 0;; ++x) {
    std::int64_t y = r;
    while (y > 0 && 4 * x * x + (2 * y - 1) * (2 * y - 1) >= 4 * std::int64_t{r} * r) --y;
    if (x > y) break;
    for (int sx : {1, -1})
      for (int sy : {1, -1}) {
        s.insert({static_cast<int>(sx * x), static_cast<int>(sy * y)});
        s.insert({static_cast<int>(sx * y), static_cast<int>(sy * x)});
      }
  }
  return Pixels(s.begin(), s.end());
}

TEST(MidpointCircle, ExplicitPixelsForRadiusOneToThree) {
  EXPECT_EQ(show(circle_pixels(0)), show({{0, 0}}));
  EXPECT_EQ(show(circle_pixels(1)), show(sorted({{0, -1}, {-1, 0}, {1, 0}, {0, 1}})));
  EXPECT_EQ(show(circle_pixels(2)), show(sorted({{0, -2}, {0, 2}, {-2, 0}, {2, 0}, {1, 2}, {-1, 2}, {1, -2}, {-1, -2},
                                                  {2, 1}, {-2, 1}, {2, -1}, {-2, -1}})));
  EXPECT_EQ(show(circle_pixels(3)), show(sorted({{0, -3}, {0, 3}, {-3, 0}, {3, 0}, {1, 3}, {-1, 3}, {1, -3}, {-1, -3},
                                                  {3, 1}, {-3, 1}, {3, -1}, {-3, -1}, {2, 2}, {-2, 2}, {2, -2}, {-2, -2}})));
}

TEST(MidpointCircle, RadiusOneToTenProperties) {
  for (int r = 1; r <= 10; ++r) {
    const Pixels px = circle_pixels(r);
    EXPECT_EQ(show(px), show(reference_circle(r))) << "r=" << r;
    std::set<IPoint> s(px.begin(), px.end());
    EXPECT_EQ(s.size(), px.size()) << "each pixel once";
    for (IPoint p : px) {
      // Eight-way symmetry.
      for (IPoint m : {IPoint{-p.x, p.y}, IPoint{p.x, -p.y}, IPoint{p.y, p.x}, IPoint{-p.y, -p.x}}) EXPECT_TRUE(s.count(m));
      // Radially within half a pixel of the true circle.
      EXPECT_LE(std::fabs(std::hypot(p.x, p.y) - r), 0.5) << "r=" << r << " at " << p.x << "," << p.y;
    }
    // Count from the octant x >= 0, y >= x: axis and diagonal pixels have 4 images, the others 8.
    int expected = 0;
    for (IPoint p : px) {
      if (p.x < 0 || p.y < p.x) continue;
      expected += (p.x == 0 || p.x == p.y) ? 4 : 8;
    }
    EXPECT_EQ(static_cast<int>(px.size()), expected) << "r=" << r;
    // A closed 8-connected ring: every pixel has exactly two 8-neighbours in the set (r >= 2).
    if (r >= 2) {
      for (IPoint p : px) {
        int nb = 0;
        for (int dx = -1; dx <= 1; ++dx)
          for (int dy = -1; dy <= 1; ++dy) nb += (dx || dy) && s.count({p.x + dx, p.y + dy});
        EXPECT_GE(nb, 2) << "r=" << r;
      }
    }
  }
}

TEST(MidpointEllipse, FourWaySymmetryAndHalfPixelAccuracy) {
  for (int rx = 0; rx <= 12; ++rx) {
    for (int ry = 0; ry <= 12; ++ry) {
      const Pixels px = ellipse_pixels(rx, ry);
      std::set<IPoint> s(px.begin(), px.end());
      ASSERT_EQ(s.size(), px.size());
      EXPECT_TRUE(s.count({rx, 0}) && s.count({-rx, 0}) && s.count({0, ry}) && s.count({0, -ry})) << rx << "x" << ry;
      for (IPoint p : px) {
        EXPECT_TRUE(s.count({-p.x, p.y}) && s.count({p.x, -p.y}));
        // Within half a pixel of the true ellipse along x or along y.
        const double ey = ry * std::sqrt(std::max(0.0, 1.0 - double(p.x) * p.x / (double(rx) * rx)));
        const double ex = rx * std::sqrt(std::max(0.0, 1.0 - double(p.y) * p.y / (double(ry) * ry)));
        const bool ok = (rx > 0 && std::fabs(std::abs(p.y) - ey) <= 0.5 + 1e-9) ||
                        (ry > 0 && std::fabs(std::abs(p.x) - ex) <= 0.5 + 1e-9) || (rx == 0 && p.x == 0) ||
                        (ry == 0 && p.y == 0);
        EXPECT_TRUE(ok) << rx << "x" << ry << " at " << p.x << "," << p.y;
      }
      // 8-connected: every pixel has a neighbour (the ring never breaks).
      if (px.size() > 1) {
        for (IPoint p : px) {
          int nb = 0;
          for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy) nb += (dx || dy) && s.count({p.x + dx, p.y + dy});
          EXPECT_GE(nb, 1) << rx << "x" << ry << " at " << p.x << "," << p.y;
        }
      }
    }
  }
  // A circle drawn as an ellipse stays within the same half-pixel band as the midpoint circle.
  EXPECT_EQ(show(ellipse_pixels(3, 3)), show(circle_pixels(3)));
}

// ---- Wu ----

TEST(Wu, ColumnsSumToSpannedFractionAndReverseIsIdentical) {
  const int w = 40, h = 30;
  std::map<std::pair<int, int>, float> a, b;
  wu_line({2.25, 3.5}, {30.75, 20.1}, w, h, [&](int x, int y, float c) { a[{x, y}] += c; });
  wu_line({30.75, 20.1}, {2.25, 3.5}, w, h, [&](int x, int y, float c) { b[{x, y}] += c; });
  ASSERT_EQ(a.size(), b.size());
  for (auto& [k, v] : a) EXPECT_NEAR(v, b[k], 1e-6);
  std::map<int, double> column;
  double total = 0;
  for (auto& [k, v] : a) {
    column[k.first] += v;
    total += v;
  }
  EXPECT_NEAR(total, 30.75 - 2.25, 1e-4);  // x-major: total weight = x extent
  for (auto& [x, v] : column) {
    const double expect = std::min(x + 1.0, 30.75) - std::max(double(x), 2.25);
    EXPECT_NEAR(v, expect, 1e-5) << "column " << x;
  }
  // The split follows the distance to the pixel centres: at x = 10.5 the line is at y0 + m*(8.25).
  const double y = 3.5 + (20.1 - 3.5) / (30.75 - 2.25) * (10.5 - 2.25) - 0.5;
  const int j = static_cast<int>(std::floor(y));
  EXPECT_NEAR((a[{10, j}]), 1 - (y - j), 1e-5);
  EXPECT_NEAR((a[{10, j + 1}]), y - j, 1e-5);
}

TEST(Wu, FarEndpointsClipToSameCoverage) {
  // The same line seen through a small canvas and a big one: identical coverage on the small canvas.
  const Point p{-1500.3, -1480.2}, q{2600.7, 2560.4};
  std::map<std::pair<int, int>, float> small_c, big_c;
  wu_line(p, q, 64, 64, [&](int x, int y, float c) { small_c[{x, y}] += c; });
  wu_line(p, q, 4000, 4000, [&](int x, int y, float c) {
    if (x < 64 && y < 64) big_c[{x, y}] += c;
  });
  ASSERT_FALSE(small_c.empty());
  ASSERT_EQ(small_c.size(), big_c.size());
  for (auto& [k, v] : small_c) EXPECT_NEAR(v, big_c[k], 1e-6);
  int calls = 0;
  wu_line({-1e12, 10.5}, {1e12, 20.5}, 64, 64, [&](int, int, float) { ++calls; });
  EXPECT_GT(calls, 0);
  EXPECT_LE(calls, 2 * 66);
}

TEST(Lines, DrawIntoImageBlendsPremultiplied) {
  Image img(16, 16);
  img.clear(Color::transparent());
  draw_line(img, {1.5, 1.5}, {10.5, 4.5}, Color{1, 0, 0, 1}, LineAlgorithm::Bresenham);
  int lit = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) lit += img.pixel(x, y)[3] == 255;
  EXPECT_EQ(lit, 10);  // pixels (1,1) .. (10,4): one per column
  EXPECT_EQ(img.pixel(1, 1)[0], 255);
  EXPECT_EQ(img.pixel(10, 4)[3], 255);
  Image c(32, 32);
  c.clear(Color::transparent());
  draw_circle(c, {16, 16}, 5, Color{0, 0, 1, 0.5f});
  int n = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) n += c.pixel(x, y)[3] > 0;
  EXPECT_EQ(n, static_cast<int>(circle_pixels(5).size()));
  EXPECT_EQ(c.pixel(16, 11)[3], 128);
}

}  // namespace
}  // namespace vraster
