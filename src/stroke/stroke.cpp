// The geometric stroker: Path + StrokeStyle -> Path whose non-zero fill is the stroke.
//
//   1. flatten_for_stroke   contours -> polylines (curves at tolerance/2; vertices inside curves are "smooth")
//   2. dash_polylines       polylines -> dashes (pattern runs on across segments and curves, restarts per
//                           subpath, and joins the last dash of a closed subpath to the first)
//   3. stroke_polylines     every piece -> one closed outline (open piece: left side, end cap, right side
//                           backwards, start cap) or two (closed piece: left loop, right loop reversed)
//
// Why the result is within `tolerance` of the exact stroke: the polyline is within tolerance/2 of the curve,
// and at smooth vertices (inside a curve) the outer side gets a round join, so the outer boundary there is the
// offset of the polyline by exactly width/2 (segments plus arcs), within tolerance/2 of the curve's offset, up
// to the chord error of the arcs (<= tolerance/2). A cusp thus gets its half disc. Round joins and caps are pie
// slices on the outer side, as in Cairo and Skia. Inner sides use the exact intersection of the two offset lines where it lies
// within the first half of both segments, else the classic pivot through the vertex (a'-> P -> b'), whose
// small loops all turn the same way as the outline, so non-zero filling gives the union. Every outline has the
// same orientation (negative shoelace area), so overlapping pieces (dashes, dots) never cancel.
#include "vraster/stroke.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vraster/error.hpp"
#include "vraster/flatten.hpp"
#include "stroke/internal.hpp"

namespace vraster {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxCurveSegments = 1 << 14;
constexpr int kMaxArcSegments = 1 << 12;
// Curves get extra points at parameter kTangentStep/n from each end, so the end segments point along the true
// tangents (a miter joined to a chord instead would be off by up to half a segment's turn, times its length).
constexpr double kTangentStep = 1e-3;

Point normal_of(Point d) { return {-d.y, d.x}; }
Point rotate(Point v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {v.x * c - v.y * s, v.x * s + v.y * c};
}

// Number of chords for an arc of radius r and angle |sweep| with chord error <= tol.
int arc_segments(double r, double sweep, double tol) {
  sweep = std::fabs(sweep);
  if (!(sweep <= 2 * kPi)) return sweep > 2 * kPi ? kMaxArcSegments : 1;  // NaN sweeps come from overflowed input
  if (!(r > tol)) return std::max(1, static_cast<int>(std::ceil(sweep / (kPi / 2))));
  const double step = 2 * std::acos(1 - tol / r);
  const double n = std::ceil(sweep / step);
  return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(kMaxArcSegments)));
}

// Appends the arc around c from direction `from` (unit) by `sweep` radians, excluding the start point,
// including the end point.
void append_arc(std::vector<Point>& out, Point c, double r, Point from, double sweep, double tol) {
  const int n = arc_segments(r, sweep, tol);
  // Incremental rotation by one step (one sincos per arc); the end point is computed directly.
  const double step = sweep / n, cs = std::cos(step), sn = std::sin(step);
  Point v = from;
  for (int k = 1; k < n; ++k) {
    v = {v.x * cs - v.y * sn, v.x * sn + v.y * cs};
    out.push_back(c + v * r);
  }
  out.push_back(c + rotate(from, sweep) * r);
}

class Flattener {
 public:
  Flattener(double tol, const Rect* clip, std::vector<StrokePolyline>& out) : tol_(tol), clip_(clip), out_(out) {}

