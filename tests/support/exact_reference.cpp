#include "support/exact_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "support/capture.hpp"

namespace vraster::test::exact {
namespace {

// Everything inside is computed in long double (64-bit mantissa): the double inputs' degenerate features (edges
// tilted by one double ulp, crossings within one ulp of a vertex) are then resolved by 11 more bits.
using Real = long double;
struct P {
  Real x, y;
};
inline Real cross(P a, P b) { return a.x * b.y - a.y * b.x; }

struct Seg {
  P a, b;  // directed a -> b
  Real ylo() const { return std::min(a.y, b.y); }
  Real yhi() const { return std::max(a.y, b.y); }
  int dir() const { return b.y > a.y ? 1 : -1; }
  // x on the supporting line at height y (exact at the end points).
  Real x_at(Real y) const {
    if (y == a.y) return a.x;
    if (y == b.y) return b.x;
    return a.x + (y - a.y) * ((b.x - a.x) / (b.y - a.y));
  }
};

struct Split {
  std::vector<Seg> sloped;       // non-horizontal segments
  std::vector<Seg> horizontals;  // horizontal, non-degenerate segments
  std::vector<Real> vertex_ys;
};

Split split_segments(const std::vector<Polygon>& contours) {
  Split s;
  for (const Polygon& poly : contours) {
    const std::size_t n = poly.size();
    if (n < 2) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const P a{poly[i].x, poly[i].y}, b{poly[(i + 1) % n].x, poly[(i + 1) % n].y};
      s.vertex_ys.push_back(a.y);
      if (a.y != b.y) {
        s.sloped.push_back({a, b});
      } else if (a.x != b.x) {
        s.horizontals.push_back({a, b});
      }
    }
  }
  std::sort(s.vertex_ys.begin(), s.vertex_ys.end());
  s.vertex_ys.erase(std::unique(s.vertex_ys.begin(), s.vertex_ys.end()), s.vertex_ys.end());
  return s;
}

// Proper (non-parallel) intersection points of all pairs of sloped segments (end points included, with a little
// slack: an extra split height is harmless, a missing one is not).
std::vector<P> intersections(const std::vector<Seg>& segs) {
  std::vector<P> out;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Seg& s = segs[i];
    const P r{s.b.x - s.a.x, s.b.y - s.a.y};
    const Real ylo = s.ylo(), yhi = s.yhi();
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const Seg& t = segs[j];
      if (t.yhi() < ylo || t.ylo() > yhi) continue;
      const P q{t.b.x - t.a.x, t.b.y - t.a.y};
      const Real denom = cross(r, q);
      if (denom == 0) continue;  // parallel: they never swap order
      const P d{t.a.x - s.a.x, t.a.y - s.a.y};
      const Real u = cross(d, q) / denom;  // along s
      const Real v = cross(d, r) / denom;  // along t
      const Real slack = 1e-12L;
      if (u < -slack || u > 1 + slack || v < -slack || v > 1 + slack) continue;
      // The height on the flatter of the two, clamped to both y ranges (the crossing lies on both).
      const Real y = std::abs(r.y) * std::abs(q.x) < std::abs(q.y) * std::abs(r.x) ? s.a.y + r.y * u : t.a.y + q.y * v;
      const Real x = s.a.x + r.x * u;
      out.push_back({x, std::clamp(y, std::max(ylo, t.ylo()), std::min(yhi, t.yhi()))});
    }
  }
  return out;
}

Real clip_len(Real lo, Real hi, Real x0, Real x1) {
  const Real a = std::max(lo, x0), b = std::min(hi, x1);
  return b > a ? b - a : 0.0L;
}

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

struct Trapezoid {
  Real yt, yb;      // slab
  Real lt, lb;      // left side x at top and bottom
  Real rt, rb;      // right side x at top and bottom
  bool filled;
};

