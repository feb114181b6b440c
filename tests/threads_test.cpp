// Threaded rasterization (Rasterizer::set_threads, Renderer::set_threads, Canvas::set_threads) against one thread on
// seeded random scenes: large polygons, curves, strokes, many small shapes, for every anti-aliasing mode and fill
// rule, with 1, 2, 3 and 7 threads. Bands must not change a single bit: the pixels are compared byte for byte, and
// for the analytic sweep the coverage calls themselves (every row's spans and rows, in order) must be the same.
// Each case also checks that the large fills were really cut into bands (Rasterizer::last_fill_bands), so the
// comparison cannot pass by running everything on one thread.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <random>
#include <tuple>

#include "raster/rasterizer_p.hpp"
#include "vraster/canvas.hpp"
#include "vraster/composite.hpp"
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
  {  // a star of 151 points: about 150 edges in every row, so its rows are crowded (marked touched as a whole)
    Path p;
    const double r = kSide * 0.45 + 10 * unit(rng), phase = unit(rng);
    for (int k = 0; k < 151; ++k) {
      const double a = 2 * 3.141592653589793 * (phase + k * 68 / 151.0);
      const Point q{kSide / 2 + r * std::cos(a), kSide / 2 + r * std::sin(a)};
      if (k == 0) {
        p.move_to(q);
      } else {
        p.line_to(q);
      }
    }
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
  for (int i = 0; i < 3; ++i) {  // slivers across the device: thin shapes, the dense sweep in strips
    Path p;
    const Point a{coord(rng), coord(rng)}, b{coord(rng), coord(rng)};
    p.move_to(a);
    p.line_to(b);
    p.line_to({a.x + 0.6 * unit(rng), a.y + 0.6 * unit(rng)});
    p.close();
    paths.push_back(p);
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

// Draws the scene with a Renderer of `threads` threads (with threads, the fills are queued and drawn by flush());
// counts the fills drawn at once that were cut into bands, and the flushes that were.
template <class T = std::uint8_t>
BasicImage<T> render(const std::vector<Path>& scene, std::uint32_t seed, FillRule rule, AntiAlias aa, int threads,
                     int& banded) {
  BasicImage<T> image(kSide, kSide);
  image.clear(Color{1, 1, 1, 1});
  Renderer renderer;
  renderer.set_threads(threads);
  std::mt19937 rng(seed);
  for (const Path& p : scene) {
    const std::size_t queued = renderer.rasterizer().queued_fills();
    renderer.fill(image, p, Affine{}, random_color(rng), FillOptions{rule, aa, 0.1});
    if (renderer.rasterizer().queued_fills() == queued && renderer.rasterizer().last_fill_bands() > 1) ++banded;
  }
  if (renderer.rasterizer().queued_fills() > 0) {
    renderer.flush();
    if (renderer.rasterizer().last_flush_bands() > 1) ++banded;
  }
  EXPECT_EQ(renderer.rasterizer().queued_fills(), 0u);
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
          // The exact boundary sweep is not banded; every other mode must have banded the large fills (NonExterior
          // fills one by one, the others as one queue).
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

// A triangle across most of the image: it spans many bands.
Path big_triangle() {
  Path p;
  p.move_to({0, 0});
  p.line_to({kSide, 10});
  p.line_to({20, kSide});
  p.close();
  return p;
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
  const Path big = big_triangle();
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

// Queued frames (Renderer::fill with threads, then flush): 16-bit images too, for the modes and rules that queue.
TEST(Threads, QueuedFramesAreBitIdenticalIn16Bits) {
  for (std::uint32_t seed = 30; seed < 32; ++seed) {
    const std::vector<Path> scene = random_scene(seed);
    for (const AntiAlias aa : {AntiAlias::Analytic, AntiAlias::None, AntiAlias::Msaa8, AntiAlias::Ssaa4}) {
      for (const FillRule rule : {FillRule::NonZero, FillRule::EvenOdd, FillRule::Negative}) {
        int banded = 0;
        const Image16 one = render<std::uint16_t>(scene, seed, rule, aa, 1, banded);
        for (const int threads : {2, 5}) {
          int banded_n = 0;
          EXPECT_TRUE(one.data == render<std::uint16_t>(scene, seed, rule, aa, threads, banded_n).data)
              << "seed " << seed << ", " << to_string(aa) << ", " << to_string(rule) << ", " << threads << " threads";
          EXPECT_GT(banded_n, 0);
        }
      }
    }
  }
}

// Hands every call on to a sink that outlives the queue (the queue owns and destroys the sinks it is given).
class Forward final : public CoverageSink {
 public:
  explicit Forward(CoverageSink& to) : to_(to) {}
  void span(int y, int x0, int x1, float coverage) override { to_.span(y, x0, x1, coverage); }
  void row(int y, int x0, int x1, const float* coverage) override { to_.row(y, x0, x1, coverage); }
  bool takes_concurrent_rows() const override { return to_.takes_concurrent_rows(); }

 private:
  CoverageSink& to_;
};

// Every queued fill's coverage calls, row by row, are those of the same fill drawn alone on one thread: the large
// sweeps, the small dense paths (a block of the band's rows only, in each band they cross) and a
// rectangle (recorded, then replayed band by band).
TEST(Threads, QueuedCoverageCallsAreTheSameRowByRow) {
  for (std::uint32_t seed = 40; seed < 43; ++seed) {
    std::vector<Path> scene = random_scene(seed);
    scene.push_back(Path().add_rect({10.5, 20.25, 250, 180.75}));
    scene.push_back(Path().add_rect({-30, -30, kSide + 30, kSide + 30}));
    for (const AntiAlias aa : {AntiAlias::Analytic, AntiAlias::None, AntiAlias::Msaa4}) {
      const FillRule rule = seed % 2 ? FillRule::NonZero : FillRule::EvenOdd;
      std::vector<CallRecorder> alone(scene.size()), queued(scene.size());
      Rasterizer one, many;
      many.set_threads(3);
      std::size_t queued_count = 0;
      for (std::size_t i = 0; i < scene.size(); ++i) {
        Polylines lines;
        flatten(scene[i], Affine{}, FlattenOptions{}, lines);
        one.fill(lines, rule, aa, kSide, kSide, alone[i]);
        const std::size_t before = many.queued_fills();
        many.fill_queued(lines, rule, aa, kSide, kSide, std::make_unique<Forward>(queued[i]));
        if (many.queued_fills() > before) ++queued_count;
      }
      // Nothing of a queued fill has reached its sink yet.
      for (std::size_t i = 0; i < scene.size(); ++i) {
        if (!alone[i].rows.empty() && queued[i].rows.empty()) continue;
        EXPECT_TRUE(alone[i].rows == queued[i].rows) << "fill " << i << " drawn at once differs";
      }
      EXPECT_GT(queued_count, scene.size() / 2);
      many.flush();
      EXPECT_GT(many.last_flush_bands(), 1);
      for (std::size_t i = 0; i < scene.size(); ++i) {
        EXPECT_TRUE(alone[i].rows == queued[i].rows)
            << "seed " << seed << ", " << to_string(aa) << ", fill " << i;
      }
    }
  }
}

// Queued rectangles are recorded with their inside rows once (CoverageRecording::repeat_row) and replayed band by
// band: their calls, row by row, are those of the same rectangle drawn alone, in every mode, for rectangles on row
// lines and between them, inside one row, one row tall, crossing the image's sides and covering it all. A large
// triangle starts the queue, so that the rectangles after it wait in it and are cut into bands.
TEST(Threads, QueuedRectanglesGiveTheCallsOfRectanglesDrawnAlone) {
  std::mt19937 rng(20261207);
  // (every one reaches into the image: one wholly outside draws nothing and is not queued)
  std::uniform_real_distribution<double> coord(-20, kSide - 5), size(25.2, 120);
  std::vector<Path> rects = {Path().add_rect({10, 20, 100, 200}),           // on row and column lines
                             Path().add_rect({10.5, 20.25, 50.75, 20.75}),  // inside one row
                             Path().add_rect({30, 40, 200, 41}),            // one row tall
                             Path().add_rect({-5.5, 100.5, 40.25, 260.75}), // left of the image too
                             Path().add_rect({-30, -30, kSide + 30, kSide + 30})};
  for (int i = 0; i < 40; ++i) {
    const double x = coord(rng), y = coord(rng);
    rects.push_back(Path().add_rect({x, y, x + size(rng), y + size(rng)}));
  }
  Polylines big;
  flatten(big_triangle(), Affine{}, FlattenOptions{}, big);
  for (const AntiAlias aa : kModes) {
    if (aa == AntiAlias::Exact) continue;  // drawn at once, never queued
    std::vector<CallRecorder> alone(rects.size()), queued(rects.size());
    CallRecorder big_alone, big_queued;
    Rasterizer one, many;
    many.set_threads(3);
    one.fill(big, FillRule::NonZero, aa, kSide, kSide, big_alone);
    many.fill_queued(big, FillRule::NonZero, aa, kSide, kSide, std::make_unique<Forward>(big_queued));
    for (std::size_t i = 0; i < rects.size(); ++i) {
      Polylines lines;
      flatten(rects[i], Affine{}, FlattenOptions{}, lines);
      one.fill(lines, FillRule::EvenOdd, aa, kSide, kSide, alone[i]);
      many.fill_queued(lines, FillRule::EvenOdd, aa, kSide, kSide, std::make_unique<Forward>(queued[i]));
    }
    EXPECT_EQ(many.queued_fills(), rects.size() + 1) << to_string(aa);
    many.flush();
    EXPECT_GT(many.last_flush_bands(), 1);
    EXPECT_TRUE(big_alone.rows == big_queued.rows) << to_string(aa);
    for (std::size_t i = 0; i < rects.size(); ++i) {
      EXPECT_FALSE(alone[i].rows.empty()) << to_string(aa) << ", rectangle " << i;
      EXPECT_TRUE(alone[i].rows == queued[i].rows) << to_string(aa) << ", rectangle " << i;
    }
  }
}

// Outlines with NaN or infinite points, or wholly outside the image, wait in the queue like any other (they are
// built at flush): they draw what the same fill draws alone, and the fills around them are unchanged.
TEST(Threads, QueuedFillsWithNonFiniteOrOffImagePointsDrawAsAlone) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  auto polyline = [](std::vector<Point> points) {
    Polylines lines;
    lines.points = std::move(points);
    lines.ends = {static_cast<std::uint32_t>(lines.points.size())};
    lines.closed = {1};
    return lines;
  };
  Polylines big;
  flatten(big_triangle(), Affine{}, FlattenOptions{}, big);
  const std::vector<Polylines> frame = {
      big,
      polyline({{10, 10}, {nan, 200}, {250, 290}}),
      polyline({{-inf, 5}, {290, 150}, {20, inf}}),
      polyline({{-500, -500}, {-400, -300}, {-450, -100}}),   // left of and above the image
      polyline({{5000, 10}, {6000, 200}, {5500, 290}}),       // right of it
      big,
  };
  std::vector<CallRecorder> alone(frame.size()), queued(frame.size());
  Rasterizer one, many;
  many.set_threads(2);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    one.fill(frame[i], FillRule::NonZero, AntiAlias::Analytic, kSide, kSide, alone[i]);
    many.fill_queued(frame[i], FillRule::NonZero, AntiAlias::Analytic, kSide, kSide,
                     std::make_unique<Forward>(queued[i]));
  }
  EXPECT_EQ(many.queued_fills(), frame.size());
  many.flush();
  EXPECT_GT(many.last_flush_bands(), 1);
  for (std::size_t i = 0; i < frame.size(); ++i) EXPECT_TRUE(alone[i].rows == queued[i].rows) << "fill " << i;
  EXPECT_FALSE(queued[0].rows.empty());
  EXPECT_TRUE(queued[4].rows.empty());
}

// The fill that starts a queue keeps the edges fill_queued built to weigh it (flush() does not build them again):
// one inside the image, one partly outside it (clipped), one with a contour that has a NaN point (left out). Each
// is queued, not drawn at once, and gives the calls of drawing it alone; a small fill queued after it does too.
TEST(Threads, TheFillThatStartsTheQueueKeepsItsBuiltEdges) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Polylines inside, clipped, with_nan, small;
  flatten(big_triangle(), Affine{}, FlattenOptions{}, inside);
  flatten(big_triangle(), Affine::translate(-120, 90), FlattenOptions{}, clipped);
  with_nan = inside;
  with_nan.points.insert(with_nan.points.end(), {{30, 30}, {nan, 60}, {90, 40}});
  with_nan.ends.push_back(static_cast<std::uint32_t>(with_nan.points.size()));
  with_nan.closed.push_back(1);
  flatten(big_triangle(), Affine::translate(100, 100) * Affine::scale(0.02, 0.02), FlattenOptions{}, small);
  for (const Polylines* first : {&inside, &clipped, &with_nan}) {
    CallRecorder alone_first, alone_small, queued_first, queued_small;
    Rasterizer one, many;
    many.set_threads(2);
    one.fill(*first, FillRule::EvenOdd, AntiAlias::Analytic, kSide, kSide, alone_first);
    one.fill(small, FillRule::EvenOdd, AntiAlias::Analytic, kSide, kSide, alone_small);
    many.fill_queued(*first, FillRule::EvenOdd, AntiAlias::Analytic, kSide, kSide,
                     std::make_unique<Forward>(queued_first));
    many.fill_queued(small, FillRule::EvenOdd, AntiAlias::Analytic, kSide, kSide,
                     std::make_unique<Forward>(queued_small));
    EXPECT_EQ(many.queued_fills(), 2u);
    EXPECT_TRUE(queued_first.rows.empty());  // nothing drawn before flush()
    many.flush();
    EXPECT_FALSE(alone_first.rows.empty());
    EXPECT_FALSE(alone_small.rows.empty());
    EXPECT_TRUE(alone_first.rows == queued_first.rows);
    EXPECT_TRUE(alone_small.rows == queued_small.rows);
  }
}

// Calls that do not queue (a borrowed sink, hairlines, a mask, a gradient compositor, exact coverage) run after
// what is queued: the painter's order holds, 8 and 16 bits, with paint compositors handed to the queue too.
template <class T>
std::vector<T> draw_mixed(std::uint32_t seed, int threads) {
  BasicImage<T> image(kSide, kSide);
  image.clear(Color{1, 1, 1, 1});
  Renderer renderer;
  renderer.set_threads(threads);
  std::mt19937 rng(seed);
  const std::vector<Path> scene = random_scene(seed);
  const FillOptions options{FillRule::NonZero, AntiAlias::Analytic, 0.1};
  Paint gradient = Paint::linear({0, 0}, {kSide, kSide / 2});
  gradient.add_stop(0, Color{1, 0, 0, 0.8f});
  gradient.add_stop(1, Color{0, 0, 1, 0.4f});
  std::vector<Paint> solids;
  for (std::size_t i = 0; i < scene.size(); ++i) solids.push_back(Paint::solid(random_color(rng)));
  const std::vector<std::uint8_t> mask(40 * 30, 200);
  for (std::size_t i = 0; i < scene.size(); ++i) {
    switch (i % 6) {
      case 0: {  // a paint compositor, handed to the queue
        auto c = std::make_unique<Compositor<T>>();
        c->set(ImageView<T>::of(image), solids[i], Affine{}, CompositeOp::SourceOver);
        renderer.fill(scene[i], Affine{}, options, kSide, kSide, std::move(c));
        break;
      }
      case 1: {  // a gradient: shades into the compositor's own buffer, so it is drawn at once
        Compositor<T> c;
        c.set(ImageView<T>::of(image), gradient, Affine{}, CompositeOp::SourceOver);
        renderer.fill(scene[i], Affine{}, options, kSide, kSide, c);
        break;
      }
      case 2: {
        SolidCompositor<T> c(image, random_color(rng));
        renderer.hairlines(scene[i], Affine{}, HairlineMode::Wu, kSide, kSide, c);
        break;
      }
      case 3: {
        SolidCompositor<T> c(image, Color{0.2f, 0.7f, 0.1f, 0.9f});
        renderer.mask(mask.data(), 40, 30, 40, static_cast<int>(i * 13) % kSide, 50, kSide, kSide, c);
        break;
      }
      case 4:
        renderer.fill(image, scene[i], Affine{}, random_color(rng),
                      FillOptions{FillRule::EvenOdd, AntiAlias::Exact, 0.1});
        break;
      default:
        renderer.fill(image, scene[i], Affine{}, random_color(rng), options);
        break;
    }
  }
  renderer.flush();
  return image.data;
}

TEST(Threads, QueuedFillsKeepThePaintersOrderWithOtherCalls) {
  for (std::uint32_t seed = 50; seed < 53; ++seed) {
    const auto one8 = draw_mixed<std::uint8_t>(seed, 1);
    const auto one16 = draw_mixed<std::uint16_t>(seed, 1);
    for (const int threads : kThreadCounts) {
      EXPECT_TRUE(one8 == draw_mixed<std::uint8_t>(seed, threads)) << "8-bit, seed " << seed << ", " << threads;
      EXPECT_TRUE(one16 == draw_mixed<std::uint16_t>(seed, threads)) << "16-bit, seed " << seed << ", " << threads;
    }
  }
}

// A queued fill changes no pixel until flush(); a small fill with nothing queued before it is drawn at once
// (queueing it would cost more than it saves), after a large one it waits too.
TEST(Threads, QueueWaitsForFlushAndSmallFillsAreDrawnAtOnce) {
  Image image(kSide, kSide);
  image.clear(Color{1, 1, 1, 1});
  const Image white = image;
  Renderer renderer;
  renderer.set_threads(2);
  const FillOptions options;
  Path tiny;
  tiny.move_to({5, 5});
  tiny.line_to({6, 5});
  tiny.line_to({5, 6});
  tiny.close();
  renderer.fill(image, tiny, Affine{}, Color{0, 0, 0, 1}, options);
  EXPECT_EQ(renderer.rasterizer().queued_fills(), 0u);
  EXPECT_FALSE(image.data == white.data);
  const Image with_tiny = image;
  renderer.fill(image, big_triangle(), Affine{}, Color{1, 0, 0, 1}, options);
  EXPECT_EQ(renderer.rasterizer().queued_fills(), 1u);
  renderer.fill(image, tiny, Affine::translate(100, 100), Color{0, 0, 1, 1}, options);
  EXPECT_EQ(renderer.rasterizer().queued_fills(), 2u);
  EXPECT_TRUE(image.data == with_tiny.data);
  renderer.flush();
  EXPECT_EQ(renderer.rasterizer().queued_fills(), 0u);
  EXPECT_FALSE(image.data == with_tiny.data);
  EXPECT_EQ(image.pixel(10, 12)[0], 255);  // inside the red triangle
  EXPECT_EQ(image.pixel(10, 12)[1], 0);

  // A borrowed sink that gives no copy of itself (CoverageSink::clone) is drawn at once.
  Polylines lines;
  flatten(big_triangle(), Affine{}, FlattenOptions{}, lines);
  Rasterizer r;
  r.set_threads(2);
  CallRecorder recorder;
  r.fill_queued(lines, FillRule::NonZero, AntiAlias::Analytic, kSide, kSide, recorder);
  EXPECT_EQ(r.queued_fills(), 0u);
  EXPECT_FALSE(recorder.rows.empty());
}

// A frame of many medium fills (none large enough to start a queue alone) is drawn at once only until the fills so
// drawn add up to a few thousand units of work; then the fills wait in a queue that flush() shares among the threads.
// Glyph-sized fills never start one (queuing would cost them more than they win). The pixels are those of one thread.
TEST(Threads, AFrameOfManyMediumFillsStartsAQueue) {
  auto triangle = [](double x, double y, double size) {
    Path p;
    p.move_to({x, y});
    p.line_to({x + size, y + 0.3 * size});
    p.line_to({x + 0.4 * size, y + size});
    p.close();
    return p;
  };
  for (const double size : {50.0, 6.0}) {
    Image one(kSide, kSide), many(kSide, kSide);
    one.clear(Color{1, 1, 1, 1});
    many.clear(Color{1, 1, 1, 1});
    Renderer single, threaded;
    threaded.set_threads(2);
    std::size_t first_queued = 0;  // the index of the first fill that waited, plus one (0: none waited)
    for (int i = 0; i < 200; ++i) {
      const Path p = triangle((i * 37) % (kSide - 60) + 0.25, (i * 53) % (kSide - 60) + 0.5, size);
      const Color c{0.004f * static_cast<float>(i), 0.5f, 1.0f - 0.004f * static_cast<float>(i), 0.6f};
      single.fill(one, p, Affine{}, c, FillOptions{});
      threaded.fill(many, p, Affine{}, c, FillOptions{});
      if (first_queued == 0 && threaded.rasterizer().queued_fills() > 0) first_queued = static_cast<std::size_t>(i) + 1;
    }
    threaded.flush();
    EXPECT_GT(first_queued, 1u) << "the first fills are drawn at once (size " << size << ")";
    if (size > 10) {
      EXPECT_LT(first_queued, 50u) << "the rest wait in a queue";
      EXPECT_GT(threaded.rasterizer().last_flush_bands(), 1);
    } else {
      // Glyph-sized fills take longer to show a frame of many, then wait in a queue too.
      EXPECT_LT(first_queued, 200u) << "the rest wait in a queue";
    }
    EXPECT_TRUE(one.data == many.data) << "size " << size;
  }
}

// set_threads and the destructor run what is queued; a queue past its memory budget runs by itself. Every case
// gives the pixels of one thread.
TEST(Threads, QueueRunsOnSetThreadsDestructionAndMemoryBudget) {
  const FillOptions options;
  // A zigzag of 8,000 edges, about half a MiB queued (its points and edges): the queue's budget of 1 MiB is
  // reached within three such fills.
  Path zigzag;
  zigzag.move_to({0, 0});
  for (int i = 0; i < 8000; ++i) {
    zigzag.line_to({kSide * (i % 2 ? 0.1 : 0.9), kSide * (i + 0.5) / 8000.0});
  }
  zigzag.line_to({0, kSide});
  zigzag.close();
  auto draw = [&](int threads, int mode) {
    Image image(kSide, kSide);
    image.clear(Color{1, 1, 1, 1});
    {
      Renderer renderer;
      renderer.set_threads(threads);
      const int fills = mode == 2 ? 12 : 3;
      std::size_t most_queued = 0;
      for (int i = 0; i < fills; ++i) {
        renderer.fill(image, mode == 2 ? zigzag : big_triangle(), Affine::translate(i * 3.0, i * 2.0),
                      Color{0.1f * static_cast<float>(i % 10), 0.5f, 0.9f, 0.5f}, options);
        most_queued = std::max(most_queued, renderer.rasterizer().queued_fills());
      }
      if (threads > 1 && mode == 2) {
        EXPECT_GT(most_queued, 1u);
        EXPECT_LT(most_queued, 12u);  // the budget ran the queue before the last fill
      }
      if (mode == 0) renderer.set_threads(1);
      // mode 1 and 2: the destructor flushes
    }
    return image.data;
  };
  for (int mode = 0; mode < 3; ++mode) EXPECT_TRUE(draw(1, mode) == draw(2, mode)) << "mode " << mode;
}

// A frame of thousands of tiny fills fills the queue's memory budget several times: each full queue is drawn in the
// background while the next one fills, and anything drawn otherwise in between (a fill whose sink cannot be kept, a
// mask, a hairline, a fill banded alone) waits for it. The pixels are one thread's, bit for bit.
TEST(Threads, QueuesDrawnInTheBackgroundKeepThePaintersOrder) {
  class Uncopyable final : public CoverageSink {  // takes concurrent rows but cannot be kept: drawn at once
   public:
    explicit Uncopyable(Image& image) : out_(image, Color{0.9f, 0.1f, 0.2f, 0.7f}) {}
    void span(int y, int x0, int x1, float c) override { out_.span(y, x0, x1, c); }
    void row(int y, int x0, int x1, const float* c) override { out_.row(y, x0, x1, c); }
    bool takes_concurrent_rows() const override { return true; }

   private:
    SolidCompositor<std::uint8_t> out_;
  };
  std::mt19937 rng(1717);
  std::uniform_real_distribution<double> at(-2, kSide + 2), size(0.3, 3), unit(0, 1);
  std::vector<Path> tiny;
  for (int i = 0; i < 12000; ++i) {
    const double x = at(rng), y = at(rng), s = size(rng);
    Path p;
    p.move_to({x, y});
    p.line_to({x + s, y + 0.3 * s * unit(rng)});
    p.line_to({x + 0.4 * s, y + s});
    p.close();
    tiny.push_back(p);
  }
  // A zigzag of 40,000 edges over the whole device, more than the queue's budget of 1 MiB on its own: queued, it is
  // drawn in the background at once, and the small fills after it (which the frame has not yet shown to be many)
  // must wait for it rather than be drawn at once.
  Path zigzag;
  zigzag.move_to({0, 0});
  for (int i = 0; i < 40000; ++i) zigzag.line_to({kSide * (i % 2 ? 0.05 : 0.95), kSide * (i + 0.5) / 40000.0});
  zigzag.line_to({0, kSide});
  zigzag.close();
  const std::uint8_t mask[4] = {255, 128, 64, 32};
  auto draw = [&](int threads, std::size_t* most_queued) {
    Image image(kSide, kSide);
    image.clear(Color{1, 1, 1, 1});
    Renderer renderer;
    renderer.set_threads(threads);
    for (std::size_t i = 0; i < tiny.size(); ++i) {
      if (i % 6000 == 0) renderer.fill(image, zigzag, Affine{}, Color{0.2f, 0.9f, 0.3f, 0.6f}, FillOptions{});
      const Color c{static_cast<float>(i % 7) / 7.0f, 0.4f, static_cast<float>(i % 11) / 11.0f, 0.8f};
      renderer.fill(image, tiny[i], Affine{}, c, FillOptions{});
      if (most_queued) *most_queued = std::max(*most_queued, renderer.rasterizer().queued_fills());
      if (i % 3001 == 3000) {
        Uncopyable now(image);
        renderer.fill(big_triangle(), Affine::translate(0.5 * static_cast<double>(i % 5), 0), FillOptions{}, kSide,
                      kSide, now);
      }
      if (i % 2503 == 2502) {
        SolidCompositor<std::uint8_t> ink(image, Color{0, 0, 0, 1});
        renderer.mask(mask, 2, 2, 2, static_cast<int>(i % kSide), static_cast<int>(i / 40 % kSide), kSide, kSide,
                      ink);
      }
    }
    renderer.flush();
    return image.data;
  };
  std::size_t most_queued = 0;
  const auto two = draw(2, &most_queued);
  EXPECT_GT(most_queued, 100u) << "the tiny fills waited in queues";
  EXPECT_LT(most_queued, tiny.size() / 2) << "the budget ran the queue several times";
  EXPECT_TRUE(draw(1, nullptr) == two);
  EXPECT_TRUE(draw(3, nullptr) == two);
}

// A sink kept in a queue entry (CoverageSink::clone_into) draws what the sink it copies draws; one that does not fit
// the storage offered is not made.
TEST(Threads, SolidCompositorClonesIntoStorage) {
  Image a(8, 2), b(8, 2);
  a.clear(Color{1, 1, 1, 1});
  b.clear(Color{1, 1, 1, 1});
  SolidCompositor<std::uint8_t> sink(a, Color{0.2f, 0.4f, 0.6f, 0.5f});
  SolidCompositor<std::uint8_t> other(b, Color{0.2f, 0.4f, 0.6f, 0.5f});
  alignas(std::max_align_t) std::byte storage[256];
  EXPECT_EQ(other.clone_into(storage, sizeof(SolidCompositor<std::uint8_t>) - 1), nullptr);
  CoverageSink* copy = sink.clone_into(storage, sizeof storage);
  ASSERT_NE(copy, nullptr);
  const float coverage[5] = {0.1f, 0.5f, 1.0f, 0.25f, 0.75f};
  copy->row(0, 1, 6, coverage);
  copy->span(1, 2, 7, 0.6f);
  copy->~CoverageSink();
  other.row(0, 1, 6, coverage);
  other.span(1, 2, 7, 0.6f);
  EXPECT_TRUE(a.data == b.data);
  EXPECT_NE(a.data, Image(8, 2).data);
}

// The queue's bands really run on several threads at once: the sink holds the first thread that enters it until a
// second thread enters it too (or 20 s pass, which only a broken pool would take).
TEST(Threads, QueuedBandsRunOnSeveralThreadsAtOnce) {
  class Rendezvous final : public CoverageSink {
   public:
    void span(int, int, int, float) override { meet(); }
    void row(int, int, int, const float*) override { meet(); }
    bool takes_concurrent_rows() const override { return true; }
    void meet() {
      std::unique_lock<std::mutex> lock(mutex_);
      threads_.insert(std::this_thread::get_id());
      if (threads_.size() >= 2) {
        met = true;
        seen_.notify_all();
      } else if (!met) {
        seen_.wait_for(lock, std::chrono::seconds(20), [&] { return met; });
      }
    }
    bool met = false;

   private:
    std::mutex mutex_;
    std::condition_variable seen_;
    std::set<std::thread::id> threads_;
  };
  Polylines lines;
  flatten(big_triangle(), Affine{}, FlattenOptions{}, lines);
  Rendezvous sink;
  Rasterizer r;
  r.set_threads(2);
  for (int i = 0; i < 4; ++i) {
    r.fill_queued(lines, FillRule::NonZero, AntiAlias::Analytic, kSide, kSide, std::make_unique<Forward>(sink));
  }
  EXPECT_EQ(r.queued_fills(), 4u);
  r.flush();
  EXPECT_TRUE(sink.met);
}

}  // namespace

}  // namespace vraster::test
