// Benchmark scenes made in the program (vraster_bench --generated): shapes the shared scenes lack (circles, rings,
// ellipses, rectangles, turned rectangles translucent and opaque, opaque triangles, thin lines), so a speed-up can
// be checked beyond the scenes it was tuned on. Each is SVG text of 1024x1024 px, the same on every machine
// (std::mt19937 is fully specified, and its numbers are mapped to coordinates without the library's distributions,
// which are not).
#pragma once

#include <string>
#include <vector>

namespace bench {

struct GeneratedScene {
  std::string name;
  std::string svg;
};

std::vector<GeneratedScene> generated_scenes();

}  // namespace bench
