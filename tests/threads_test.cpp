// Threaded rasterization (Rasterizer::set_threads, Renderer::set_threads, Canvas::set_threads) against one thread on
// seeded random scenes: large polygons, curves, strokes, many small shapes, for every anti-aliasing mode and fill
// rule, with 1, 2, 3 and 7 threads. Bands must not change a single bit: the pixels are compared byte for byte, and
// for the analytic sweep the coverage calls themselves (every row's spans and rows, in order) must be the same.
// Each case also checks that the large fills were really cut into bands (Rasterizer::last_fill_bands), so the
// comparison cannot pass by running everything on one thread.
#include <gtest/gtest.h>

#include <map>
#include <mutex>
#include <random>
#include <tuple>

#include "vraster/canvas.hpp"
#include "vraster/renderer.hpp"
#include "vraster/stroke.hpp"

namespace vraster::test {
namespace {

constexpr AntiAlias kModes[] = {AntiAlias::None,  AntiAlias::Analytic, AntiAlias::Exact, AntiAlias::Ssaa2,
                                AntiAlias::Ssaa4, AntiAlias::Ssaa16,   AntiAlias::Msaa4, AntiAlias::Msaa8,
                                AntiAlias::Msaa16};
constexpr FillRule kRules[] = {FillRule::EvenOdd,  FillRule::NonZero, FillRule::NonExterior,
                               FillRule::Positive, FillRule::Negative, FillRule::AbsGeq2};
constexpr int kThreadCounts[] = {2, 3, 7};
constexpr int kSide = 300;

// Random polygons, curved paths, strokes and small shapes on a kSide x kSide device, some reaching outside it.
std::vector<Path> random_scene(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-40, kSide + 40), small(0, 12), unit(0, 1);
  std::vector<Path> paths;
  for (int i = 0; i < 6; ++i) {  // large self-crossing polygons
    Path p;
    p.move_to({coord(rng), coord(rng)});
    const int n = 3 + static_cast<int>(rng() % 30);
    for (int k = 0; k < n; ++k) p.line_to({coord(rng), coord(rng)});
    p.close();
    paths.push_back(p);
  }
  for (int i = 0; i < 4; ++i) {  // curves, with a second contour
    Path p;
    for (int c = 0; c < 2; ++c) {
      p.move_to({coord(rng), coord(rng)});
      p.cubic_to({coord(rng), coord(rng)}, {coord(rng), coord(rng)}, {coord(rng), coord(rng)});
      p.quad_to({coord(rng), coord(rng)}, {coord(rng), coord(rng)});
      p.close();
    }
    paths.push_back(p);
  }
  for (int i = 0; i < 3; ++i) {  // strokes, thin and thick
    Path line;
    line.move_to({coord(rng), coord(rng)});
    line.cubic_to({coord(rng), coord(rng)}, {coord(rng), coord(rng)}, {coord(rng), coord(rng)});
    line.line_to({coord(rng), coord(rng)});
    StrokeStyle style;
    style.width = i == 0 ? 0.7 : 3 + 20 * unit(rng);
    style.join = LineJoin::Round;
    paths.push_back(stroke_to_path(line, style, 0.1));
  }
  for (int i = 0; i < 20; ++i) {  // small shapes: one thread
    Path p;
    const Point o{coord(rng), coord(rng)};
    p.move_to(o);
    p.line_to({o.x + small(rng), o.y + small(rng)});
    p.line_to({o.x - small(rng), o.y + small(rng)});
    p.close();
    paths.push_back(p);
  }
  return paths;
}

Color random_color(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0, 1);
  return {u(rng), u(rng), u(rng), rng() % 3 == 0 ? 1.0f : 0.2f + 0.7f * u(rng)};
}

// Every coverage call, kept per row in the order it came (rows of different bands arrive from different threads).
class CallRecorder final : public CoverageSink {
 public:
  using Call = std::tuple<int, int, std::vector<float>>;  // x0, x1, coverage (one value for a span)
  void span(int y, int x0, int x1, float coverage) override { add(y, {x0, x1, {coverage}}); }
  void row(int y, int x0, int x1, const float* coverage) override {
    add(y, {x0, x1, std::vector<float>(coverage, coverage + (x1 - x0))});
  }
  bool takes_concurrent_rows() const override { return true; }
  std::map<int, std::vector<Call>> rows;

 private:
  void add(int y, Call call) {
    const std::lock_guard<std::mutex> lock(mutex_);
    rows[y].push_back(std::move(call));
  }
  std::mutex mutex_;
};

// Draws the scene with a Renderer of `threads` threads; counts the fills that were cut into bands.
Image render(const std::vector<Path>& scene, std::uint32_t seed, FillRule rule, AntiAlias aa, int threads,
             int& banded) {
  Image image(kSide, kSide);
  image.clear(Color{1, 1, 1, 1});
  Renderer renderer;
  renderer.set_threads(threads);
  std::mt19937 rng(seed);
  for (const Path& p : scene) {
    renderer.fill(image, p, Affine{}, random_color(rng), FillOptions{rule, aa, 0.1});
    if (renderer.rasterizer().last_fill_bands() > 1) ++banded;
  }
  return image;
}

TEST(Threads, FillsAreBitIdenticalForEveryModeRuleAndThreadCount) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const std::vector<Path> scene = random_scene(seed);
    for (const AntiAlias aa : kModes) {
      for (const FillRule rule : kRules) {
        int banded = 0;
        const Image one = render(scene, seed, rule, aa, 1, banded);
        EXPECT_EQ(banded, 0);
        for (const int threads : kThreadCounts) {
          int banded_n = 0;
          const Image many = render(scene, seed, rule, aa, threads, banded_n);
          EXPECT_TRUE(one.data == many.data) << "seed " << seed << ", " << to_string(aa) << ", " << to_string(rule)
                                             << ", " << threads << " threads";
          // The exact boundary sweep is not banded; every other mode must have banded the large fills.
          if (aa != AntiAlias::Exact) {
            EXPECT_GT(banded_n, 0) << to_string(aa) << ", " << to_string(rule);
          }
        }
      }
    }
  }
}

