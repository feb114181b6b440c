// vraster command-line tool: the conformance comparison (`vraster compare`).
#include "cli/image_compare.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "cli/cli.hpp"
#include "vraster/png.hpp"

namespace vraster::cli {

int neighbourhood_error(const Image& a, const Image& b, int x, int y) {
  const std::uint8_t* pa = a.pixel(x, y);
  int lo[4] = {255, 255, 255, 255}, hi[4] = {0, 0, 0, 0};
  for (int ny = std::max(0, y - 1); ny <= std::min(b.height - 1, y + 1); ++ny) {
    for (int nx = std::max(0, x - 1); nx <= std::min(b.width - 1, x + 1); ++nx) {
      const std::uint8_t* pb = b.pixel(nx, ny);
      for (int c = 0; c < 4; ++c) {
        lo[c] = std::min<int>(lo[c], pb[c]);
        hi[c] = std::max<int>(hi[c], pb[c]);
      }
    }
  }
  int error = 0;
  for (int c = 0; c < 4; ++c) error = std::max({error, lo[c] - pa[c], pa[c] - hi[c]});
  return error;
}

CompareResult compare_images(const Image& reference, const Image& ours, const CompareRule& rule, Image* diff) {
  CompareResult r;
  r.pixels = static_cast<std::int64_t>(reference.width) * reference.height;
  r.same_size = reference.width == ours.width && reference.height == ours.height;
  if (diff) *diff = Image(std::max(reference.width, 1), std::max(reference.height, 1));
  if (!r.same_size) {
    r.off = r.far_off = r.pixels;
    r.max_error = 255;
    if (diff) diff->clear(Color{1, 0, 0, 1});
    return r;
  }
  for (int y = 0; y < reference.height; ++y) {
    for (int x = 0; x < reference.width; ++x) {
      const int error =
          std::max(neighbourhood_error(reference, ours, x, y), neighbourhood_error(ours, reference, x, y));
      const std::uint8_t* p = reference.pixel(x, y);
      const std::uint8_t* q = ours.pixel(x, y);
      int raw = 0;
      for (int c = 0; c < 4; ++c) raw = std::max(raw, std::abs(p[c] - q[c]));
      r.max_error = std::max(r.max_error, error);
      if (error > rule.small) ++r.off;
      if (raw > rule.large) ++r.far_off;
      if (diff) {
        std::uint8_t* out = diff->pixel(x, y);
        if (raw > rule.large) {
          out[0] = 255, out[1] = 0, out[2] = 0;
        } else if (error > rule.small) {
          out[0] = 255, out[1] = 150, out[2] = 0;
        } else {
          // The reference's luminance over white, faded to a quarter, so the shapes stay recognisable.
          const int luma = (p[0] * 54 + p[1] * 183 + p[2] * 19) >> 8;  // premultiplied: over black
          const int over_white = luma + (255 - p[3]);
          const auto grey = static_cast<std::uint8_t>(255 - (255 - over_white) / 4);
          out[0] = out[1] = out[2] = grey;
        }
        out[3] = 255;
      }
    }
  }
  const double allowed = rule.allowed_fraction * static_cast<double>(r.pixels);
  r.passed = static_cast<double>(r.off) <= allowed && static_cast<double>(r.far_off) <= allowed;
  return r;
}

int run_compare(int argc, char** argv) {
  std::string reference, ours, diff_path;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--diff") {
      if (i + 1 >= argc) throw UsageError{"--diff needs a file name"};
      diff_path = argv[++i];
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError{"compare: unknown option '" + std::string(arg) + "'"};
    } else if (reference.empty()) {
      reference = arg;
    } else if (ours.empty()) {
      ours = arg;
    } else {
      throw UsageError{"compare: more than two images given"};
    }
  }
  if (ours.empty()) throw UsageError{"compare: needs REFERENCE.png and OURS.png"};
  const Image a = read_png(reference);
  const Image b = read_png(ours);
  Image diff;
  const CompareResult r = compare_images(a, b, CompareRule{}, diff_path.empty() ? nullptr : &diff);
  if (!diff_path.empty()) write_png(diff_path, diff);
  std::printf("%s pixels=%lld off=%lld far_off=%lld max_error=%d%s\n", r.passed ? "pass" : "fail",
              static_cast<long long>(r.pixels), static_cast<long long>(r.off), static_cast<long long>(r.far_off),
              r.max_error, r.same_size ? "" : " size_mismatch");
  return r.passed ? 0 : 1;
}

}  // namespace vraster::cli