  void move(Point p) {
    flush(false);
    cur_.points.assign(1, p);
    cur_.corner.assign(1, 1);
    open_ = true;
    drew_ = false;
  }
  void line(Point p) {
    add(p, 1);
    drew_ = true;
  }
  void quad(Point p0, Point c, Point p) {
    if (hull_misses(std::initializer_list<Point>{p0, c, p})) return line(p);
    const int n = std::min(wang_segments_quad(p0, c, p, tol_), kMaxCurveSegments);
    auto at = [&](double t) {
      const double u = 1 - t;
      return p0 * (u * u) + c * (2 * u * t) + p * (t * t);
    };
    const double eps = kTangentStep / n;
    add(at(eps), 0);  // a tiny first and last segment: joins and caps see the true end tangents
    for (int i = 1; i < n; ++i) add(at(static_cast<double>(i) / n), 0);
    add(at(1 - eps), 0);
    line(p);
  }
  void cubic(Point p0, Point c1, Point c2, Point p) {
    if (hull_misses(std::initializer_list<Point>{p0, c1, c2, p})) return line(p);
    const int n = std::min(wang_segments_cubic(p0, c1, c2, p, tol_), kMaxCurveSegments);
    auto at = [&](double t) {
      const double u = 1 - t;
      return p0 * (u * u * u) + c1 * (3 * u * u * t) + c2 * (3 * u * t * t) + p * (t * t * t);
    };
    const double eps = kTangentStep / n;
    add(at(eps), 0);
    for (int i = 1; i < n; ++i) add(at(static_cast<double>(i) / n), 0);
    add(at(1 - eps), 0);
    line(p);
  }
  void close() {
    drew_ = true;
    flush(true);
  }
  void flush(bool closed) {
    if (!open_) return;
    open_ = false;
    if (!drew_) return;  // a lone move draws nothing
    StrokePolyline& c = cur_;
    // A closing point equal to the start up to round-off (arcs end there after trigonometry) is the start.
    const auto nearly = [](Point a, Point b) {
      const double scale = 1e-9 * std::max({1.0, std::fabs(a.x), std::fabs(a.y)});
      return std::fabs(a.x - b.x) <= scale && std::fabs(a.y - b.y) <= scale;
    };
    if (closed && c.points.size() >= 2 && nearly(c.points.back(), c.points.front())) {
      c.points.pop_back();
      c.corner.pop_back();
    }
    if (c.points.size() == 1) {
      c.closed = false;
      c.dot_direction = {1, 0};
    } else {
      c.closed = closed;
    }
    c.corner.front() = 1;
    out_.push_back(c);
  }

 private:
  void add(Point p, std::uint8_t corner) {
    if (cur_.points.back() == p) {
      cur_.corner.back() |= corner;
      return;
    }
    cur_.points.push_back(p);
    cur_.corner.push_back(corner);
  }
  bool hull_misses(std::initializer_list<Point> pts) const {
    if (!clip_) return false;
    Rect box = Rect::from_point(*pts.begin());
    for (Point q : pts) box.include(q);
    // Inclusive test (a hull touching the clip edge still counts as visible).
    return box.x1 < clip_->x0 || box.x0 > clip_->x1 || box.y1 < clip_->y0 || box.y0 > clip_->y1;
  }

  double tol_;
  const Rect* clip_;
  std::vector<StrokePolyline>& out_;
  StrokePolyline cur_;
  bool open_ = false;
  bool drew_ = false;
};

void flatten_impl(const Path& path, double tolerance, const Rect* clip, std::vector<StrokePolyline>& out) {
  Flattener f(tolerance, clip, out);
  const auto pts = path.points();
  std::size_t i = 0;
  Point last{};
  for (Verb v : path.verbs()) {
    switch (v) {
      case Verb::Move: last = pts[i++]; f.move(last); break;
      case Verb::Line: last = pts[i++]; f.line(last); break;
      case Verb::Quad: f.quad(last, pts[i], pts[i + 1]); last = pts[i + 1]; i += 2; break;
      case Verb::Cubic: f.cubic(last, pts[i], pts[i + 1], pts[i + 2]); last = pts[i + 2]; i += 3; break;
      case Verb::Close: f.close(); break;
    }
  }
  f.flush(false);
}

// ---- step 3: outlining ----

[[noreturn, gnu::cold]] void throw_outline_too_big() {
  throw Error("stroke: the outline needs more than " + std::to_string(kMaxStrokeOutlinePoints) +
              " points (the limit per stroke); the stroke is far wider than its curves are flat at this tolerance");
}

class Outliner {
 public:
  Outliner(const StrokeStyle& style, double tolerance, Path& out)
      : hw_(style.width / 2), style_(style), cap_(style.cap), tol_(tolerance / 2), out_(out) {
    miter_limit_ = std::max(1.0, std::isfinite(style.miter_limit) ? style.miter_limit : 1.0);
  }

  /// Bounded work: throws once the outline (emitted plus being built) passes kMaxStrokeOutlinePoints.
  void check_budget() const {
    if (emitted_ + left_.size() + right_.size() + contour_.size() > kMaxStrokeOutlinePoints) throw_outline_too_big();
  }