// The filled trapezoids of the slab decomposition (see the header).
std::vector<Trapezoid> filled_trapezoids(const std::vector<Polygon>& contours, FillRule rule, double tol) {
  const Split sp = split_segments(contours);
  std::vector<Real> ys = sp.vertex_ys;
  for (P p : intersections(sp.sloped)) ys.push_back(p.y);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  const std::size_t slabs = ys.size() < 2 ? 0 : ys.size() - 1;

  // Per slab: the segments spanning it, in x order at mid-height.
  std::vector<std::vector<std::uint32_t>> active(slabs);
  std::vector<std::size_t> base(slabs + 1, 1);  // node 0 is the exterior
  for (std::size_t k = 0; k < slabs; ++k) {
    const Real y0 = ys[k], y1 = ys[k + 1], ym = 0.5L * (y0 + y1);
    auto& act = active[k];
    for (std::uint32_t i = 0; i < sp.sloped.size(); ++i) {
      if (sp.sloped[i].ylo() <= y0 && sp.sloped[i].yhi() >= y1) act.push_back(i);
    }
    std::sort(act.begin(), act.end(),
              [&](std::uint32_t i, std::uint32_t j) { return sp.sloped[i].x_at(ym) < sp.sloped[j].x_at(ym); });
    base[k + 1] = base[k] + act.size() + 1;  // intervals 0 .. act.size()
  }

  UnionFind uf(base[slabs]);
  if (rule == FillRule::NonExterior) {
    const Real inf = std::numeric_limits<Real>::infinity();
    for (std::size_t k = 0; k < slabs; ++k) {
      uf.unite(0, base[k]);
      uf.unite(0, base[k] + active[k].size());
    }
    // Boundary b lies at ys[b] between slab b-1 (above; the exterior when b == 0) and slab b (below; the exterior
    // when b == slabs).
    for (std::size_t b = 0; b <= slabs && !ys.empty(); ++b) {
      const Real y = ys[b];
      // x of each bounding segment at the boundary, and how far off that x may be: the boundary height itself is
      // rounded (to a long double ulp), which moves a flat segment's x by |dx/dy| times that.
      std::vector<Real> xa, xb, ua, ub;
      auto add = [&](std::vector<Real>& xs, std::vector<Real>& us, const Seg& s) {
        const Real x = s.x_at(y);
        xs.push_back(x);
        const Real slope = std::abs((s.b.x - s.a.x) / (s.b.y - s.a.y));
        us.push_back((slope * std::abs(y) + std::abs(x) + 1) * 0x1p-58L);
      };
      if (b > 0) {
        for (std::uint32_t i : active[b - 1]) add(xa, ua, sp.sloped[i]);
      }
      if (b < slabs) {
        for (std::uint32_t i : active[b]) add(xb, ub, sp.sloped[i]);
      }
      std::vector<std::pair<Real, Real>> hs;
      for (const Seg& h : sp.horizontals) {
        if (h.a.y == y) hs.emplace_back(std::min(h.a.x, h.b.x), std::max(h.a.x, h.b.x));
      }
      std::sort(hs.begin(), hs.end());
      std::vector<std::pair<Real, Real>> merged;
      for (auto h : hs) {
        if (!merged.empty() && h.first <= merged.back().second) {
          merged.back().second = std::max(merged.back().second, h.second);
        } else {
          merged.push_back(h);
        }
      }
      auto node = [&](bool above, std::size_t interval) -> std::size_t {
        if (above) return b == 0 ? 0 : base[b - 1] + interval;
        return b == slabs ? 0 : base[b] + interval;
      };
      for (std::size_t i = 0; i <= xa.size(); ++i) {
        const Real alo = i == 0 ? -inf : xa[i - 1], ahi = i == xa.size() ? inf : xa[i];
        const Real ualo = i == 0 ? 0 : ua[i - 1], uahi = i == xa.size() ? 0 : ua[i];
        for (std::size_t j = 0; j <= xb.size(); ++j) {
          const Real blo = j == 0 ? -inf : xb[j - 1], bhi = j == xb.size() ? inf : xb[j];
          const Real ublo = j == 0 ? 0 : ub[j - 1], ubhi = j == xb.size() ? 0 : ub[j];
          const Real lo = std::max(alo, blo), hi = std::min(ahi, bhi);
          const Real slack = tol + (alo >= blo ? ualo : ublo) + (ahi <= bhi ? uahi : ubhi);
          if (!(hi - lo > slack)) continue;
          Real free_len = hi - lo;
          if (std::isinf(free_len)) {
            uf.unite(node(true, i), node(false, j));
            continue;
          }
          for (auto [hlo, hhi] : merged) free_len -= clip_len(hlo, hhi, lo, hi);
          if (free_len > slack) uf.unite(node(true, i), node(false, j));
        }
      }
    }
  }

  std::vector<Trapezoid> out;
  for (std::size_t k = 0; k < slabs; ++k) {
    const auto& act = active[k];
    const Real y0 = ys[k], y1 = ys[k + 1];
    int w = 0;
    for (std::size_t j = 1; j < act.size(); ++j) {
      const Seg& l = sp.sloped[act[j - 1]];
      const Seg& r = sp.sloped[act[j]];
      w += l.dir();
      const bool filled = rule == FillRule::NonExterior ? uf.find(base[k] + j) != 0 : rule_inside(rule, w);
      if (!filled) continue;
      out.push_back({y0, y1, l.x_at(y0), l.x_at(y1), r.x_at(y0), r.x_at(y1), true});
    }
  }
  return out;
}

}  // namespace


