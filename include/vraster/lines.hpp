// vraster: classic scan conversion of lines, circles and ellipses (the course notes' algorithms).
//
// Pixel convention: pixel (x, y) is the square [x, x+1) x [y, y+1); integer line endpoints name pixels.
// Every drawing function clips to a canvas [0, width) x [0, height) first, so work is proportional to the
// visible part, and plots exactly the pixels the unclipped algorithm would plot inside the canvas.
//
// Bresenham tie-break (documented once, used everywhere): at every column (row, for steep lines) the pixel
// nearest the true line is plotted; when the line passes exactly halfway between two pixels, the one with the
// SMALLER minor coordinate wins ("round half down"). The rule is stated on absolute coordinates, so drawing
// p->q and q->p lights the same pixels. It agrees with the seeds' worked example (3,4)->(8,7), whose error-term
// test "p <= 0: keep y" rounds halves down for lines going down-right.
// DDA rounds with floor(v + 0.5) (round half UP), so DDA and Bresenham differ exactly at those ties.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"

namespace vraster {

/// An integer pixel position.
struct IPoint {
  int x = 0;
  int y = 0;
  friend constexpr bool operator==(IPoint a, IPoint b) { return a.x == b.x && a.y == b.y; }
  friend constexpr bool operator<(IPoint a, IPoint b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }
};

/// Whether the last pixel of a line is drawn.
enum class LineEnd : std::uint8_t {
  Closed,    ///< both endpoints drawn
  HalfOpen,  ///< the end pixel q is not drawn (GL's diamond-exit spirit): a polyline draws each joint once
};

/// The integer state of a clipped Bresenham walk (computed by plan_bresenham, consumed by bresenham_line).
/// Canonical form: the major coordinate u increases by 1 per pixel; the minor coordinate v moves by `sv`
/// whenever `rem` (the error term, kept in [0, two_du)) wraps around.
struct BresenhamWalk {
  bool x_major = true;
  std::int64_t u = 0, v = 0;   ///< first plotted pixel, in (major, minor) coordinates
  std::int64_t count = 0;      ///< pixels to plot
  int sv = 0;                  ///< minor step: -1, 0, +1
  std::int64_t rem = 0;        ///< error term at the first pixel
  std::int64_t two_dv = 0;     ///< 2 |minor delta|
  std::int64_t two_du = 1;     ///< 2 |major delta| (>= 2, or 1 for a single point)
};

/// Plans the Bresenham walk from p to q clipped to [0, width) x [0, height). Returns false when nothing is
/// visible. The error term is restarted exactly at the first visible pixel (128-bit arithmetic), so the pixels
/// are those of the unclipped line.
bool plan_bresenham(IPoint p, IPoint q, int width, int height, LineEnd end, BresenhamWalk& walk);

/// Bresenham's line from p to q, all eight octants, integer arithmetic only. Calls plot(int x, int y) for every
/// pixel inside [0, width) x [0, height), in order of increasing major coordinate.
template <class Plot>
void bresenham_line(IPoint p, IPoint q, int width, int height, LineEnd end, Plot&& plot) {
  BresenhamWalk w;
  if (!plan_bresenham(p, q, width, height, end, w)) return;
  std::int64_t u = w.u, v = w.v, rem = w.rem;
  const std::int64_t two_dv = w.two_dv, two_du = w.two_du;
  const int sv = w.sv;
  if (w.x_major) {
    for (std::int64_t i = 0; i < w.count; ++i) {
      plot(static_cast<int>(u), static_cast<int>(v));
      ++u;
      rem += two_dv;
      if (rem >= two_du) {
        rem -= two_du;
        v += sv;
      }
    }
  } else {
    for (std::int64_t i = 0; i < w.count; ++i) {
      plot(static_cast<int>(v), static_cast<int>(u));
      ++u;
      rem += two_dv;
      if (rem >= two_du) {
        rem -= two_du;
        v += sv;
      }
    }
  }
}

/// The visible range of a DDA / Wu walk along the major axis (computed in lines.cpp).
struct MajorRange {
  bool x_major = true;
  std::int64_t first = 0, last = -1;  ///< major coordinates to visit, inclusive
};

/// Plans the DDA from p to q: steps along the major axis clipped to the canvas (and to where the minor
/// coordinate is on the canvas). False when nothing is visible.
bool plan_dda(IPoint p, IPoint q, int width, int height, MajorRange& range);

/// The seeds' DDA: steps = max(|dx|, |dy|); at step i the pixel is (round(x0 + dx*i/steps),
/// round(y0 + dy*i/steps)) with round(v) = floor(v + 0.5). (The position is computed from i rather than by
/// repeated addition, so that exact halves stay exact and the tie rule is predictable.) Plots only pixels inside
/// the canvas, in order of increasing major coordinate; both endpoints are drawn (LineEnd::HalfOpen omits q).
template <class Plot>
void dda_line(IPoint p, IPoint q, int width, int height, LineEnd end, Plot&& plot) {
  MajorRange r;
  if (!plan_dda(p, q, width, height, r)) return;
  const double dx = static_cast<double>(q.x) - p.x, dy = static_cast<double>(q.y) - p.y;
  const double steps = std::fabs(dx) >= std::fabs(dy) ? std::fabs(dx) : std::fabs(dy);
  if (steps == 0) {  // a single pixel
    if (end == LineEnd::Closed && p.x >= 0 && p.x < width && p.y >= 0 && p.y < height) plot(p.x, p.y);
    return;
  }
  for (std::int64_t m = r.first; m <= r.last; ++m) {
    // Step index i along p -> q for major coordinate m.
    const double i = r.x_major ? (dx >= 0 ? m - p.x : p.x - m) : (dy >= 0 ? m - p.y : p.y - m);
    if (end == LineEnd::HalfOpen && i == steps) continue;
    const double x = r.x_major ? static_cast<double>(m) : std::floor(p.x + dx * i / steps + 0.5);
    const double y = r.x_major ? std::floor(p.y + dy * i / steps + 0.5) : static_cast<double>(m);
    if (x >= 0 && x < width && y >= 0 && y < height) plot(static_cast<int>(x), static_cast<int>(y));
  }
}

/// Plans a Wu line: the major axis, and the pixel columns (rows) to visit, clipped with Liang-Barsky to the
/// canvas grown by one pixel. False when nothing is visible or p == q.
bool plan_wu(Point p, Point q, int width, int height, MajorRange& range);

/// Xiaolin Wu's antialiased line between real points p and q (device pixels, pixel centres at +0.5), the
/// seeds' "ratio" idea: in every column (row, for steep lines) crossed, the line's height at the column's
/// centre is split between the two nearest pixel centres in proportion to distance (weights 1-f and f), times
/// the fraction of the column the segment spans (so the end columns are partial and a polyline's joints add up
/// to one). Intensity is not corrected for slope (a 45-degree line is sqrt(2) lighter than the analytic
/// 1-px stroke). Calls plot(int x, int y, float coverage) with coverage in (0, 1] for pixels on the canvas.
template <class Plot>
void wu_line(Point p, Point q, int width, int height, Plot&& plot) {
  MajorRange r;
  if (!plan_wu(p, q, width, height, r)) return;
  // Canonical: u major (increasing), v minor.
  double u0 = r.x_major ? p.x : p.y, v0 = r.x_major ? p.y : p.x;
  double u1 = r.x_major ? q.x : q.y, v1 = r.x_major ? q.y : q.x;
  if (u1 < u0) {
    std::swap(u0, u1);
    std::swap(v0, v1);
  }
  const double slope = (v1 - v0) / (u1 - u0);
  const int vmax = r.x_major ? height : width;
  for (std::int64_t i = r.first; i <= r.last; ++i) {
    const double a = static_cast<double>(i) > u0 ? static_cast<double>(i) : u0;
    const double b = static_cast<double>(i + 1) < u1 ? static_cast<double>(i + 1) : u1;
    const double span = b - a;
    if (!(span > 0)) continue;
    const double vm = v0 + slope * (0.5 * (a + b) - u0) - 0.5;  // minor position in pixel-centre units
    const double fl = std::floor(vm);
    const float f = static_cast<float>(vm - fl);
    const std::int64_t j = static_cast<std::int64_t>(fl);
    const float c0 = static_cast<float>(span) * (1.0f - f), c1 = static_cast<float>(span) * f;
    const int ii = static_cast<int>(i);
    if (j >= 0 && j < vmax && c0 > 0) {
      if (r.x_major) plot(ii, static_cast<int>(j), c0); else plot(static_cast<int>(j), ii, c0);
    }
    if (j + 1 >= 0 && j + 1 < vmax && c1 > 0) {
      if (r.x_major) plot(ii, static_cast<int>(j + 1), c1); else plot(static_cast<int>(j + 1), ii, c1);
    }
  }
}

/// Midpoint circle (seeds' version: d = (x+1)^2 + (y-1/2)^2 - r^2 scaled by 4 to stay integer; d >= 0 steps y).
/// Computes the octant from (0, r) to the diagonal and plots it with eight-way symmetry around centre c, each
/// distinct pixel once; only pixels on the canvas are plotted. r < 0 draws nothing; r == 0 draws c.
template <class Plot>
void midpoint_circle(IPoint c, int r, int width, int height, Plot&& plot) {
  if (r < 0) return;
  auto put = [&](std::int64_t x, std::int64_t y) {
    x += c.x;
    y += c.y;
    if (x >= 0 && x < width && y >= 0 && y < height) plot(static_cast<int>(x), static_cast<int>(y));
  };
  std::int64_t x = 0, y = r, d = 5 - 4 * static_cast<std::int64_t>(r);
  while (x <= y) {
    if (x == 0) {
      put(0, y);
      if (y != 0) {
        put(0, -y);
        put(y, 0);
        put(-y, 0);
      }
    } else if (x == y) {
      put(x, y); put(-x, y); put(x, -y); put(-x, -y);
    } else {
      put(x, y); put(-x, y); put(x, -y); put(-x, -y);
      put(y, x); put(-y, x); put(y, -x); put(-y, -x);
    }
    if (d < 0) {
      d += 4 * (2 * x + 3);
    } else {
      d += 4 * (2 * (x - y) + 5);
      --y;
    }
    ++x;
  }
}

/// Midpoint ellipse with semi-axes rx, ry (>= 0) around c: where |slope| <= 1 it steps x (from the top),
/// elsewhere it steps y (from the side); decision variables scaled by 4 so they stay integer (64-bit).
/// Four-way symmetry, each distinct pixel once. rx or ry == 0 draws the axis segment.
template <class Plot>
void midpoint_ellipse(IPoint c, int rx, int ry, int width, int height, Plot&& plot) {
  if (rx < 0 || ry < 0) return;
  auto put4 = [&](std::int64_t x, std::int64_t y) {
    const std::int64_t xs[2] = {x, -x}, ys[2] = {y, -y};
    for (int a = 0; a < (x == 0 ? 1 : 2); ++a) {
      for (int b = 0; b < (y == 0 ? 1 : 2); ++b) {
        const std::int64_t px = c.x + xs[a], py = c.y + ys[b];
        if (px >= 0 && px < width && py >= 0 && py < height) plot(static_cast<int>(px), static_cast<int>(py));
      }
    }
  };
  if (rx == 0 || ry == 0) {  // degenerate: a segment along an axis
    for (std::int64_t x = 0; x <= rx; ++x)
      for (std::int64_t y = 0; y <= ry; ++y) put4(x, y);
    return;
  }
  const std::int64_t a2 = static_cast<std::int64_t>(rx) * rx, b2 = static_cast<std::int64_t>(ry) * ry;
  // The quadrant is split where the true ellipse has slope -1: x* = a2 / sqrt(a2 + b2), y* = b2 / sqrt(a2 + b2).
  // Pass 1 walks the columns x <= x* (one pixel per column), pass 2 the rows y <= y* (one pixel per row); the
  // two can only share pass 1's last pixel, which pass 2 skips.
  using wide = __int128;
  const wide sum = wide{a2} + b2;
  // Pass 1: from (0, ry); d = b2 (x+1)^2 + a2 (y-1/2)^2 - a2 b2, times 4; d >= 0 steps y.
  std::int64_t x = 0, y = ry;
  std::int64_t d = 4 * b2 - 4 * a2 * ry + a2;
  std::int64_t last_x = -1, last_y = -1;
  while (wide{x} * x * sum <= wide{a2} * a2) {
    put4(x, y);
    last_x = x;
    last_y = y;
    if (d < 0) {
      d += 4 * b2 * (2 * x + 3);
    } else {
      d += 4 * (b2 * (2 * x + 3) - a2 * (2 * y - 2));
      --y;
    }
    ++x;
  }
  // Pass 2: from (rx, 0); d = b2 (x-1/2)^2 + a2 (y+1)^2 - a2 b2, times 4; d >= 0 steps x.
  x = rx;
  y = 0;
  d = 4 * a2 - 4 * b2 * rx + b2;
  while (wide{y} * y * sum <= wide{b2} * b2) {
    if (!(x == last_x && y == last_y)) put4(x, y);
    if (d < 0) {
      d += 4 * a2 * (2 * y + 3);
    } else {
      d += 4 * (a2 * (2 * y + 3) - b2 * (2 * x - 2));
      --x;
    }
    ++y;
  }
}

// ---- convenience: pixel lists (unclipped: a canvas big enough for any int) and drawing into images ----

/// The pixels of bresenham_line without clipping, in walk order.
std::vector<IPoint> bresenham_pixels(IPoint p, IPoint q, LineEnd end = LineEnd::Closed);
/// The pixels of dda_line without clipping, in walk order.
std::vector<IPoint> dda_pixels(IPoint p, IPoint q, LineEnd end = LineEnd::Closed);
/// The distinct pixels of midpoint_circle around (0, 0), sorted (y, then x).
std::vector<IPoint> circle_pixels(int r);
/// The distinct pixels of midpoint_ellipse around (0, 0), sorted (y, then x).
std::vector<IPoint> ellipse_pixels(int rx, int ry);

/// Source-over of one colour onto single pixels of an 8-bit premultiplied image (no bounds check), with the
/// colour converted once: the per-pixel plot target of the line algorithms.
class PixelBlender {
 public:
  PixelBlender(Image& image, Color color);
  /// Full coverage: integer math, exact rounding.
  void blend_full(int x, int y);
  /// Coverage in [0, 1].
  void blend(int x, int y, float coverage);

 private:
  Image& image_;
  float alpha_;
  float premul_[4];
  std::uint32_t src8_[4];
  std::uint32_t inv8_;
};

/// Source-over of `color` at `coverage` (0..1) onto one pixel (premultiplied 8-bit); no bounds check.
void blend_pixel(Image& image, int x, int y, Color color, float coverage);

/// Which algorithm draw_line uses.
enum class LineAlgorithm : std::uint8_t { Bresenham, Dda, Wu };
/// Draws one line into `image` (source-over). Bresenham/Dda round p and q down to the pixels that contain them.
void draw_line(Image& image, Point p, Point q, Color color, LineAlgorithm algorithm, LineEnd end = LineEnd::Closed);
/// Draws a circle / ellipse outline (midpoint algorithm) into `image`.
void draw_circle(Image& image, IPoint c, int r, Color color);
void draw_ellipse(Image& image, IPoint c, int rx, int ry, Color color);

}  // namespace vraster
