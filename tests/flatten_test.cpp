// Flattening: the stated error bound (both directions) on random and nasty curves, Wang's segment counts,
// clipped flattening of huge curves, and the error cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/reference.hpp"
#include "vraster/vraster.hpp"

namespace vraster::test {
namespace {

// A quadratic (3 points) or cubic (4 points) Bezier curve, evaluated here by de Casteljau.
struct Curve {
  std::vector<Point> p;

  Point at(double t) const {
    Point q[4];
    std::copy(p.begin(), p.end(), q);
    for (std::size_t n = p.size(); n > 1; --n)
      for (std::size_t i = 0; i + 1 < n; ++i) q[i] = lerp(q[i], q[i + 1], t);
    return q[0];
  }
  Curve mapped(const Affine& m) const {
    Curve c;
    for (Point q : p) c.p.push_back(m.apply(q));
    return c;
  }
  double scale() const {
    double s = 0;
    for (Point q : p) s = std::max({s, std::abs(q.x), std::abs(q.y)});
    return s;
  }
  std::string str() const {
    std::ostringstream s;
    s.precision(17);
    s << (p.size() == 3 ? "quad" : "cubic");
    for (Point q : p) s << " (" << q.x << ", " << q.y << ")";
    return s.str();
  }
};

Path path_of(const Curve& c) {
  Path path;
  path.move_to(c.p[0]);
  if (c.p.size() == 3) {
    path.quad_to(c.p[1], c.p[2]);
  } else {
    path.cubic_to(c.p[1], c.p[2], c.p[3]);
  }
  return path;
}

std::vector<Point> flatten_curve(const Curve& c, double tol, const Affine& m = Affine{}, const Rect* clip = nullptr) {
  Polylines lines;
  FlattenOptions o;
  o.tolerance = tol;
  o.clip = clip;
  flatten(path_of(c), m, o, lines);
  EXPECT_EQ(lines.contour_count(), 1u);
  const auto k = lines.contour(0);
  return {k.begin(), k.end()};
}

double point_segment_distance(Point q, Point a, Point b) {
  const Point d = b - a;
  const double len2 = dot(d, d);
  double t = len2 > 0 ? dot(q - a, d) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return length(q - lerp(a, b, t));
}

// Distance from q to the polyline; `hint` is a segment index to search around first (updated to the best one).
// The windowed search can only overestimate, so a full search confirms before a point is reported far.
double distance_to_polyline(Point q, const std::vector<Point>& line, std::size_t& hint) {
  if (line.size() == 1) return length(q - line[0]);
  const std::size_t segs = line.size() - 1;
  double best = std::numeric_limits<double>::infinity();
  const std::size_t lo = hint > 4 ? hint - 4 : 0, hi = std::min(segs, hint + 5);
  for (std::size_t i = lo; i < hi; ++i) {
    const double d = point_segment_distance(q, line[i], line[i + 1]);
    if (d < best) best = d, hint = i;
  }
  return best;
}

double full_distance_to_polyline(Point q, const std::vector<Point>& line) {
  double best = length(q - line[0]);
  for (std::size_t i = 0; i + 1 < line.size(); ++i) best = std::min(best, point_segment_distance(q, line[i], line[i + 1]));
  return best;
}

// Distance from q to the curve: refine (golden section over the neighbouring sample intervals) around the nearest
// dense sample, searched near `hint` first; when that is not close enough, around every sample that could be
// nearest (a local minimum within one sample spacing `h` of the best), so a crossing branch cannot hide the right
// one.
constexpr int kCurveSamples = 2000;

double distance_to_curve(Point q, const Curve& c, const std::vector<Point>& samples, double h, int& hint,
                         double enough) {
  auto refine = [&](int i) {
    double a = std::max(0.0, (i - 1.0) / kCurveSamples), b = std::min(1.0, (i + 1.0) / kCurveSamples);
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int it = 0; it < 40; ++it) {  // shrinks the interval by 0.618^40 ~ 4e-9
      const double t1 = b - g * (b - a), t2 = a + g * (b - a);
      if (length(c.at(t1) - q) < length(c.at(t2) - q)) {
        b = t2;
      } else {
        a = t1;
      }
    }
    return std::min(length(samples[i] - q), length(c.at(0.5 * (a + b)) - q));
  };
  int best_i = std::clamp(hint, 0, kCurveSamples);
  for (int i = std::max(0, hint - 40); i <= std::min(kCurveSamples, hint + 40); ++i) {
    if (length(samples[i] - q) < length(samples[best_i] - q)) best_i = i;
  }
  double d = refine(best_i);
  hint = best_i;
  if (d <= enough) return d;
  double best = std::numeric_limits<double>::infinity();
  for (const Point& s : samples) best = std::min(best, length(s - q));
  auto dist = [&](int i) { return length(samples[std::clamp(i, 0, kCurveSamples)] - q); };
  for (int i = 0; i <= kCurveSamples && d > enough; ++i) {
    const double di0 = dist(i);
    if (di0 <= best + h && di0 <= dist(i - 1) && di0 <= dist(i + 1)) {  // a local minimum that could be nearest
      const double di = refine(i);
      if (di < d) d = di, hint = i;
    }
  }
  return d;
}

// The error bound of flatten(): polyline ends = curve ends, every polyline point on the curve, every curve point
// (2000 parameters, plus the ends) within `tol` of the polyline.
::testing::AssertionResult within_bound(const Curve& device_curve, const std::vector<Point>& line, double tol) {
  const double eps = 1e-9 * (1 + device_curve.scale());
  if (line.size() < 2) return ::testing::AssertionFailure() << "polyline has " << line.size() << " points";
  if (length(line.front() - device_curve.p.front()) > eps || length(line.back() - device_curve.p.back()) > eps) {
    return ::testing::AssertionFailure() << "polyline does not start and end at the curve's end points";
  }
  std::vector<Point> samples;
  for (int i = 0; i <= kCurveSamples; ++i) samples.push_back(device_curve.at(double(i) / kCurveSamples));
  double h = 0;
  for (int i = 0; i < kCurveSamples; ++i) h = std::max(h, length(samples[i + 1] - samples[i]));
  int curve_hint = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const double d = distance_to_curve(line[i], device_curve, samples, h, curve_hint, eps);
    if (d > eps) {
      return ::testing::AssertionFailure() << "polyline point " << i << " (" << line[i].x << ", " << line[i].y
                                           << ") is " << d << " off the curve";
    }
  }
  std::size_t hint = 0;
  for (int i = 0; i <= kCurveSamples; ++i) {
    const double t = double(i) / kCurveSamples;
    const Point q = samples[i];
    double d = distance_to_polyline(q, line, hint);
    if (d > tol) d = full_distance_to_polyline(q, line);
    if (d > tol * (1 + 1e-9) + eps) {
      return ::testing::AssertionFailure() << "curve point t=" << t << " (" << q.x << ", " << q.y << ") is " << d
                                           << " from the polyline (tolerance " << tol << ", " << line.size() - 1
                                           << " segments)";
    }
  }
  return ::testing::AssertionSuccess();
}

