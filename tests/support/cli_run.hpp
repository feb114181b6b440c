// Test support: running the `vraster` command (the binary VRASTER_CLI names) and checking the images it writes
// pixel by pixel against maps drawn by hand (one letter per pixel).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "vraster/image.hpp"
#include "vraster/png.hpp"

namespace vraster::test {

inline std::string work_dir() {
  std::filesystem::create_directories(VRASTER_TEST_OUT);
  return VRASTER_TEST_OUT;
}

inline std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = work_dir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

/// Runs the vraster binary with `args` (shell words); returns its exit status, its output in `log`.
inline int run_vraster(const std::string& args, std::string& log) {
  const std::string command = std::string("'") + VRASTER_CLI + "' " + args + " 2>&1";
  log.clear();
  FILE* p = popen(command.c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) log.append(buf, n);
  const int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/// Renders `args` to `out` (removed first) and reads it back; a failed run fails the test.
inline Image run_to_png(const std::string& args, const std::string& out) {
  std::filesystem::remove(out);
  std::string log;
  const int status = run_vraster(args + " -o '" + out + "'", log);
  EXPECT_EQ(status, 0) << args << "\n" << log;
  if (status != 0 || !std::filesystem::exists(out)) return Image{};
  return read_png(out);
}

struct Rgba {
  int r, g, b, a;
};

inline std::string describe(const std::uint8_t* p) {
  // Appended piece by piece: "(" + std::to_string(...) trips GCC 12's false -Wrestrict warning.
  std::string s = "(";
  for (int c = 0; c < 4; ++c) s.append(std::to_string(p[c])).append(c < 3 ? "," : ")");
  return s;
}

/// Every pixel of `image` equals the colour its letter in `map` stands for (one string per row).
inline void expect_pixels(const Image& image, const std::vector<std::string>& map,
                   const std::vector<std::pair<char, Rgba>>& legend, const std::string& what) {
  ASSERT_EQ(image.height, static_cast<int>(map.size())) << what;
  ASSERT_EQ(image.width, static_cast<int>(map[0].size())) << what;
  int wrong = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      Rgba want{-1, -1, -1, -1};
      for (const auto& [letter, c] : legend) {
        if (letter == map[y][x]) want = c;
      }
      const std::uint8_t* p = image.pixel(x, y);
      if (p[0] != want.r || p[1] != want.g || p[2] != want.b || p[3] != want.a) {
        if (++wrong <= 8) ADD_FAILURE() << what << ": pixel (" << x << ", " << y << ") is " << describe(p)
                                        << ", expected '" << map[y][x] << "'";
      }
    }
  }
  EXPECT_EQ(wrong, 0) << what;
}

// Three pixel-aligned rectangles on an 8 x 6 canvas and the image they must give: every antialiasing mode but fxaa
// (a post-filter that blurs colour edges on purpose) covers each pixel fully or not at all.
inline const char* const kRects = R"(<svg xmlns="http://www.w3.org/2000/svg" width="8" height="6">
  <rect x="1" y="1" width="3" height="2" fill="#ff0000"/>
  <rect x="4" y="2" width="3" height="3" fill="#0000ff"/>
  <path d="M2 4h1v1h-1z" fill="#00ff00"/>
</svg>
)";
inline const std::vector<std::string> kRectsMap = {
    "........",  //
    ".RRR....",  //
    ".RRRBBB.",  //
    "....BBB.",  //
    "..G.BBB.",  //
    "........",  //
};

}  // namespace vraster::test
