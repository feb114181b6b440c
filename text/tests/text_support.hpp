// Helpers shared by the text tests.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "vraster/image.hpp"

namespace vraster::text::testing {

inline std::string shared_font(const std::string& file) {
  return std::string(VRASTER_SOURCE_DIR) + "/../shared/conformance/fonts/" + file;
}
inline std::string repo_font(const std::string& file) { return std::string(VRASTER_SOURCE_DIR) + "/text/fonts/" + file; }

inline std::string out_dir() {
  std::filesystem::create_directories(VRASTER_TEXT_TEST_OUT);
  return VRASTER_TEXT_TEST_OUT;
}

/// Runs a shell command; returns its standard output, sets `status` to its exit status (-1 when it did not run).
inline std::string run_command(const std::string& command, int& status) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (!p) {
    status = -1;
    return out;
  }
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int rc = pclose(p);
  status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return out;
}

inline bool have_program(const std::string& name) {
  int status = 0;
  run_command("command -v " + name + " >/dev/null 2>&1", status);
  return status == 0;
}

/// Ink per pixel in [0, 1]: alpha for images on transparent, darkness for black-on-white images.
inline std::vector<double> ink_of(const Image& image, bool on_white) {
  std::vector<double> ink(static_cast<std::size_t>(image.width) * image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto* p = image.pixel(x, y);
      ink[static_cast<std::size_t>(y) * image.width + x] =
          on_white ? 1.0 - (p[0] + p[1] + p[2]) / (3.0 * 255.0) : p[3] / 255.0;
    }
  }
  return ink;
}

struct InkStats {
  double total = 0, cx = 0, cy = 0;
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;  // box of pixels with ink > 0 (inclusive)
};

inline InkStats ink_stats(const std::vector<double>& ink, int width, int height) {
  InkStats s;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double v = ink[static_cast<std::size_t>(y) * width + x];
      if (v <= 0) continue;
      s.total += v;
      s.cx += v * (x + 0.5);
      s.cy += v * (y + 0.5);
      s.x0 = std::min(s.x0, x), s.y0 = std::min(s.y0, y), s.x1 = std::max(s.x1, x), s.y1 = std::max(s.y1, y);
    }
  }
  if (s.total > 0) s.cx /= s.total, s.cy /= s.total;
  return s;
}

}  // namespace vraster::text::testing
