// Sample: the smallest program against an installed vraster (C++ core API): a red disc on white, written to a
// PNG, and the colours of two pixels printed (the package test compares them).
//
//   hello_vraster [OUT.png]
#include <cstdio>
#include <string>

#include "vraster/vraster.hpp"

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "hello_vraster.png";
  try {
    vraster::Image image(64, 64);
    image.clear(vraster::Color::rgb8(255, 255, 255));
    vraster::Path disc;
    disc.add_circle({32, 32}, 20);
    vraster::Renderer renderer;
    renderer.fill(image, disc, {}, vraster::Color::rgb8(255, 0, 0), {});
    vraster::write_png(out, image);
    for (const auto& [x, y] : {std::pair{32, 32}, std::pair{2, 2}}) {
      const std::uint8_t* p = image.pixel(x, y);
      std::printf("pixel %d,%d = %d %d %d %d\n", x, y, p[0], p[1], p[2], p[3]);
    }
    return 0;
  } catch (const vraster::Error& e) {
    std::fprintf(stderr, "hello_vraster: %s\n", e.what());
    return 2;
  }
}