// Wang's formula, written out: n = ceil(sqrt(k * M / tol)), M the largest second difference, k = 1/4 or 3/4.
int expected_segments(const Curve& c, double tol) {
  const auto& p = c.p;
  double m = length(p[0] - p[1] * 2 + p[2]);
  if (p.size() == 4) m = std::max(m, length(p[1] - p[2] * 2 + p[3]));
  const double k = p.size() == 3 ? 0.25 : 0.75;
  return std::max(1, static_cast<int>(std::ceil(std::sqrt(k * m / tol))));
}

Curve random_curve(std::mt19937& rng, int degree, double extent) {
  std::uniform_real_distribution<double> u(-extent, extent);
  Curve c;
  for (int i = 0; i <= degree; ++i) c.p.push_back({u(rng), u(rng)});
  return c;
}

const double kTolerances[] = {0.01, 0.03, 0.1, 0.3, 1.0};

// ---------------------------------------------------------------------------------------------------------------

TEST(Flatten, RandomCurvesStayWithinToleranceBothWays) {
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    for (int degree : {2, 3}) {
      const Curve c = random_curve(rng, degree, seed % 3 == 0 ? 20 : 200);
      for (double tol : kTolerances) {
        const auto line = flatten_curve(c, tol);
        EXPECT_TRUE(within_bound(c, line, tol)) << "seed " << seed << ", tolerance " << tol << ": " << c.str();
      }
    }
  }
}

