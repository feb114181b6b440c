// The rasterizer blends most runs straight into a SolidCompositor's pixels (CoverageSink::solid_over8: every row of
// the dense sweep, and the row sweep's narrow rows and sparse rows' clusters), from its cells, without a coverage row
// in between. The pixels must be exactly those of the same fill handed to the compositor as spans and rows: the same
// compositor behind a sink that forwards the calls and does not offer its pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "raster/cpu.hpp"
#include "vraster/renderer.hpp"

namespace vraster {
namespace {

// A SolidCompositor that only takes coverage (span, row, rows): what every fill did before blend_cells.
class CoverageOnly final : public CoverageSink {
 public:
  CoverageOnly(Image& image, Color color) : inner_(image, color) {}
  void span(int y, int x0, int x1, float coverage) override { inner_.span(y, x0, x1, coverage); }
  void row(int y, int x0, int x1, const float* coverage) override { inner_.row(y, x0, x1, coverage); }
  void rows(const CoverageRow* rows, std::size_t count) override { inner_.rows(rows, count); }
  bool takes_concurrent_rows() const override { return true; }

 private:
  SolidCompositor<std::uint8_t> inner_;
};

// A random scene of `shapes` fills: discs, rings (even-odd), turned rectangles, triangles and ellipses, from a few
// pixels to larger than the image, some crossing its sides; every fill in its own colour, opaque or translucent,
// onto a noisy background.
struct Scene {
  std::vector<Polylines> fills;
  std::vector<FillRule> rules;
  std::vector<Color> colors;
};

Scene random_scene(std::uint32_t seed, int w, int h, int shapes) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  Scene scene;
  for (int i = 0; i < shapes; ++i) {
    const double cx = -30 + (w + 60) * unit(rng), cy = -30 + (h + 60) * unit(rng);
    const double size = unit(rng) < 0.3 ? 3 + 20 * unit(rng) : 20 + 200 * unit(rng);
    Path path;
    FillRule rule = FillRule::NonZero;
    switch (i % 5) {
      case 0:
        path.add_circle({cx, cy}, size);
        break;
      case 1:  // a ring: four pieces a row
        path.add_circle({cx, cy}, size);
        path.add_circle({cx, cy}, size * (0.5 + 0.4 * unit(rng)));
        rule = FillRule::EvenOdd;
        break;
      case 2: {
        // (a third of them slivers 0.01 to 0.5 px wide: the dense sweep of thin shapes)
        const double turn = 3.14159 * unit(rng), a = size;
        const double b = unit(rng) < 0.3 ? 0.005 + 0.25 * unit(rng) : size * (0.05 + unit(rng));
        const double c = std::cos(turn), s = std::sin(turn);
        path.move_to(cx + a * c - b * s, cy + a * s + b * c);
        path.line_to(cx - a * c - b * s, cy - a * s + b * c);
        path.line_to(cx - a * c + b * s, cy - a * s - b * c);
        path.line_to(cx + a * c + b * s, cy + a * s - b * c);
        path.close();
        break;
      }
      case 3:
        path.move_to(cx, cy);
        path.line_to(cx + size * (unit(rng) - 0.5) * 2, cy + size * (unit(rng) - 0.5) * 2);
        path.line_to(cx + size * (unit(rng) - 0.5) * 2, cy + size * (unit(rng) - 0.5) * 2);
        path.close();
        break;
      default:
        path.add_ellipse({cx, cy}, size, size * (0.2 + 0.8 * unit(rng)));
        break;
    }
    Polylines lines;
    flatten(path, Affine::rotate(90 * unit(rng), w / 2.0, h / 2.0), FlattenOptions{}, lines);
    scene.fills.push_back(std::move(lines));
    scene.rules.push_back(rule);
    const float alpha = unit(rng) < 0.4 ? 1.f : static_cast<float>(0.05 + 0.9 * unit(rng));
    scene.colors.push_back(Color{static_cast<float>(unit(rng)), static_cast<float>(unit(rng)),
                                 static_cast<float>(unit(rng)), alpha});
  }
  return scene;
}

Image background(int w, int h, std::uint32_t seed) {
  Image image(w, h);
  std::mt19937 rng(seed);
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    const std::uint8_t a = static_cast<std::uint8_t>(rng() % 256);
    for (int c = 0; c < 3; ++c) image.data[i + c] = static_cast<std::uint8_t>(rng() % (a + 1));  // premultiplied
    image.data[i + 3] = a;
  }
  return image;
}

// Draws the scene into `image`, each fill through SolidCompositor itself (blended from the cells where the rasterizer
// may) or through CoverageOnly.
void draw(const Scene& scene, Image& image, bool coverage_only, int threads) {
  Rasterizer r;
  r.set_threads(threads);
  for (std::size_t i = 0; i < scene.fills.size(); ++i) {
    if (coverage_only) {
      CoverageOnly sink(image, scene.colors[i]);
      r.fill(scene.fills[i], scene.rules[i], AntiAlias::Analytic, image.width, image.height, sink);
    } else {
      SolidCompositor<std::uint8_t> sink(image, scene.colors[i]);
      r.fill(scene.fills[i], scene.rules[i], AntiAlias::Analytic, image.width, image.height, sink);
    }
  }
}

TEST(BlendCells, PixelsBlendedFromTheCellsAreThoseOfTheCoverageRows) {
  if (!detail::cpu_has_avx2()) {
    std::printf("note: no AVX2 here, so both sides take the coverage rows\n");
  }
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    const int w = 97 + static_cast<int>(seed * 37 % 400), h = 60 + static_cast<int>(seed * 53 % 300);
    const Scene scene = random_scene(seed, w, h, 40);
    for (const int threads : {1, 2}) {
      Image fused = background(w, h, seed), rows = background(w, h, seed);
      draw(scene, fused, false, threads);
      draw(scene, rows, true, threads);
      ASSERT_EQ(fused.data, rows.data) << "seed " << seed << ", " << threads << " threads";
    }
  }
}

// Not every pixel the same colour: the scenes above draw something (a test comparing two blank images passes
// whatever the blend does).
TEST(BlendCells, TheScenesDrawMostOfTheImage) {
  const Scene scene = random_scene(5, 300, 200, 40);
  Image image = background(300, 200, 5);
  const Image before = image;
  draw(scene, image, false, 1);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    changed += std::memcmp(&image.data[i], &before.data[i], 4) != 0 ? 1 : 0;
  }
  EXPECT_GT(changed, image.data.size() / 4 / 2);
}

}  // namespace
}  // namespace vraster
