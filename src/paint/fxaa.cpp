// FXAA post-filter (after FXAA 3.11 "quality", Timothy Lottes, 2011), on the CPU.
//
//   1. luma plane of the image
//   2. per pixel: local contrast over N, S, E, W; below the thresholds -> unchanged (not an edge)
//   3. edge orientation from the 3x3 neighbourhood; the side (N/S or W/E) with the steeper gradient
//   4. walk along the edge from the half-pixel point between the two sides, both ways, until the luma leaves the
//      edge's average by a quarter of the gradient: the edge's two ends
//   5. offset across the edge: 0.5 - (distance to the nearer end) / (edge length), if that end is the right kind;
//      at least the sub-pixel term (how much the pixel differs from its 3x3 low-pass)
//   6. the new pixel is a bilinear sample of the original image at the offset position
#include "vraster/fxaa.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace vraster {
namespace {

struct Plane {
  const float* v;
  int w, h;
  float at(int x, int y) const {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return v[static_cast<std::size_t>(y) * w + x];
  }
  // Bilinear with pixel centres at integer coordinates, clamped at the border.
  float sample(float fx, float fy) const {
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const float tx = fx - x0, ty = fy - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    float a, b, c, d;
    if (ix >= 0 && iy >= 0 && ix + 1 < w && iy + 1 < h) {  // inside: no clamping
      const float* p = v + static_cast<std::size_t>(iy) * w + ix;
      a = p[0], b = p[1], c = p[w], d = p[w + 1];
    } else {
      a = at(ix, iy), b = at(ix + 1, iy), c = at(ix, iy + 1), d = at(ix + 1, iy + 1);
    }
    return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
  }
};

constexpr float kSteps[] = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f};

// Where to sample each changed pixel: the result of steps 2-5. Returns false for pixels left alone.
bool fxaa_offset(const Plane& L, int x, int y, const FxaaOptions& o, float& sx, float& sy) {
  const float m = L.at(x, y), n = L.at(x, y - 1), s = L.at(x, y + 1), w = L.at(x - 1, y), e = L.at(x + 1, y);
  const float max_l = std::max({m, n, s, w, e}), min_l = std::min({m, n, s, w, e});
  const float range = max_l - min_l;
  if (range < std::max(o.edge_threshold_min, max_l * o.edge_threshold)) return false;
  const float nw = L.at(x - 1, y - 1), ne = L.at(x + 1, y - 1), sw = L.at(x - 1, y + 1), se = L.at(x + 1, y + 1);

  // Sub-pixel aliasing: how far the pixel is from the low-pass of its neighbourhood.
  const float low_pass = (2.0f * (n + s + w + e) + (nw + ne + sw + se)) / 12.0f;
  const float sub_a = std::clamp(std::abs(low_pass - m) / range, 0.0f, 1.0f);
  const float sub_b = (-2.0f * sub_a + 3.0f) * sub_a * sub_a;
  const float sub = sub_b * sub_b * o.subpixel;

  // Orientation: a horizontal edge (luma changes along y) has a large second difference in y.
  const float edge_h = std::abs(-2.0f * w + nw + sw) + 2.0f * std::abs(-2.0f * m + n + s) + std::abs(-2.0f * e + ne + se);
  const float edge_v = std::abs(-2.0f * n + nw + ne) + 2.0f * std::abs(-2.0f * m + w + e) + std::abs(-2.0f * s + sw + se);
  const bool horizontal = edge_h >= edge_v;
  float l_neg = horizontal ? n : w, l_pos = horizontal ? s : e;  // the two sides across the edge
  const float g_neg = l_neg - m, g_pos = l_pos - m;
  const bool to_neg = std::abs(g_neg) >= std::abs(g_pos);
  const float gradient = std::max(std::abs(g_neg), std::abs(g_pos));
  const float step_across = to_neg ? -1.0f : 1.0f;
  const float edge_luma = 0.5f * (m + (to_neg ? l_neg : l_pos));  // average of the two sides

  // Start half a pixel across, then walk along the edge both ways.
  float bx = static_cast<float>(x), by = static_cast<float>(y);
  const float ax = horizontal ? 1.0f : 0.0f, ay = horizontal ? 0.0f : 1.0f;  // along the edge
  if (horizontal) {
    by += 0.5f * step_across;
  } else {
    bx += 0.5f * step_across;
  }
  const float scaled = 0.25f * gradient;
  float dn = 0, dp = 0;
  float end_n = 0, end_p = 0;
  bool done_n = false, done_p = false;
  for (const float step : kSteps) {
    if (!done_n) {
      dn += step;
      end_n = L.sample(bx - ax * dn, by - ay * dn) - edge_luma;
      done_n = std::abs(end_n) >= scaled;
    }
    if (!done_p) {
      dp += step;
      end_p = L.sample(bx + ax * dp, by + ay * dp) - edge_luma;
      done_p = std::abs(end_p) >= scaled;
    }
    if (done_n && done_p) break;
  }
  const bool m_below = m - edge_luma < 0;
  const bool good_n = (end_n < 0) != m_below, good_p = (end_p < 0) != m_below;
  const float span = dn + dp;
  const bool nearer_n = dn < dp;
  const float dist = std::min(dn, dp);
  const bool good = nearer_n ? good_n : good_p;
  const float offset = std::max(good ? 0.5f - dist / span : 0.0f, sub);
  if (!(offset > 0)) return false;
  sx = static_cast<float>(x);
  sy = static_cast<float>(y);
  if (horizontal) {
    sy += offset * step_across;
  } else {
    sx += offset * step_across;
  }
  return true;
}