std::vector<double> scan_coverage(const std::vector<Polygon>& contours, FillRule rule, int width, int height) {
  std::vector<double> cov(static_cast<std::size_t>(width) * height, 0.0);
  const Split sp = split_segments(contours);
  std::vector<P> inter = intersections(sp.sloped);
  std::sort(inter.begin(), inter.end(), [](P p, P q) { return p.y < q.y; });

  std::vector<Real> ys;
  std::vector<std::pair<Real, int>> crossings;
  // Filled length inside [x0, x0 + 1] of the horizontal line at height y (y is never a vertex height).
  auto filled_length = [&](Real y, Real x0) {
    crossings.clear();
    for (const Seg& s : sp.sloped) {
      if (s.ylo() < y && y < s.yhi()) crossings.emplace_back(s.x_at(y), s.dir());
    }
    std::sort(crossings.begin(), crossings.end());
    Real len = 0;
    int w = 0;
    for (std::size_t i = 0; i + 1 < crossings.size(); ++i) {
      w += crossings[i].second;
      if (rule_inside(rule, w)) len += clip_len(crossings[i].first, crossings[i + 1].first, x0, x0 + 1);
    }
    return len;
  };

  for (int py = 0; py < height; ++py) {
    const Real top = py, bottom = py + 1;
    const auto v0 = std::upper_bound(sp.vertex_ys.begin(), sp.vertex_ys.end(), top);
    const auto v1 = std::lower_bound(sp.vertex_ys.begin(), sp.vertex_ys.end(), bottom);
    const auto i0 = std::upper_bound(inter.begin(), inter.end(), top, [](Real y, P p) { return y < p.y; });
    const auto i1 = std::lower_bound(inter.begin(), inter.end(), bottom, [](P p, Real y) { return p.y < y; });
    for (int px = 0; px < width; ++px) {
      const Real left = px, right = px + 1;
      ys.assign({top, bottom});
      ys.insert(ys.end(), v0, v1);
      for (auto it = i0; it != i1; ++it) {
        const Real slack = 1e-9L * (1 + std::abs(it->x));
        if (it->x >= left - slack && it->x <= right + slack) ys.push_back(it->y);
      }
      for (const Seg& s : sp.sloped) {
        if (s.yhi() <= top || s.ylo() >= bottom) continue;
        const Real xlo = std::min(s.a.x, s.b.x), xhi = std::max(s.a.x, s.b.x);
        for (Real side : {left, right}) {
          if (xlo < side && side < xhi) {
            const Real y = s.a.y + (side - s.a.x) * ((s.b.y - s.a.y) / (s.b.x - s.a.x));
            if (y > top && y < bottom) ys.push_back(y);
          }
        }
      }
      std::sort(ys.begin(), ys.end());
      Real area = 0;
      for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
        const Real h = ys[k + 1] - ys[k];
        if (h > 0) area += h * filled_length(ys[k] + 0.5L * h, left);
      }
      cov[static_cast<std::size_t>(py) * width + px] = static_cast<double>(area);
    }
  }
  return cov;
}

std::vector<double> trapezoid_coverage(const std::vector<Polygon>& contours, FillRule rule, int width, int height,
                                       double gap_tolerance) {
  std::vector<double> cov(static_cast<std::size_t>(width) * height, 0.0);
  for (const Trapezoid& t : filled_trapezoids(contours, rule, gap_tolerance)) {
    const double yt = static_cast<double>(t.yt), yb = static_cast<double>(t.yb);
    const Polygon quad{{static_cast<double>(t.lt), yt}, {static_cast<double>(t.rt), yt},
                       {static_cast<double>(t.rb), yb}, {static_cast<double>(t.lb), yb}};
    if (!(yb > yt)) continue;  // thinner than a double: no area
    const int r0 = std::max(0, static_cast<int>(std::floor(yt)));
    const int r1 = std::min(height, static_cast<int>(std::ceil(yb)));
    const double xmin = static_cast<double>(std::min(t.lt, t.lb)), xmax = static_cast<double>(std::max(t.rt, t.rb));
    const int c0 = static_cast<int>(std::max(0.0, std::floor(xmin)));
    const int c1 = static_cast<int>(std::min<double>(width, std::ceil(xmax)));
    for (int y = r0; y < r1; ++y) {
      for (int x = c0; x < c1; ++x) {
        const Polygon cell = clip_to_box(quad, x, y, x + 1.0, y + 1.0);
        if (cell.size() >= 3) cov[static_cast<std::size_t>(y) * width + x] += std::abs(shoelace_area(cell));
      }
    }
  }
  return cov;
}