  void piece(const StrokePolyline& pl) {
    if (pl.points.empty()) return;
    if (pl.points.size() == 1) return make_dot(pl.points[0], pl.dot_direction);
    if (pl.closed && pl.points.size() == 2) {
      // A -> B -> A: both joins are 180-degree reversals, whose shape is a half disc (round) or nothing (miter
      // over any limit, bevel). Outlined as the open segment with those as caps: one contour covering the
      // region once (two loops would cover it twice, doubling the coverage of edge pixels).
      StrokePolyline open = pl;
      open.closed = false;
      const LineCap saved = cap_;
      cap_ = style_.join == LineJoin::Round ? LineCap::Round : LineCap::Butt;
      piece(open);
      cap_ = saved;
      return;
    }
    const std::size_t n = pl.points.size();
    const std::size_t segs = pl.closed ? n : n - 1;
    dirs_.resize(segs);
    lens_.resize(segs);
    for (std::size_t i = 0; i < segs; ++i) {
      const Point a = pl.points[i], b = pl.points[(i + 1) % n];
      Point d = b - a;
      // Far-apart finite points (|x| near 1e308) overflow the difference or its square: halve both first.
      const bool halved = !is_finite(d) || !std::isfinite(d.x * d.x + d.y * d.y);
      if (halved) d = b * 0.5 - a * 0.5;
      const double len = std::hypot(d.x, d.y);
      lens_[i] = halved ? 2 * len : len;
      dirs_[i] = len > 0 && std::isfinite(len) ? d * (1 / len) : Point{1, 0};
    }
    left_.clear();
    right_.clear();
    if (pl.closed) {
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t prev = (j + segs - 1) % segs;
        join(pl.points[j], prev, j, pl.corner[j] != 0);
        check_budget();
      }
      emit(left_);
      std::reverse(right_.begin(), right_.end());
      emit(right_);
      return;
    }
    const Point n0 = normal_of(dirs_[0]);
    left_.push_back(pl.points[0] + n0 * hw_);
    right_.push_back(pl.points[0] - n0 * hw_);
    for (std::size_t j = 1; j + 1 < n; ++j) {
      join(pl.points[j], j - 1, j, pl.corner[j] != 0);
      check_budget();
    }
    const Point pe = pl.points[n - 1], de = dirs_[segs - 1], ne = normal_of(de);
    left_.push_back(pe + ne * hw_);
    right_.push_back(pe - ne * hw_);
    // Outline: left side forwards, end cap, right side backwards, start cap.
    contour_.assign(left_.begin(), left_.end());
    cap(pe, de, contour_);
    contour_.insert(contour_.end(), right_.rbegin(), right_.rend());
    cap(pl.points[0], dirs_[0] * -1.0, contour_);
    emit(contour_);
  }

 private:
  // Appends the cap at p facing direction d, from p + n hw (already in out) to p - n hw (the next point added).
  void cap(Point p, Point d, std::vector<Point>& out) {
    const Point n = normal_of(d);
    switch (cap_) {
      case LineCap::Butt: break;
      case LineCap::Square:
        out.push_back(p + n * hw_ + d * hw_);
        out.push_back(p - n * hw_ + d * hw_);
        break;
      case LineCap::Round:
        append_arc(out, p, hw_, n, -kPi, tol_);
        out.pop_back();  // the end point p - n hw comes next anyway
        break;
    }
  }

  void make_dot(Point p, Point d) {
    if (style_.cap == LineCap::Butt) return;
    contour_.clear();
    if (style_.cap == LineCap::Square) {
      const Point n = normal_of(d);
      contour_ = {p + (n + d) * hw_, p + (d - n) * hw_, p - (n + d) * hw_, p + (n - d) * hw_};
    } else {
      contour_.push_back(p + Point{hw_, 0});
      append_arc(contour_, p, hw_, Point{1, 0}, -2 * kPi, tol_);
      contour_.pop_back();
    }
    emit(contour_);
  }

  // The join at vertex p between segment a (incoming) and b (outgoing): appends to left_ and right_.
  void join(Point p, std::size_t a, std::size_t b, bool corner) {
    const Point d0 = dirs_[a], d1 = dirs_[b];
    const Point n0 = normal_of(d0), n1 = normal_of(d1);
    // The turn from d0 to d1 by its cosine and sine (unit directions): the half-angle functions below come from
    // them by identities; the angle itself only for round joins (no atan2, tan, cos per join).
    const double turn_cos = dot(d0, d1), turn_sin = cross(d0, d1);
    // Turning towards +n puts the inner corner on the left side; the outer one on the right.
    // atan2(turn_sin, turn_cos) >= 0: a positive sine, or a zero one going straight on or (+0) turning back.
    const bool left_turn = turn_sin > 0 || (turn_sin == 0 && (turn_cos > 0 || !std::signbit(turn_sin)));
    const double s = left_turn ? -1.0 : 1.0;  // sign of the outer side's normals
    std::vector<Point>& outer = left_turn ? right_ : left_;
    std::vector<Point>& inner = left_turn ? left_ : right_;
    const Point oa = p + n0 * (s * hw_), ob = p + n1 * (s * hw_);
    const double one_plus_cos = std::max(0.0, 1 + turn_cos);
    const double cos_half = std::sqrt(0.5 * one_plus_cos);  // cos(|theta| / 2), theta in [-pi, pi]
    // Outer side.
    const LineJoin style = corner ? style_.join : LineJoin::Round;
    outer.push_back(oa);
    if (style == LineJoin::Round) {
      const double theta = std::atan2(turn_sin, turn_cos);  // turn angle in [-pi, pi]
      if (arc_segments(hw_, theta, tol_) == 1) {
        outer.push_back(ob);  // a turn so small that one chord is within tolerance
      } else {
        append_arc(outer, p, hw_, n0 * s, theta, tol_);
      }
    } else {
      const double c = cos_half;
      const bool miter = style == LineJoin::Miter || style == LineJoin::MiterClip;
      if (miter && c * miter_limit_ >= 1 && c > 0) {
        Point bis = (n0 + n1) * s;
        const double bl = length(bis);
        if (bl > 0) outer.push_back(p + bis * (hw_ / (bl * c)));
      } else if (style == LineJoin::MiterClip) {
        // The miter cut by the line square to the bisector at miter_limit * hw from p: each outer edge runs on
        // past its end (oa along d0, ob back along d1) until it meets that line. oa and ob lie hw * cos(half)
        // from p along the bisector; the edges approach the line at sin(half) per unit length.
        const double sn = std::sqrt(std::max(0.0, 0.5 * (1 - turn_cos)));  // sin(|theta| / 2)
        if (sn > 0) {
          const double t = hw_ * (miter_limit_ - c) / sn;
          outer.push_back(oa + d0 * t);
          outer.push_back(ob - d1 * t);
        }
      }
      outer.push_back(ob);
    }
    // Inner side.
    const Point ia = p - n0 * (s * hw_), ib = p - n1 * (s * hw_);
    // Distance from p to the offset lines' intersection along each: hw tan(|theta| / 2) = hw |sin| / (1 + cos).
    // Turns of almost 180 degrees (|theta| / 2 within 1e-9 of 90 degrees) have none.
    const bool meets = one_plus_cos > 2e-18;
    const double back = meets ? hw_ * std::fabs(turn_sin) / one_plus_cos : 0;
    if (meets && back <= 0.5 * std::min(lens_[a], lens_[b])) {
      inner.push_back(ia - d0 * back);
    } else {
      inner.push_back(ia);
      inner.push_back(p);
      inner.push_back(ib);
    }
  }

  // Emits pts as a closed contour.
  void emit(const std::vector<Point>& pts) {
    if (pts.size() < 2) return;
    // A contour that overflowed (input within a pen width of the double range) is dropped, not thrown.
    for (const Point& p : pts) {
      if (!is_finite(p)) return;
    }
    emitted_ += pts.size();
    if (emitted_ > kMaxStrokeOutlinePoints) throw_outline_too_big();
    out_.reserve_more(pts.size() + 1, pts.size());
    out_.move_to(pts[0]);
    for (std::size_t i = 1; i < pts.size(); ++i) {
      if (!(pts[i] == pts[i - 1])) out_.line_to(pts[i]);
    }
    out_.close();
  }

  double hw_;
  const StrokeStyle& style_;
  LineCap cap_;  // the cap in use (a closed A-B-A piece uses its join as caps)
  double tol_;
  double miter_limit_;
  Path& out_;
  std::vector<Point> dirs_;
  std::vector<double> lens_;
  std::vector<Point> left_, right_, contour_;
  std::size_t emitted_ = 0;
};