TEST(Flatten, NastyCurvesStayWithinToleranceBothWays) {
  const Curve nasty[] = {
      {{{0, 10}, {-10, 10}, {180, 10}, {60, 10}}},       // collinear, doubles back twice
      {{{0, 0}, {100, 0}, {-50, 0}, {50, 0}}},           // collinear control points that double back
      {{{0, 0}, {100, 100}, {0, 100}, {100, 0}}},        // a cusp at t = 0.5
      {{{0, 0}, {150, 100}, {-50, 100}, {100, 0}}},      // a loop
      {{{0, 0}, {100, 100}, {-100, 100}, {0, 0}}},       // a closed loop
      {{{0, 0}, {0, 0}, {100, 100}, {100, 100}}},        // coincident control points at both ends
      {{{0, 0}, {0, 0}, {0, 0}, {50, 70}}},              // three coincident points
      {{{5, 5}, {5, 5}, {5, 5}, {5, 5}}},                // a single point
      {{{0, 0}, {100, 0}, {50, 0}}},                     // quadratic doubling back
      {{{0, 0}, {300, 1}, {0, 2}}},                      // quadratic, very sharp turn
      {{{0, 0}, {0, 0}, {0, 0}}},                        // quadratic point
      {{{1e-3, 0}, {0, 1e-3}, {-1e-3, 0}, {0, -1e-3}}},  // tiny
  };
  for (const Curve& c : nasty) {
    for (double tol : kTolerances) {
      EXPECT_TRUE(within_bound(c, flatten_curve(c, tol), tol)) << "tolerance " << tol << ": " << c.str();
    }
  }
}

TEST(Flatten, ToleranceIsMeasuredInDeviceSpace) {
  std::mt19937 rng(5);
  const Affine m = Affine::translate(30, -7) * Affine::rotate(33) * Affine::scale(7, 2.5) * Affine::skew_x(20);
  for (int i = 0; i < 30; ++i) {
    const Curve c = random_curve(rng, 2 + i % 2, 30);
    for (double tol : {0.02, 0.5}) {
      const auto line = flatten_curve(c, tol, m);
      EXPECT_TRUE(within_bound(c.mapped(m), line, tol)) << "curve " << i << ", tolerance " << tol << ": " << c.str();
    }
  }
}

