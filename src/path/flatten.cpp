// Flattening: path (user space) -> transform -> polylines (device space) with a bounded error.
#include "vraster/flatten.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "vraster/error.hpp"

namespace vraster {
namespace {

constexpr int kMaxSegmentsPerCurve = 1 << 20;
// Curves bigger than this many clip sizes are halved before flattening, so Wang's count stays small.
constexpr double kSplitFactor = 4.0;
constexpr int kMaxSplitDepth = 48;

// Wang's count n = ceil(sqrt(k * M / tolerance)) with M = sqrt(dot(d, d)) is the smallest n >= 1 with
// n^4 >= q = dot(d, d) * factor, factor = (k / tolerance)^2, i.e. with n^2 >= ceil(sqrt(q)) (n^2 is an integer).
// Glyph-sized curves need at most 16 segments: for those one square root and a table replace two dependent
// square roots and a rounding (the segment loop waits on n).
constexpr int kSmallCount = 16;
constexpr double kSmallLimit = 65536.0;  // 16^4

// Smallest n >= 1 with n * n >= m, for m in [0, 256].
constexpr auto kCeilSqrt = [] {
  std::array<std::uint8_t, kSmallCount * kSmallCount + 1> r{};
  for (int m = 0; m <= kSmallCount * kSmallCount; ++m) {
    int n = 1;
    while (n * n < m) ++n;
    r[static_cast<std::size_t>(m)] = static_cast<std::uint8_t>(n);
  }
  return r;
}();

double wang_factor(double k, double tolerance) { return (k / tolerance) * (k / tolerance); }

int segments_for(double squared_difference, double factor) {
  const double q = squared_difference * factor;
  if (q <= kSmallLimit) {
    const double r = std::sqrt(q);  // <= 256
    const int m = static_cast<int>(r);
    return kCeilSqrt[static_cast<std::size_t>(m + (m < r ? 1 : 0))];
  }
  if (squared_difference == 0) return 1;  // a straight curve, even when factor is infinite (tiny tolerance)
  const double x = std::sqrt(std::sqrt(q));
  if (!(x < kMaxSegmentsPerCurve)) return kMaxSegmentsPerCurve;  // also catches NaN and infinity
  // Round up without std::ceil (a library call on baseline x86-64).
  const int n = static_cast<int>(x);
  return n + (n < x ? 1 : 0);
}

// 1 / n for the small counts, so the common case needs no division before its loop (same values as 1.0 / n).
constexpr auto kInverseCounts = [] {
  std::array<double, kSmallCount + 1> r{};
  for (int n = 1; n <= kSmallCount; ++n) r[n] = 1.0 / n;
  return r;
}();

inline double inverse_count(int n) { return n <= kSmallCount ? kInverseCounts[n] : 1.0 / n; }

int quad_segments(Point p0, Point p1, Point p2, double factor) {
  const Point d = p0 - p1 * 2 + p2;
  return segments_for(dot(d, d), factor);
}

int cubic_segments(Point p0, Point p1, Point p2, Point p3, double factor) {
  const Point d1 = p0 - p1 * 2 + p2, d2 = p1 - p2 * 2 + p3;
  return segments_for(std::max(dot(d1, d1), dot(d2, d2)), factor);
}

Rect control_box(const Point* p, int count) {
  Rect r = Rect::from_point(p[0]);
  for (int i = 1; i < count; ++i) r.include(p[i]);
  return r;
}

class Flattener {
 public:
  Flattener(const FlattenOptions& options, Polylines& out)
      : options_(options),
        out_(out),
        quad_factor_(wang_factor(0.25, options.tolerance)),
        cubic_factor_(wang_factor(0.75, options.tolerance)) {
    if (options.clip) {
      // One pixel of margin: nothing within it can change coverage inside the clip, and it keeps round-off
      // at the border from mattering.
      clip_ = Rect{options.clip->x0 - 1, options.clip->y0 - 1, options.clip->x1 + 1, options.clip->y1 + 1};
      clip_size_ = std::max(clip_.width(), clip_.height());
    }
  }