bool segment_may_reach(Point a, Point b, const Rect& r) {
  return std::max(a.x, b.x) >= r.x0 && std::min(a.x, b.x) <= r.x1 && std::max(a.y, b.y) >= r.y0 &&
         std::min(a.y, b.y) <= r.y1;
}

}  // namespace

void clip_pieces(const std::vector<StrokePolyline>& in, const Rect& reachable, std::vector<StrokePolyline>& out) {
  for (const StrokePolyline& pl : in) {
    const std::size_t n = pl.points.size();
    if (n == 1) {
      const Point p = pl.points[0];
      if (segment_may_reach(p, p, reachable)) out.push_back(pl);
      continue;
    }
    const std::size_t segs = pl.closed ? n : n - 1;
    std::size_t first_hidden = segs;
    for (std::size_t i = 0; i < segs && first_hidden == segs; ++i) {
      if (!segment_may_reach(pl.points[i], pl.points[(i + 1) % n], reachable)) first_hidden = i;
    }
    if (first_hidden == segs) {  // all of it may show
      out.push_back(pl);
      continue;
    }
    // Runs of segments that may show become open pieces. A closed piece is walked from just after a hidden
    // segment, so no run wraps around its start.
    const std::size_t begin = pl.closed ? first_hidden + 1 : 0;
    StrokePolyline run;
    auto flush = [&] {
      if (run.points.size() >= 2) out.push_back(std::move(run));
      run = StrokePolyline{};
    };
    for (std::size_t k = 0; k < segs; ++k) {
      const std::size_t i = (begin + k) % n, j = (i + 1) % n;
      if (!segment_may_reach(pl.points[i], pl.points[j], reachable)) {
        flush();
        continue;
      }
      if (run.points.empty()) {
        run.points.push_back(pl.points[i]);
        run.corner.push_back(1);
      }
      run.points.push_back(pl.points[j]);
      run.corner.push_back(pl.corner[j]);
    }
    flush();
  }
}