TEST(Flatten, SegmentCountsFollowWangsFormula) {
  std::mt19937 rng(11);
  for (int i = 0; i < 100; ++i) {
    const Curve c = random_curve(rng, 2 + i % 2, i < 50 ? 100 : 3);
    for (double tol : kTolerances) {
      const int n = expected_segments(c, tol);
      const auto line = flatten_curve(c, tol);
      EXPECT_EQ(static_cast<int>(line.size()) - 1, n) << c.str() << ", tolerance " << tol;
      const int reported = c.p.size() == 3 ? wang_segments_quad(c.p[0], c.p[1], c.p[2], tol)
                                           : wang_segments_cubic(c.p[0], c.p[1], c.p[2], c.p[3], tol);
      EXPECT_EQ(reported, n) << c.str();
    }
  }
  // Hand-checked values: quad (0,0) (50,100) (100,0): M = |(0,-200)| = 200, n = ceil(sqrt(50 / 0.5)) = 10.
  EXPECT_EQ(wang_segments_quad({0, 0}, {50, 100}, {100, 0}, 0.5), 10);
  // Cubic (0,0) (0,40) (40,40) (40,0): M = 40 * sqrt(2), n = ceil(sqrt(0.75 * 56.57 / 0.1)) = ceil(20.6) = 21.
  EXPECT_EQ(wang_segments_cubic({0, 0}, {0, 40}, {40, 40}, {40, 0}, 0.1), 21);
  // Straight lines (zero second differences) need one segment.
  EXPECT_EQ(wang_segments_cubic({0, 0}, {1, 1}, {2, 2}, {3, 3}, 0.1), 1);
  EXPECT_EQ(flatten_curve({{{0, 0}, {1, 1}, {2, 2}, {3, 3}}}, 0.01).size(), 2u);
  // Without a clip, the count is capped at 2^20.
  EXPECT_EQ(wang_segments_cubic({0, 0}, {1e30, 0}, {0, 0}, {1, 0}, 0.1), 1 << 20);
}

TEST(Flatten, SegmentCountsAreExactAtEveryStepAcrossTheSmallCountTable) {
  // Quad (0,0) (0,0) (M,0) at tolerance 0.25: k * M / tolerance = M, so n = ceil(sqrt(M)). At M = n^2 the count is
  // exactly n, a hair above it n + 1, a hair below it n; on both sides of the switch from the table (n <= 16) to
  // square roots.
  for (int n = 1; n <= 24; ++n) {
    const double m = static_cast<double>(n) * n;
    EXPECT_EQ(wang_segments_quad({0, 0}, {0, 0}, {m, 0}, 0.25), n) << n;
    EXPECT_EQ(wang_segments_quad({0, 0}, {0, 0}, {m * (1 + 1e-9), 0}, 0.25), n + 1) << n;
    if (n > 1) {
      EXPECT_EQ(wang_segments_quad({0, 0}, {0, 0}, {m * (1 - 1e-9), 0}, 0.25), n) << n;
    }
  }
  // A straight curve needs one segment even at a tolerance so small that (k / tolerance)^2 overflows.
  EXPECT_EQ(wang_segments_quad({0, 0}, {1, 1}, {2, 2}, 1e-300), 1);
  EXPECT_EQ(wang_segments_cubic({0, 0}, {1, 1}, {2, 2}, {3, 3}, 1e-300), 1);
}

TEST(Flatten, HugeCurveWithAClipStaysSmallAndAccurateInsideTheClip) {
  const Rect clip{0, 0, 100, 100};
  for (double s : {1e6, 1e9, 1e12}) {
    // An S through the clip: B(0.5) = (50, 50), control points s away.
    const Curve huge{{{50 - s, 50}, {50 - s, 50 + s}, {50 + s, 50 - s}, {50 + s, 50}}};
    const auto line = flatten_curve(huge, 0.1, Affine{}, &clip);
    EXPECT_LT(line.size(), 10000u) << "span " << s;
    // Inside the clip, the bound holds: sample the parameters near 0.5 that map into it.
    int inside = 0;
    for (int i = -5000; i <= 5000; ++i) {
      const Point q = huge.at(0.5 + i / 5000.0 * 200 / s);
      if (q.x < clip.x0 || q.x > clip.x1 || q.y < clip.y0 || q.y > clip.y1) continue;
      ++inside;
      // Evaluating a curve of size s in double is itself off by about s * 1e-16.
      ASSERT_LE(full_distance_to_polyline(q, line), 0.1 + s * 1e-15) << "span " << s << ", point " << i;
    }
    EXPECT_GT(inside, 500) << "span " << s;
  }
  // A huge quadratic, and a cubic far away from the clip.
  const Curve huge_quad{{{-1e12, 60}, {3e12, 1e12}, {1e12, -2e12}}};
  EXPECT_LT(flatten_curve(huge_quad, 0.1, Affine{}, &clip).size(), 10000u);
  const Curve far{{{-5e11, 50}, {-1e11, -3e11}, {1e11, 4e11}, {5e11, 50}}};
  EXPECT_LT(flatten_curve(far, 0.1, Affine{}, &clip).size(), 10000u);

  // A curve 100 times the clip's size: fewer points than without the clip, and within the bound inside the clip.
  const Curve big{{{-5000, 20}, {-2000, 300}, {3000, -200}, {6000, 80}}};
  const auto big_line = flatten_curve(big, 0.05, Affine{}, &clip);
  const auto full_line = flatten_curve(big, 0.05);
  EXPECT_LT(big_line.size(), full_line.size());
  std::size_t hint = 0;
  int inside = 0;
  for (int i = 0; i <= 200000; ++i) {
    const Point q = big.at(i / 200000.0);
    if (q.x < clip.x0 || q.x > clip.x1 || q.y < clip.y0 || q.y > clip.y1) continue;
    ++inside;
    double d = distance_to_polyline(q, big_line, hint);
    if (d > 0.05) d = full_distance_to_polyline(q, big_line);
    ASSERT_LE(d, 0.05 + 1e-9) << "t=" << i / 200000.0;
  }
  EXPECT_GT(inside, 100);
}