  void move(Point p) {
    finish_contour(false);
    out_.points.push_back(p);
    open_ = true;
  }
  void line(Point p) { out_.points.push_back(p); }
  void close() { finish_contour(true); }
  void finish() { finish_contour(false); }

  // The curve calls are inlined into flatten()'s verb loop: as out-of-line calls, GCC packed the Point arguments
  // through the stack and every curve paid a store-forwarding stall. The clipping branch stays out of line.
  [[gnu::always_inline]] void quad(Point p0, Point p1, Point p2) {
    if (options_.clip) [[unlikely]] return quad_clipped(p0, p1, p2, 0);
    emit_quad(p0, p1, p2);
  }

  [[gnu::always_inline]] void cubic(Point p0, Point p1, Point p2, Point p3) {
    if (options_.clip) [[unlikely]] return cubic_clipped(p0, p1, p2, p3, 0);
    emit_cubic(p0, p1, p2, p3);
  }

 private:
  [[gnu::noinline]] void quad_clipped(Point p0, Point p1, Point p2, int depth) {
    const Point pts[3] = {p0, p1, p2};
    const Rect box = control_box(pts, 3);
    if (!box.intersects(clip_)) return line(p2);
    if (depth < kMaxSplitDepth && std::max(box.width(), box.height()) > kSplitFactor * clip_size_) {
      const Point a = lerp(p0, p1, 0.5), b = lerp(p1, p2, 0.5), m = lerp(a, b, 0.5);
      quad_clipped(p0, a, m, depth + 1);
      quad_clipped(m, b, p2, depth + 1);
      return;
    }
    emit_quad(p0, p1, p2);
  }

  [[gnu::noinline]] void cubic_clipped(Point p0, Point p1, Point p2, Point p3, int depth) {
    const Point pts[4] = {p0, p1, p2, p3};
    const Rect box = control_box(pts, 4);
    if (!box.intersects(clip_)) return line(p3);
    if (depth < kMaxSplitDepth && std::max(box.width(), box.height()) > kSplitFactor * clip_size_) {
      const Point ab = lerp(p0, p1, 0.5), bc = lerp(p1, p2, 0.5), cd = lerp(p2, p3, 0.5);
      const Point abc = lerp(ab, bc, 0.5), bcd = lerp(bc, cd, 0.5), m = lerp(abc, bcd, 0.5);
      cubic_clipped(p0, ab, abc, m, depth + 1);
      cubic_clipped(m, bcd, cd, p3, depth + 1);
      return;
    }
    emit_cubic(p0, p1, p2, p3);
  }

  [[gnu::always_inline]] void emit_quad(Point p0, Point p1, Point p2) {
    const int n = quad_segments(p0, p1, p2, quad_factor_);
    if (out_.points.size() + static_cast<std::size_t>(n) > limit_) [[unlikely]] throw_too_many_points();
    // Power basis: B(t) = (a t + b) t + p0.
    const Point a = p0 - p1 * 2 + p2, b = (p1 - p0) * 2;
    const double step = inverse_count(n);
    for (int i = 1; i < n; ++i) {
      const double t = i * step;
      out_.points.push_back({(a.x * t + b.x) * t + p0.x, (a.y * t + b.y) * t + p0.y});
    }
    line(p2);
  }

  [[gnu::always_inline]] void emit_cubic(Point p0, Point p1, Point p2, Point p3) {
    const int n = cubic_segments(p0, p1, p2, p3, cubic_factor_);
    if (out_.points.size() + static_cast<std::size_t>(n) > limit_) [[unlikely]] throw_too_many_points();
    // Power basis: B(t) = ((a t + b) t + c) t + p0.
    const Point a = p3 - p0 + (p1 - p2) * 3, b = (p0 - p1 * 2 + p2) * 3, c = (p1 - p0) * 3;
    const double step = inverse_count(n);
    for (int i = 1; i < n; ++i) {
      const double t = i * step;
      out_.points.push_back({((a.x * t + b.x) * t + c.x) * t + p0.x, ((a.y * t + b.y) * t + c.y) * t + p0.y});
    }
    line(p3);
  }