namespace {

/// The sum of a normalized pattern (an odd list counts twice), or 0 when an entry is negative or not finite or
/// the sum is not finite and positive (a doubled 1e308 overflows).
double pattern_total(const std::vector<double>& dashes) {
  double sum = 0;
  for (double d : dashes) {
    if (!(d >= 0) || !std::isfinite(d)) return 0;
    sum += d;
  }
  if (dashes.size() % 2 == 1) sum *= 2;
  return sum > 0 && std::isfinite(sum) ? sum : 0;
}

/// Length of the control polygon of every contour (closing segments included): at least the arc length.
double control_polygon_length(const Path& path) {
  double total = 0;
  Point start{}, last{};
  const auto pts = path.points();
  std::size_t i = 0;
  for (Verb v : path.verbs()) {
    const int n = v == Verb::Move ? 0 : v == Verb::Line ? 1 : v == Verb::Quad ? 2 : v == Verb::Cubic ? 3 : -1;
    if (v == Verb::Move) {
      start = last = pts[i++];
    } else if (n < 0) {
      total += length(start - last);
      last = start;
    } else {
      for (int k = 0; k < n; ++k, ++i) {
        total += length(pts[i] - last);
        last = pts[i];
      }
    }
  }
  return total;
}

}  // namespace

std::vector<double> normalize_dashes(const std::vector<double>& dashes) {
  if (pattern_total(dashes) == 0) return {};
  std::vector<double> p = dashes;
  if (p.size() % 2 == 1) p.insert(p.end(), dashes.begin(), dashes.end());
  return p;
}

DashVerdict check_dashes(const Path& path, const std::vector<double>& dashes) {
  if (dashes.empty()) return DashVerdict::None;
  const double total = pattern_total(dashes);
  if (total == 0) return DashVerdict::Invalid;
  const double elements = static_cast<double>(dashes.size() % 2 ? 2 * dashes.size() : dashes.size());
  if (!(control_polygon_length(path) / total * elements <= kMaxDashElements)) return DashVerdict::TooMany;
  return DashVerdict::Dashed;
}

bool parse_line_cap(std::string_view name, LineCap& out) {
  if (name == "butt") out = LineCap::Butt;
  else if (name == "round") out = LineCap::Round;
  else if (name == "square") out = LineCap::Square;
  else return false;
  return true;
}