double total_area(const std::vector<Polygon>& contours, FillRule rule, double gap_tolerance) {
  Real area = 0;
  for (const Trapezoid& t : filled_trapezoids(contours, rule, gap_tolerance)) {
    area += (t.yb - t.yt) * 0.5L * ((t.rt - t.lt) + (t.rb - t.lb));
  }
  return static_cast<double>(area);
}

int winding_at(const std::vector<Polygon>& contours, Point p) {
  int w = 0;
  for (const Polygon& poly : contours) {
    const std::size_t n = poly.size();
    if (n < 2) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const Seg s{{poly[i].x, poly[i].y}, {poly[(i + 1) % n].x, poly[(i + 1) % n].y}};
      if (s.a.y == s.b.y || p.y < s.ylo() || p.y >= s.yhi()) continue;
      if (s.x_at(p.y) < p.x) w += s.dir();
    }
  }
  return w;
}

Polygon random_polygon(std::mt19937& rng, int n, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  Polygon poly;
  for (int i = 0; i < n; ++i) poly.push_back({u(rng), u(rng)});
  return poly;
}

Polylines polylines_of(const std::vector<Polygon>& contours) {
  Polylines lines;
  for (const Polygon& poly : contours) {
    lines.points.insert(lines.points.end(), poly.begin(), poly.end());
    lines.ends.push_back(static_cast<std::uint32_t>(lines.points.size()));
    lines.closed.push_back(1);
  }
  return lines;
}

namespace {
std::vector<double> grid_values(const CoverageGrid& grid, std::vector<std::string>* violations) {
  if (violations) {
    violations->insert(violations->end(), grid.violations().begin(), grid.violations().end());
  } else if (!grid.violations().empty()) {
    ADD_FAILURE() << "sink contract violated: " << grid.violations().front() << " (" << grid.violations().size()
                  << " violations)";
  }
  std::vector<double> out(static_cast<std::size_t>(grid.width()) * grid.height());
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) out[static_cast<std::size_t>(y) * grid.width() + x] = grid.at(x, y);
  }
  return out;
}
}  // namespace

std::vector<double> engine_coverage(const std::vector<Polygon>& contours, FillRule rule, AntiAlias aa, int width,
                                    int height, std::vector<std::string>* violations) {
  CoverageGrid grid(width, height);
  Rasterizer r;
  r.fill(polylines_of(contours), rule, aa, width, height, grid);
  return grid_values(grid, violations);
}

std::vector<double> engine_coverage(const Path& path, FillRule rule, AntiAlias aa, int width, int height,
                                    double tol) {
  return grid_values(rasterize(path, rule, aa, width, height, tol), nullptr);
}

::testing::AssertionResult grids_near(const std::vector<double>& got, const std::vector<double>& want, int width,
                                      double abs_tol, double* max_error) {
  if (got.size() != want.size()) return ::testing::AssertionFailure() << "grid sizes differ";
  double worst = 0, worst_excess = 0;
  std::size_t worst_i = 0, bad = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const double err = std::abs(got[i] - want[i]);
    if (!(err == err) || std::isnan(got[i])) return ::testing::AssertionFailure() << "NaN at pixel " << i;
    worst = std::max(worst, err);
    const double excess = err - (abs_tol + std::abs(want[i]) * 0x1p-24);
    if (excess > 0) {
      ++bad;
      if (excess > worst_excess) worst_excess = excess, worst_i = i;
    }
  }
  if (max_error) *max_error = worst;
  if (bad == 0) return ::testing::AssertionSuccess();
  std::ostringstream msg;
  msg.precision(17);
  msg << bad << " pixel(s) off by more than " << abs_tol << "; worst at (x=" << worst_i % width
      << ", y=" << worst_i / width << "): got " << got[worst_i] << ", want " << want[worst_i] << "\n";
  if (got.size() <= 1024) msg << "got:\n" << grid_text(got, width) << "want:\n" << grid_text(want, width);
  return ::testing::AssertionFailure() << msg.str();
}

double sum(const std::vector<double>& grid) {
  double s = 0;
  for (double v : grid) s += v;
  return s;
}

std::string grid_text(const std::vector<double>& grid, int width) {
  std::ostringstream out;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%4.0f", grid[i] * 100.0);
    out << buf;
    if ((i + 1) % width == 0) out << "\n";
  }
  return out.str();
}

}  // namespace vraster::test::exact
