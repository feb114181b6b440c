// Seed fill by scanline spans (include/vraster/seed_fill.hpp has the data flow).
#include "vraster/seed_fill.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "vraster/error.hpp"

namespace vraster {

template <class T>
void premultiply_to(Color c, T out[4]) {
  auto unit = [](float v) { return std::isfinite(v) ? std::clamp(static_cast<double>(v), 0.0, 1.0) : 0.0; };
  const double a = unit(c.a), scale = BasicImage<T>::kMax;
  out[0] = static_cast<T>(std::lround(unit(c.r) * a * scale));
  out[1] = static_cast<T>(std::lround(unit(c.g) * a * scale));
  out[2] = static_cast<T>(std::lround(unit(c.b) * a * scale));
  out[3] = static_cast<T>(std::lround(a * scale));
}

namespace {

// Whether a pixel belongs to the region: a colour compared channel by channel with a tolerance.
template <class T>
struct RegionTest {
  T reference[4];
  int tolerance;
  bool inside_when_close;  // Interior: close to the seed colour is inside; Boundary: close to the boundary is outside

  bool operator()(const T* px) const {
    bool close = true;
    for (int c = 0; c < 4; ++c) {
      close = close && std::abs(static_cast<int>(px[c]) - static_cast<int>(reference[c])) <= tolerance;
    }
    return close == inside_when_close;
  }
};

struct Seed {
  int x, y;
};

}  // namespace

template <class T>
SeedFillRegion seed_fill_region(const BasicImage<T>& image, int x, int y, const SeedFillOptions& options) {
  if (!(options.tolerance >= 0 && options.tolerance <= 1)) {
    throw Error("seed fill: tolerance must be a number from 0 to 1");
  }
  SeedFillRegion region;
  region.width = image.width;
  region.height = image.height;
  region.mask.assign(static_cast<std::size_t>(image.width) * image.height, 0);
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return region;

  RegionTest<T> inside{};
  inside.tolerance = static_cast<int>(std::floor(options.tolerance * BasicImage<T>::kMax + 1e-9));
  if (options.region == SeedRegion::Interior) {
    std::copy(image.pixel(x, y), image.pixel(x, y) + 4, inside.reference);
    inside.inside_when_close = true;
  } else {
    premultiply_to(options.boundary, inside.reference);
    inside.inside_when_close = false;
  }
  const int w = image.width, h = image.height;
  auto open = [&](int px, int py) {  // in the region and not yet marked
    return region.mask[static_cast<std::size_t>(py) * w + px] == 0 && inside(image.pixel(px, py));
  };
  if (!open(x, y)) return region;

  region.x0 = x, region.x1 = x + 1, region.y0 = y, region.y1 = y + 1;
  // Runs on neighbour rows may reach one pixel further each way when diagonals connect.
  const int reach = options.connectivity == Connectivity::Eight ? 1 : 0;
  std::vector<Seed> stack{{x, y}};
  while (!stack.empty()) {
    const Seed s = stack.back();
    stack.pop_back();
    if (!open(s.x, s.y)) continue;  // filled through another run since it was pushed
    // The run through the seed pixel.
    int left = s.x, right = s.x + 1;
    while (left > 0 && open(left - 1, s.y)) --left;
    while (right < w && open(right, s.y)) ++right;
    std::fill(region.mask.begin() + static_cast<std::ptrdiff_t>(s.y) * w + left,
              region.mask.begin() + static_cast<std::ptrdiff_t>(s.y) * w + right, 1);
    region.pixel_count += right - left;
    region.x0 = std::min(region.x0, left), region.x1 = std::max(region.x1, right);
    region.y0 = std::min(region.y0, s.y), region.y1 = std::max(region.y1, s.y + 1);
    // One seed per run of open pixels on the rows above and below that touches [left, right).
    const int scan0 = std::max(0, left - reach), scan1 = std::min(w, right + reach);
    for (const int ny : {s.y - 1, s.y + 1}) {
      if (ny < 0 || ny >= h) continue;
      bool in_run = false;
      for (int nx = scan0; nx < scan1; ++nx) {
        const bool o = open(nx, ny);
        if (o && !in_run) stack.push_back({nx, ny});
        in_run = o;
      }
    }
  }
  return region;
}

template <class T>
std::int64_t flood_fill(BasicImage<T>& image, int x, int y, Color fill, const SeedFillOptions& options) {
  const SeedFillRegion region = seed_fill_region(image, x, y, options);
  if (region.pixel_count == 0) return 0;
  T px[4];
  premultiply_to(fill, px);
  for (int py = region.y0; py < region.y1; ++py) {
    for (int qx = region.x0; qx < region.x1; ++qx) {
      if (region.contains(qx, py)) std::copy(px, px + 4, image.pixel(qx, py));
    }
  }
  return region.pixel_count;
}

template void premultiply_to(Color, std::uint8_t[4]);
template void premultiply_to(Color, std::uint16_t[4]);
template SeedFillRegion seed_fill_region(const BasicImage<std::uint8_t>&, int, int, const SeedFillOptions&);
template SeedFillRegion seed_fill_region(const BasicImage<std::uint16_t>&, int, int, const SeedFillOptions&);
template std::int64_t flood_fill(BasicImage<std::uint8_t>&, int, int, Color, const SeedFillOptions&);
template std::int64_t flood_fill(BasicImage<std::uint16_t>&, int, int, Color, const SeedFillOptions&);

}  // namespace vraster