bool parse_line_join(std::string_view name, LineJoin& out) {
  if (name == "miter") out = LineJoin::Miter;
  else if (name == "round") out = LineJoin::Round;
  else if (name == "bevel") out = LineJoin::Bevel;
  else if (name == "miter-clip") out = LineJoin::MiterClip;
  else return false;
  return true;
}

void flatten_for_stroke(const Path& path, double tolerance, std::vector<StrokePolyline>& out) {
  flatten_impl(path, tolerance, nullptr, out);
}

void dash_polylines(const std::vector<StrokePolyline>& in, const std::vector<double>& pattern, double offset,
                    std::vector<StrokePolyline>& out) {
  if (pattern.empty()) {
    out.insert(out.end(), in.begin(), in.end());
    return;
  }
  double total = 0;
  for (double d : pattern) total += d;
  if (!(total > 0) || !std::isfinite(total)) {  // not a pattern dash_polylines can walk: solid
    out.insert(out.end(), in.begin(), in.end());
    return;
  }
  // Bounded work: a pattern that would cut the paths into more than kMaxDashElements pieces is ignored (solid).
  double path_length = 0;
  for (const StrokePolyline& pl : in) {
    const std::size_t m = pl.points.size();
    for (std::size_t i = 0; i + 1 < m; ++i) path_length += length(pl.points[i + 1] - pl.points[i]);
    if (pl.closed && m > 1) path_length += length(pl.points[0] - pl.points[m - 1]);
  }
  if (!(path_length / total * static_cast<double>(pattern.size()) <= kMaxDashElements)) {
    out.insert(out.end(), in.begin(), in.end());
    return;
  }
  double off = std::fmod(offset, total);
  if (!std::isfinite(off)) off = 0;
  if (off < 0) off += total;
  // The element the offset falls in: element k covers [start_k, start_k + len_k); a zero-length element at
  // exactly the offset is kept (it draws a dot).
  if (!(off < total)) off = 0;  // fmod's result rounded up to the total
  std::size_t idx0 = 0;
  // At most one pass over the pattern (off < total); the count guards against round-off at the last element.
  for (std::size_t steps = 0; steps < pattern.size() && (off > pattern[idx0] || (off == pattern[idx0] && pattern[idx0] > 0));
       ++steps) {
    off -= pattern[idx0];
    idx0 = (idx0 + 1) % pattern.size();
  }
  off = std::min(off, pattern[idx0]);
  const double rem0 = pattern[idx0] - off;

  for (const StrokePolyline& pl : in) {
    std::size_t idx = idx0;
    double rem = rem0;
    bool on = idx % 2 == 0;
    if (pl.points.size() == 1) {
      if (on) out.push_back(pl);
      continue;
    }
    const std::size_t n = pl.points.size();
    const std::size_t segs = pl.closed ? n : n - 1;
    const std::size_t first_out = out.size();
    const bool started_on = on;
    bool cut = false;
    StrokePolyline cur;
    auto begin_piece = [&](Point p, Point dir) {
      cur = StrokePolyline{};
      cur.points.push_back(p);
      cur.corner.push_back(1);
      cur.dot_direction = dir;
    };
    auto add = [&](Point p, std::uint8_t corner) {
      if (cur.points.back() == p) {
        cur.corner.back() |= corner;
        return;
      }
      cur.points.push_back(p);
      cur.corner.push_back(corner);
    };
    if (on) begin_piece(pl.points[0], Point{1, 0});
    for (std::size_t i = 0; i < segs; ++i) {
      const Point a = pl.points[i], b = pl.points[(i + 1) % n];
      const double len = length(b - a);
      const Point dir = len > 0 ? (b - a) * (1 / len) : Point{1, 0};
      if (i == 0 && on) cur.dot_direction = dir;
      double pos = 0;
      while (len - pos > rem) {
        pos += rem;
        const Point p = pos >= len ? b : a + dir * pos;
        if (on) {
          add(p, 1);
          out.push_back(cur);
        } else {
          begin_piece(p, dir);
        }
        cut = true;
        on = !on;
        idx = (idx + 1) % pattern.size();
        rem = pattern[idx];
      }
      rem -= len - pos;
      if (on) add(b, pl.corner[(i + 1) % n]);
    }
    if (!on) {
      // A zero-length dash due exactly at the end of an open subpath is still a dot (on a closed one it is the
      // dot at the start).
      const std::size_t next = (idx + 1) % pattern.size();
      if (!pl.closed && rem <= 0 && pattern[next] == 0) {
        const Point a = pl.points[n - 2], b = pl.points[n - 1];
        begin_piece(b, (b - a) * (1 / length(b - a)));
        out.push_back(cur);
      }
      continue;
    }
    if (!cut) {  // the whole contour is one dash
      StrokePolyline whole = pl;
      out.push_back(whole);
      continue;
    }
    if (pl.closed && started_on && out.size() > first_out) {
      // Join the last dash to the first (they meet at the start vertex, a corner).
      StrokePolyline& first = out[first_out];
      for (std::size_t k = 1; k < first.points.size(); ++k) add(first.points[k], first.corner[k]);
      cur.corner[0] = 1;
      first = cur;
      continue;
    }
    out.push_back(cur);
  }
}