TEST(Threads, AnalyticCoverageCallsAreTheSameRowByRow) {
  for (std::uint32_t seed = 10; seed < 14; ++seed) {
    for (const Path& p : random_scene(seed)) {
      for (const FillRule rule : {FillRule::NonZero, FillRule::EvenOdd, FillRule::AbsGeq2}) {
        Polylines lines;
        flatten(p, Affine{}, FlattenOptions{}, lines);
        CallRecorder one, many;
        Rasterizer r1, r3;
        r3.set_threads(3);
        r1.fill(lines, rule, AntiAlias::Analytic, kSide, kSide, one);
        r3.fill(lines, rule, AntiAlias::Analytic, kSide, kSide, many);
        EXPECT_TRUE(one.rows == many.rows) << "seed " << seed << ", " << to_string(rule);
      }
    }
  }
}

// A sink that needs its calls in order is never given bands.
TEST(Threads, OrderedSinksGetOneThread) {
  class Ordered final : public CoverageSink {
   public:
    void span(int y, int, int, float) override { check(y); }
    void row(int y, int, int, const float*) override { check(y); }
    void check(int y) {
      if (y < last_) out_of_order = true;
      last_ = y;
    }
    bool out_of_order = false;

   private:
    int last_ = -1;
  };
  Path big;
  big.move_to({0, 0});
  big.line_to({kSide, 10});
  big.line_to({20, kSide});
  big.close();
  Polylines lines;
  flatten(big, Affine{}, FlattenOptions{}, lines);
  Rasterizer r;
  r.set_threads(4);
  Ordered sink;
  r.fill(lines, FillRule::NonZero, AntiAlias::Analytic, kSide, kSide, sink);
  EXPECT_EQ(r.last_fill_bands(), 1);
  EXPECT_FALSE(sink.out_of_order);
  CallRecorder concurrent;
  r.fill(lines, FillRule::NonZero, AntiAlias::Analytic, kSide, kSide, concurrent);
  EXPECT_GT(r.last_fill_bands(), 1);
}

// The canvas: solid fills, strokes, a path clip (its mask is rasterized in bands too), a layer with opacity, a
// gradient (one thread: it shades into a shared buffer) and an unbounded operator (one thread: rows in order).
template <class T>
std::vector<T> draw_canvas(std::uint32_t seed, AntiAlias aa, int threads) {
  BasicImage<T> image(kSide, kSide);
  image.clear(Color{1, 1, 1, 1});
  Canvas c(image);
  c.set_threads(threads);
  EXPECT_EQ(c.threads(), threads);
  c.set_anti_alias(aa);
  std::mt19937 rng(seed);
  const std::vector<Path> scene = random_scene(seed);
  for (std::size_t i = 0; i < scene.size(); ++i) {
    if (i == 3) {
      c.save();
      c.clip(scene[0], FillRule::EvenOdd);
    }
    if (i == 5) c.begin_layer(0.6f);
    if (i == 7) {
      Paint g = Paint::linear({0, 0}, {kSide, kSide});
      g.add_stop(0, Color{1, 0, 0, 1});
      g.add_stop(1, Color{0, 0, 1, 0.5f});
      c.set_fill_paint(g);
    } else {
      c.set_fill_color(random_color(rng));
    }
    if (i == 9) c.set_composite(CompositeOp::SourceIn);
    c.fill(scene[i], i % 2 ? FillRule::NonZero : FillRule::EvenOdd);
    if (i == 9) c.set_composite(CompositeOp::SourceOver);
    if (i == 10) c.end_layer();
    if (i == 12) c.restore();
  }
  c.set_line_width(6);
  c.set_stroke_color(Color{0, 0.5f, 0, 0.8f});
  c.stroke(scene[1]);
  return image.data;
}

TEST(Threads, CanvasDrawingIsBitIdentical) {
  for (std::uint32_t seed = 20; seed < 23; ++seed) {
    for (const AntiAlias aa : {AntiAlias::Analytic, AntiAlias::None, AntiAlias::Exact, AntiAlias::Msaa8}) {
      const auto one8 = draw_canvas<std::uint8_t>(seed, aa, 1);
      const auto one16 = draw_canvas<std::uint16_t>(seed, aa, 1);
      for (const int threads : kThreadCounts) {
        EXPECT_TRUE(one8 == draw_canvas<std::uint8_t>(seed, aa, threads))
            << "8-bit, seed " << seed << ", " << to_string(aa) << ", " << threads << " threads";
        EXPECT_TRUE(one16 == draw_canvas<std::uint16_t>(seed, aa, threads))
            << "16-bit, seed " << seed << ", " << to_string(aa) << ", " << threads << " threads";
      }
    }
  }
}

TEST(Threads, ThreadCountIsClamped) {
  Rasterizer r;
  EXPECT_EQ(r.threads(), 1);
  r.set_threads(0);
  EXPECT_EQ(r.threads(), 1);
  r.set_threads(1000);
  EXPECT_EQ(r.threads(), 64);
  r.set_threads(2);
  EXPECT_EQ(r.threads(), 2);
  Rasterizer moved = std::move(r);  // the workers move with the rasterizer
  EXPECT_EQ(moved.threads(), 2);
}

}  // namespace
}  // namespace vraster::test