TEST(Flatten, CurveWhoseHullMissesTheClipBecomesItsChord) {
  const Rect clip{0, 0, 100, 100};
  const Curve outside{{{-50, -50}, {-40, -80}, {-20, -80}, {-10, -50}}};
  const auto line = flatten_curve(outside, 0.1, Affine{}, &clip);
  ASSERT_EQ(line.size(), 2u);
  EXPECT_EQ(line[0], (Point{-50, -50}));
  EXPECT_EQ(line[1], (Point{-10, -50}));
}

TEST(Flatten, ContoursKeepTheirOrderEndsAndClosedFlags) {
  Path p;
  p.move_to(0, 0).line_to(10, 0).line_to(10, 10).close().move_to(20, 20).line_to(30, 30);
  Polylines lines;
  flatten(p, Affine::translate(1, 2), FlattenOptions{}, lines);
  ASSERT_EQ(lines.contour_count(), 2u);
  const std::vector<Point> first(lines.contour(0).begin(), lines.contour(0).end());
  const std::vector<Point> second(lines.contour(1).begin(), lines.contour(1).end());
  EXPECT_EQ(first, (std::vector<Point>{{1, 2}, {11, 2}, {11, 12}}));
  EXPECT_EQ(second, (std::vector<Point>{{21, 22}, {31, 32}}));
  EXPECT_EQ(lines.closed, (std::vector<std::uint8_t>{1, 0}));
  // Appends to what is already there.
  flatten(p, Affine{}, FlattenOptions{}, lines);
  EXPECT_EQ(lines.contour_count(), 4u);
}

TEST(Flatten, NonFiniteTransformResultOrBadToleranceThrows) {
  Path p;
  p.move_to(1, 1).line_to(1e300, 0);
  Polylines lines;
  EXPECT_THROW(flatten(p, Affine::scale(1e10), FlattenOptions{}, lines), Error);
  Path q;
  q.move_to(0, 0).cubic_to({1e300, 0}, {0, 1}, {1, 1});  // only a control point overflows
  EXPECT_THROW(flatten(q, Affine::scale(1e10), FlattenOptions{}, lines), Error);
  EXPECT_THROW(flatten(q, Affine{1, 0, 0, std::numeric_limits<double>::quiet_NaN(), 0, 0}, FlattenOptions{}, lines),
               Error);
  for (double tol : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    FlattenOptions o;
    o.tolerance = tol;
    EXPECT_THROW(flatten(q, Affine{}, o, lines), Error) << "tolerance " << tol;
  }
}

}  // namespace
}  // namespace vraster::test