void stroke_polylines(const std::vector<StrokePolyline>& pieces, const StrokeStyle& style, double tolerance,
                      Path& out) {
  if (!(style.width > 0) || !std::isfinite(style.width)) return;
  if (!(tolerance > 0) || !std::isfinite(tolerance)) tolerance = kDefaultTolerance;
  Outliner o(style, tolerance, out);
  for (const StrokePolyline& pl : pieces) o.piece(pl);
}

Path stroke_to_path(const Path& path, const StrokeStyle& style, double tolerance) {
  return stroke_to_path_visible(path, style, tolerance, nullptr);
}

Path stroke_to_path_visible(const Path& path, const StrokeStyle& style, double tolerance, const Rect* visible) {
  Path out;
  if (!(style.width > 0) || !std::isfinite(style.width)) return out;
  if (!(tolerance > 0) || !std::isfinite(tolerance)) tolerance = kDefaultTolerance;
  const std::vector<double> pattern =
      check_dashes(path, style.dashes) == DashVerdict::Dashed ? normalize_dashes(style.dashes) : std::vector<double>{};
  // How far the outline reaches from the centre line: half the width, times the miter limit for miters, times
  // sqrt(2) for square caps; plus the tolerance.
  const bool miter = style.join == LineJoin::Miter || style.join == LineJoin::MiterClip;
  const double factor = std::max(std::sqrt(2.0), miter && std::isfinite(style.miter_limit)
                                                     ? style.miter_limit
                                                     : 1.0);
  Rect reachable{};
  if (visible) {
    const double reach = style.width / 2 * factor + tolerance;
    reachable = Rect{visible->x0 - reach, visible->y0 - reach, visible->x1 + reach, visible->y1 + reach};
  }
  std::vector<StrokePolyline> pieces;
  // Curves that cannot show become chords, except under dashes (a chord is shorter: later dashes would move).
  flatten_impl(path, tolerance / 2, visible && pattern.empty() ? &reachable : nullptr, pieces);
  if (!pattern.empty()) {
    std::vector<StrokePolyline> dashed;
    dash_polylines(pieces, pattern, style.dash_offset, dashed);
    pieces.swap(dashed);
  }
  if (visible) {
    std::vector<StrokePolyline> shown;
    clip_pieces(pieces, reachable, shown);
    pieces.swap(shown);
  }
  stroke_polylines(pieces, style, tolerance, out);
  return out;
}

double user_tolerance(const Affine& m, double device_tolerance) {
  // Largest singular value of the linear part.
  const double a = m.a, b = m.b, c = m.c, d = m.d;
  const double s1 = a * a + b * b + c * c + d * d;
  const double det = a * d - b * c;
  const double disc = std::sqrt(std::max(0.0, s1 * s1 / 4 - det * det));
  const double smax = std::sqrt(s1 / 2 + disc);
  if (!(smax > 0) || !std::isfinite(smax)) return device_tolerance;
  return device_tolerance / smax;
}

// Used by hairline.cpp: flattening with a clip rectangle (curves whose hull misses it become chords).
void flatten_for_stroke_clipped(const Path& path, double tolerance, const Rect& clip, std::vector<StrokePolyline>& out) {
  flatten_impl(path, tolerance, &clip, out);
}

}  // namespace vraster
