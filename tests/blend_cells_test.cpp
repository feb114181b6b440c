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
#include "vraster/canvas.hpp"
#include "vraster/composite.hpp"
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
  std::vector<Path> paths;  // each drawn under its own transform
  std::vector<Affine> transforms;
  std::vector<Polylines> fills;  // the paths flattened under their transforms
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
    const Affine turn = Affine::rotate(90 * unit(rng), w / 2.0, h / 2.0);
    Polylines lines;
    flatten(path, turn, FlattenOptions{}, lines);
    scene.fills.push_back(std::move(lines));
    scene.paths.push_back(std::move(path));
    scene.transforms.push_back(turn);
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


// The canvas's Compositor offers its pixels too, under a solid paint, source-over and global alpha 1. Drawn into a
// view of the whole image (the rasterizer blends) and into a view of part of it (it must not: the view does not
// start at the fill's (0, 0); the compositor clips the rows), against the same compositor fed coverage only.
class CompositorCoverageOnly final : public CoverageSink {
 public:
  explicit CompositorCoverageOnly(Compositor<std::uint8_t>& inner) : inner_(inner) {}
  void span(int y, int x0, int x1, float coverage) override { inner_.span(y, x0, x1, coverage); }
  void row(int y, int x0, int x1, const float* coverage) override { inner_.row(y, x0, x1, coverage); }
  bool takes_concurrent_rows() const override { return true; }

 private:
  Compositor<std::uint8_t>& inner_;
};

TEST(BlendCells, CompositorWithASolidPaintGivesTheCoverageRowsPixels) {
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    const int w = 150 + static_cast<int>(seed * 41 % 300), h = 90 + static_cast<int>(seed * 29 % 200);
    const Scene scene = random_scene(seed + 100, w, h, 40);
    for (const bool part : {false, true}) {
      Image fused = background(w, h, seed), rows = background(w, h, seed);
      Rasterizer r;
      r.set_threads(seed % 2 + 1);
      for (std::size_t i = 0; i < scene.fills.size(); ++i) {
        for (Image* image : {&fused, &rows}) {
          ImageView<std::uint8_t> view = ImageView<std::uint8_t>::of(*image);
          if (part) {  // rows 7 .. h - 5, columns 11 .. w - 3
            view = {image->pixel(11, 7), 11, 7, w - 14, h - 12, view.stride};
          }
          Compositor<std::uint8_t> compositor;
          compositor.set(view, Paint::solid(scene.colors[i]), Affine{}, CompositeOp::SourceOver);
          SolidOver8 offered;
          EXPECT_EQ(compositor.solid_over8(offered), true) << "a solid paint, source-over, alpha 1";
          if (image == &fused) {
            r.fill(scene.fills[i], scene.rules[i], AntiAlias::Analytic, w, h, compositor);
          } else {
            CompositorCoverageOnly sink(compositor);
            r.fill(scene.fills[i], scene.rules[i], AntiAlias::Analytic, w, h, sink);
          }
        }
      }
      ASSERT_EQ(fused.data, rows.data) << "seed " << seed << (part ? ", a view of part of the image" : "");
    }
  }
}

// Only where row() would give the same pixels: not under a global alpha below 1, another operator or a gradient.
TEST(BlendCells, CompositorOffersItsPixelsOnlyForASolidColourOverAtFullAlpha) {
  Image image(8, 8);
  Compositor<std::uint8_t> c;
  SolidOver8 t;
  const Color red{1, 0, 0, 0.5f};
  c.set(ImageView<std::uint8_t>::of(image), Paint::solid(red), Affine{}, CompositeOp::SourceOver, 1);
  EXPECT_TRUE(c.solid_over8(t));
  EXPECT_EQ(t.width, 8);
  c.set(ImageView<std::uint8_t>::of(image), Paint::solid(red), Affine{}, CompositeOp::SourceOver, 0.5f);
  EXPECT_FALSE(c.solid_over8(t));
  c.set(ImageView<std::uint8_t>::of(image), Paint::solid(red), Affine{}, CompositeOp::Multiply, 1);
  EXPECT_FALSE(c.solid_over8(t));
  Paint ramp = Paint::linear({0, 0}, {8, 0});
  ramp.add_stop(0, red);
  ramp.add_stop(1, Color{0, 0, 1, 1});
  c.set(ImageView<std::uint8_t>::of(image), ramp, Affine{}, CompositeOp::SourceOver, 1);
  EXPECT_FALSE(c.solid_over8(t));
}

// Through the canvas: fills under a pixel-aligned clip (the clip box only: the rasterizer blends, at the region's
// corner), in a layer (a view that starts inside the image), on 1 and 2 threads, against the same drawing under one
// more clip that leaves a mask (a notch off pixel (0, 0)), which is full on every other pixel and keeps the
// compositor's coverage rows. Every pixel but (0, 0) must be the same.
void draw_on_canvas(const Scene& scene, Image& image, bool with_mask, bool in_layer, int threads) {
  Canvas canvas(image);
  canvas.set_threads(threads);
  if (with_mask) {
    Path notched;
    notched.move_to(0.5, 0);
    notched.line_to(image.width, 0);
    notched.line_to(image.width, image.height);
    notched.line_to(0, image.height);
    notched.line_to(0, 0.5);
    notched.close();
    canvas.clip(notched, FillRule::NonZero);
  }
  Path aligned;
  aligned.add_rect({6, 4, static_cast<double>(image.width - 9), static_cast<double>(image.height - 2)});
  canvas.clip(aligned, FillRule::NonZero);
  if (in_layer) canvas.begin_layer(1.f);
  for (std::size_t i = 0; i < scene.paths.size(); ++i) {
    canvas.set_transform(scene.transforms[i]);
    canvas.set_fill_color(scene.colors[i]);
    canvas.fill(scene.paths[i], scene.rules[i]);
  }
  if (in_layer) canvas.end_layer();
}

TEST(BlendCells, CanvasFillsAreThoseDrawnThroughAFullClipMask) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    const int w = 120 + static_cast<int>(seed * 67 % 300), h = 80 + static_cast<int>(seed * 31 % 200);
    const Scene scene = random_scene(seed + 200, w, h, 40);
    for (const bool in_layer : {false, true}) {
      for (const int threads : {1, 2}) {
        Image fused = background(w, h, seed), masked = background(w, h, seed);
        draw_on_canvas(scene, fused, false, in_layer, threads);
        draw_on_canvas(scene, masked, true, in_layer, threads);
        std::memcpy(&fused.data[0], &masked.data[0], 4);  // the notch
        ASSERT_EQ(fused.data, masked.data) << "seed " << seed << (in_layer ? ", in a layer" : "") << ", " << threads
                                           << " threads";
      }
    }
  }
}

}  // namespace
}  // namespace vraster