  void finish_contour(bool closed) {
    if (!open_) return;
    out_.ends.push_back(static_cast<std::uint32_t>(out_.points.size()));
    out_.closed.push_back(closed ? 1 : 0);
    open_ = false;
  }

  [[noreturn, gnu::cold, gnu::noinline]] void throw_too_many_points() const {
    throw Error("flatten: the path needs more than " + std::to_string(kMaxFlattenedPoints) +
                " line segments at tolerance " + std::to_string(options_.tolerance) +
                " px (the limit per path); use a larger tolerance");
  }

  const FlattenOptions& options_;
  Polylines& out_;
  std::size_t limit_ = out_.points.size() + kMaxFlattenedPoints;  // the points this call may add
  Rect clip_{};
  double clip_size_ = 0;
  double quad_factor_, cubic_factor_;
  bool open_ = false;
};

[[noreturn, gnu::cold]] void throw_not_finite() {
  throw Error("flatten: a coordinate is not finite after the transform");
}

inline Point device(const Affine& m, Point p) {
  const Point q = m.apply(p);
  if (!is_finite(q)) [[unlikely]] throw_not_finite();
  return q;
}

// The device-space box of the path's control points (the transformed corners of its user-space box contain them).
Rect device_box(const Path& path, const Affine& m) {
  const Rect b = path.control_bounds();
  Rect r = Rect::from_point(m.apply({b.x0, b.y0}));
  r.include(m.apply({b.x1, b.y0}));
  r.include(m.apply({b.x0, b.y1}));
  r.include(m.apply({b.x1, b.y1}));
  return r;
}

}  // namespace

int wang_segments_quad(Point p0, Point p1, Point p2, double tolerance) {
  return quad_segments(p0, p1, p2, wang_factor(0.25, tolerance));
}

int wang_segments_cubic(Point p0, Point p1, Point p2, Point p3, double tolerance) {
  return cubic_segments(p0, p1, p2, p3, wang_factor(0.75, tolerance));
}

void flatten(const Path& path, const Affine& transform, const FlattenOptions& options, Polylines& out) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) {
    throw Error("flatten: tolerance must be a positive number");
  }
  if (!transform.is_finite()) throw Error("flatten: transform has a non-finite entry");
  if (path.empty()) return;
  // Do only the clipping work the path needs: when all of it lies inside the clip, no curve needs the test.
  FlattenOptions effective = options;
  if (options.clip) {
    const Rect box = device_box(path, transform);
    if (box.x0 >= options.clip->x0 && box.y0 >= options.clip->y0 && box.x1 <= options.clip->x1 &&
        box.y1 <= options.clip->y1) {
      effective.clip = nullptr;
    }
  }
  Flattener f(effective, out);
  const auto pts = path.points();
  std::size_t i = 0;
  Point last{};
  for (Verb v : path.verbs()) {
    switch (v) {
      case Verb::Move:
        last = device(transform, pts[i++]);
        f.move(last);
        break;
      case Verb::Line:
        last = device(transform, pts[i++]);
        f.line(last);
        break;
      case Verb::Quad: {
        const Point c = device(transform, pts[i]), p = device(transform, pts[i + 1]);
        f.quad(last, c, p);
        last = p;
        i += 2;
        break;
      }
      case Verb::Cubic: {
        const Point c1 = device(transform, pts[i]), c2 = device(transform, pts[i + 1]);
        const Point p = device(transform, pts[i + 2]);
        f.cubic(last, c1, c2, p);
        last = p;
        i += 3;
        break;
      }
      case Verb::Close: f.close(); break;
    }
  }
  f.finish();
}

}  // namespace vraster
