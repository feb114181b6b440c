// Helpers shared by the text tests.
#pragma once

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "vraster/image.hpp"

namespace vraster::text::testing {

/// A font file a Debian package installs (scripts/setup.sh installs every package named here).
struct SystemFont {
  const char* path;     ///< where the package installs it (`dpkg -L PACKAGE`)
  const char* package;  ///< the Debian package
};

// The tests' fonts beyond the embedded default (text/fonts/NotoSans-Regular.ttf): none comes from ../shared, so a
// bare clone passes its tests on a machine set up by scripts/setup.sh.
inline constexpr SystemFont kNotoSerif{"/usr/share/fonts/truetype/noto/NotoSerif-Regular.ttf", "fonts-noto-core"};
inline constexpr SystemFont kNotoSansDevanagari{"/usr/share/fonts/truetype/noto/NotoSansDevanagari-Regular.ttf",
                                                "fonts-noto-core"};
inline constexpr SystemFont kAmiri{"/usr/share/fonts/opentype/fonts-hosny-amiri/Amiri-Regular.ttf",
                                   "fonts-hosny-amiri"};
inline constexpr SystemFont kCantarellCff{"/usr/share/fonts/opentype/cantarell/Cantarell-Regular.otf",
                                          "fonts-cantarell"};  // OpenType with CFF outlines
inline constexpr SystemFont kWqyMicroHeiCollection{"/usr/share/fonts/truetype/wqy/wqy-microhei.ttc",
                                                   "fonts-wqy-microhei"};  // a TrueType collection of two faces
inline constexpr SystemFont kNotoColorEmoji{"/usr/share/fonts/truetype/noto/NotoColorEmoji.ttf",
                                            "fonts-noto-color-emoji"};  // CBDT/CBLC colour bitmaps, no outlines

/// A test resource that is not there: the test fails with this message (never a crash, never a silent skip).
struct MissingResource : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The path of `font`; throws MissingResource, naming the file and its package, when it is not installed.
inline std::string system_font(const SystemFont& font) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(font.path, ec)) {
    throw MissingResource(std::string("test font ") + font.path + " is missing: install the Debian package " +
                          font.package + " (bash scripts/setup.sh installs it)");
  }
  return font.path;
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

/// Throws MissingResource, naming the program and its Debian package, unless `name` is on the PATH.
inline void require_program(const std::string& name, const std::string& package) {
  if (!have_program(name)) {
    throw MissingResource("reference program " + name + " is missing: install the Debian package " + package +
                          " (bash scripts/setup.sh installs it)");
  }
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
