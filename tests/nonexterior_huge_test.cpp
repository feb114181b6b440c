// Regression (found by fuzz_canvas): NonExterior finds its boundary on unclipped edges, which may lie far beyond
// 64-bit row numbers (1e300); the sweep must neither convert such heights to integers nor lose the fill.
#include <gtest/gtest.h>

#include "vraster/renderer.hpp"

using namespace vraster;

TEST(NonExteriorHugeCoordinates, AShapeReachingFarBeyondTheImageCoversIt) {
  for (const double far : {1e300, 1e200, 1e19}) {
    Path path;
    path.add_rect({-far, -far, far, far});
    path.add_rect({2, 2, 6, 6});  // an inner contour: no hole under NonExterior
    for (const AntiAlias aa : {AntiAlias::Analytic, AntiAlias::Exact, AntiAlias::None}) {
      Image image(8, 8);
      Renderer renderer;
      renderer.fill(image, path, {}, Color{0, 0, 1, 1}, {FillRule::NonExterior, aa});
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) ASSERT_EQ(image.pixel(x, y)[3], 255) << far << " at " << x << "," << y;
      }
    }
  }
}

TEST(NonExteriorHugeCoordinates, FarAwayGeometryLeavesTheImageAlone) {
  Path path;
  path.add_rect({1e300, 1e300, 2e300, 2e300});
  path.move_to(-1e300, 3).line_to(1e300, 3).line_to(1e300, 1e300).close();
  Image image(8, 8);
  Renderer renderer;
  renderer.fill(image, path, {}, Color{0, 0, 1, 1}, {FillRule::NonExterior, AntiAlias::Exact});
  // Near the image the triangle lies between its top edge y = 3 and its long edge from (-1e300, 3) to
  // (1e300, 1e300), which passes x = 0 at y ~ 5e299: rows 3 and below are covered, rows above it are not.
  EXPECT_EQ(image.pixel(0, 1)[3], 0);
  EXPECT_EQ(image.pixel(4, 5)[3], 255);
}