// Runs the filter over the luma plane; `apply(x, y, sx, sy)` is called for every changed pixel with the position to
// sample the original image at.
template <class Apply>
void run(const float* luma, int width, int height, const FxaaOptions& options, Apply&& apply) {
  const Plane L{luma, width, height};
  std::vector<std::uint8_t> candidate(static_cast<std::size_t>(width) + 8, 0);
  for (int y = 0; y < height; ++y) {
    const float* row = luma + static_cast<std::size_t>(y) * width;
    const float* up = y > 0 ? row - width : row;
    const float* down = y + 1 < height ? row + width : row;
    // Quick reject, branch-free so it vectorises: a pixel equal to its 4 neighbours is no edge (the common case).
    std::uint8_t* c = candidate.data();
    c[0] = up[0] != row[0] || down[0] != row[0] || (width > 1 && row[1] != row[0]);
    for (int x = 1; x + 1 < width; ++x) {
      const float m = row[x];
      c[x] = static_cast<std::uint8_t>((up[x] != m) | (down[x] != m) | (row[x - 1] != m) | (row[x + 1] != m));
    }
    if (width > 1) {
      const int x = width - 1;
      c[x] = up[x] != row[x] || down[x] != row[x] || row[x - 1] != row[x];
    }
    for (int x = 0; x < width; ++x) {
      if ((x & 7) == 0) {  // skip 8 non-candidates at a time
        std::uint64_t word;
        std::memcpy(&word, c + x, 8);
        if (word == 0) {
          x += 7;
          continue;
        }
      }
      if (!c[x]) continue;
      float sx, sy;
      if (fxaa_offset(L, x, y, options, sx, sy)) apply(x, y, sx, sy);
    }
  }
}

template <class T>
void fxaa_image(BasicImage<T>& image, const FxaaOptions& options) {
  if (image.width <= 0 || image.height <= 0) return;
  const float scale = 1.0f / static_cast<float>(BasicImage<T>::kMax);
  const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
  std::vector<float> luma(count);
  unsigned all_opaque = 1;
  for (std::size_t i = 0; i < count; ++i) all_opaque &= image.data[i * 4 + 3] == BasicImage<T>::kMax;
  const bool opaque = all_opaque != 0;
  for (std::size_t i = 0; i < count; ++i) {
    const T* p = &image.data[i * 4];
    const float l = (0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]) * scale;
    luma[i] = opaque ? l : 0.5f * (l + p[3] * scale);
  }
  const std::vector<T> source = image.data;  // the filter reads the unfiltered image
  const int w = image.width, h = image.height;
  auto at = [&](int x, int y, int c) -> float {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return source[(static_cast<std::size_t>(y) * w + x) * 4 + c];
  };
  run(luma.data(), w, h, options, [&](int x, int y, float sx, float sy) {
    const float x0 = std::floor(sx), y0 = std::floor(sy);
    const float tx = sx - x0, ty = sy - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    T* p = image.pixel(x, y);
    for (int c = 0; c < 4; ++c) {
      const float top = at(ix, iy, c) + (at(ix + 1, iy, c) - at(ix, iy, c)) * tx;
      const float bottom = at(ix, iy + 1, c) + (at(ix + 1, iy + 1, c) - at(ix, iy + 1, c)) * tx;
      const float v = top + (bottom - top) * ty;
      p[c] = static_cast<T>(std::clamp(v, 0.0f, static_cast<float>(BasicImage<T>::kMax)) + 0.5f);
    }
  });
}

}  // namespace

void fxaa(Image& image, const FxaaOptions& options) { fxaa_image(image, options); }
void fxaa(Image16& image, const FxaaOptions& options) { fxaa_image(image, options); }

void fxaa(std::span<float> plane, int width, int height, const FxaaOptions& options) {
  if (width <= 0 || height <= 0 || plane.size() != static_cast<std::size_t>(width) * height) return;
  const std::vector<float> source(plane.begin(), plane.end());
  const Plane src{source.data(), width, height};
  run(source.data(), width, height, options, [&](int x, int y, float sx, float sy) {
    plane[static_cast<std::size_t>(y) * width + x] = src.sample(sx, sy);
  });
}

bool parse_anti_alias_method(std::string_view name, AntiAliasMethod& out) {
  if (name == "fxaa") {
    out = {AntiAlias::None, true};
    return true;
  }
  AntiAlias aa;
  if (!parse_anti_alias(name, aa)) return false;
  out = {aa, false};
  return true;
}

std::string_view to_string(const AntiAliasMethod& method) {
  return method.fxaa ? std::string_view("fxaa") : to_string(method.coverage);
}

void post_filter(const AntiAliasMethod& method, Image& image) {
  if (method.fxaa) fxaa(image);
}
void post_filter(const AntiAliasMethod& method, Image16& image) {
  if (method.fxaa) fxaa(image);
}
void post_filter(const AntiAliasMethod& method, std::span<float> plane, int width, int height) {
  if (method.fxaa) fxaa(plane, width, height);
}

}  // namespace vraster
