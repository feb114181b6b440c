#include "generated_scenes.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <random>

namespace bench {
namespace {

constexpr double kSize = 1024;
constexpr double kPi = 3.14159265358979323846;
// A quarter circle as one cubic: its control points lie this far (times the radius) along the tangents.
constexpr double kQuarterCubic = 0.5522847498307936;

// Uniform numbers in [lo, hi) from the generator's 32-bit outputs.
class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}
  double operator()(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(engine_()) * 0x1p-32); }
  std::string colour() {
    char text[8];
    std::snprintf(text, sizeof text, "#%06x", static_cast<unsigned>(engine_() & 0xFFFFFFu));
    return text;
  }

 private:
  std::mt19937 engine_;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

std::string point(double x, double y) { return number(x) + " " + number(y); }

// An ellipse with radii rx, ry turned by `angle` about its centre: four cubics.
std::string ellipse(double cx, double cy, double rx, double ry, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  auto at = [&](double x, double y) { return point(cx + c * x - s * y, cy + s * x + c * y); };
  const double kx = kQuarterCubic * rx, ky = kQuarterCubic * ry;
  return "M " + at(rx, 0) + " C " + at(rx, ky) + " " + at(kx, ry) + " " + at(0, ry) + " C " + at(-kx, ry) + " " +
         at(-rx, ky) + " " + at(-rx, 0) + " C " + at(-rx, -ky) + " " + at(-kx, -ry) + " " + at(0, -ry) + " C " +
         at(kx, -ry) + " " + at(rx, -ky) + " " + at(rx, 0) + " Z";
}

// A w x h rectangle centred on (cx, cy), turned by `angle`.
std::string turned_rect(double cx, double cy, double w, double h, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  auto at = [&](double x, double y) { return point(cx + c * x - s * y, cy + s * x + c * y); };
  return "M " + at(-w / 2, -h / 2) + " L " + at(w / 2, -h / 2) + " L " + at(w / 2, h / 2) + " L " + at(-w / 2, h / 2) +
         " Z";
}

// `count` paths, each from `shape`, with a random colour at `opacity` (1: none given) under `rule`.
GeneratedScene scene(std::string name, std::uint32_t seed, int count, double opacity, const char* rule,
                     const std::function<std::string(Random&)>& shape) {
  Random random(seed);
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1024\" height=\"1024\">\n";
  for (int i = 0; i < count; ++i) {
    const std::string fill = random.colour();
    svg += "<path fill=\"" + fill + "\"";
    if (opacity < 1) svg += " fill-opacity=\"" + number(opacity) + "\"";
    svg += std::string(" fill-rule=\"") + rule + "\" d=\"" + shape(random) + "\"/>\n";
  }
  svg += "</svg>\n";
  return {std::move(name), std::move(svg)};
}

}  // namespace

std::vector<GeneratedScene> generated_scenes() {
  std::vector<GeneratedScene> scenes;
  // 500 discs of radius 100, opacity 0.6
  scenes.push_back(scene("discs100", 1, 500, 0.6, "nonzero", [](Random& r) {
    return ellipse(r(100, kSize - 100), r(100, kSize - 100), 100, 100, 0);
  }));
  // 3000 discs of radius 4-20, opacity 0.6
  scenes.push_back(scene("discs20", 2, 3000, 0.6, "nonzero", [](Random& r) {
    const double radius = r(4, 20);
    return ellipse(r(radius, kSize - radius), r(radius, kSize - radius), radius, radius, 0);
  }));
  // 300 even-odd rings of radius 120, wall 6, opacity 0.6
  scenes.push_back(scene("rings120", 3, 300, 0.6, "evenodd",
                         [](Random& r) {
                           const double x = r(120, kSize - 120), y = r(120, kSize - 120);
                           return ellipse(x, y, 120, 120, 0) + " " + ellipse(x, y, 114, 114, 0);
                         }));
  // 1000 turned ellipses of radii 10-80, opacity 0.7
  scenes.push_back(scene("ellipses", 4, 1000, 0.7, "nonzero",
                         [](Random& r) {
                           return ellipse(r(80, kSize - 80), r(80, kSize - 80), r(10, 80), r(10, 80), r(0, kPi));
                         }));
  // 2000 rectangles of 5-200 px at fractional positions, opacity 0.5
  scenes.push_back(scene("rects", 5, 2000, 0.5, "nonzero",
                         [](Random& r) {
                           const double w = r(5, 200), h = r(5, 200);
                           return turned_rect(r(0, kSize - w) + w / 2, r(0, kSize - h) + h / 2, w, h, 0);
                         }));
  // 2000 turned rectangles of 10-150 px, opacity 0.7
  scenes.push_back(scene("turned_rects", 6, 2000, 0.7, "nonzero",
                         [](Random& r) {
                           return turned_rect(r(50, kSize - 50), r(50, kSize - 50), r(10, 150), r(10, 150), r(0, kPi));
                         }));
  // 2000 opaque turned rectangles of 10-60 px
  scenes.push_back(scene("opaque_rects", 9, 2000, 1, "nonzero",
                         [](Random& r) {
                           return turned_rect(r(50, kSize - 50), r(50, kSize - 50), r(10, 60), r(10, 60), r(0, kPi));
                         }));
  // 300 opaque triangles with corners anywhere in the frame
  scenes.push_back(scene("opaque_triangles", 7, 300, 1, "nonzero",
                         [](Random& r) {
                           const double x0 = r(0, kSize), y0 = r(0, kSize), x1 = r(0, kSize), y1 = r(0, kSize);
                           const double x2 = r(0, kSize), y2 = r(0, kSize);
                           return "M " + point(x0, y0) + " L " + point(x1, y1) + " L " + point(x2, y2) + " Z";
                         }));
  // 3000 lines as outlines, 1.5 px wide and 50-400 px long, opacity 0.8
  scenes.push_back(scene("thin_lines", 8, 3000, 0.8, "nonzero",
                         [](Random& r) {
                           return turned_rect(r(200, kSize - 200), r(200, kSize - 200), r(50, 400), 1.5, r(0, kPi));
                         }));
  return scenes;
}

}  // namespace bench
