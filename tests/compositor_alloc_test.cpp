// Steady state allocates nothing: a Compositor reused for draw calls of the same kinds and sizes makes no heap
// allocation after the first round. The test binary's global operator new counts allocations (it only counts;
// every other test is unaffected).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

#include "vraster/blur.hpp"
#include "vraster/canvas.hpp"
#include "vraster/composite.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
// Every other plain form too, so that whatever new allocates, the matching delete frees it the same way (with only
// some forms replaced, AddressSanitizer sees its own operator new paired with our free).
void* operator new[](std::size_t size) { return ::operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return ::operator new(size, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace vraster {
namespace {

TEST(Compositor, SteadyStateDrawingAllocatesNothing) {
  Image image(96, 64);
  auto tile = std::make_shared<const Image>(8, 8);
  Paint solid = Paint::solid({0.2f, 0.4f, 0.6f, 0.7f});
  Paint linear = Paint::linear({0, 0}, {90, 30});
  linear.add_stop(0, {1, 0, 0, 1});
  linear.add_stop(0.5, {0, 1, 0, 0.5f});
  linear.add_stop(1, {0, 0, 1, 1});
  Paint radial = Paint::radial({20, 20}, 2, {40, 30}, 30);
  radial.add_stop(0, {1, 1, 0, 1});
  radial.add_stop(1, {0, 0, 1, 0.3f});
  Paint conic = Paint::conic(0.5, {48, 32});
  conic.add_stop(0, {1, 0, 1, 1});
  conic.add_stop(1, {0, 1, 1, 1});
  Paint pattern = Paint::pattern(tile);
  Paint dithered = linear;
  dithered.set_dither(true);
  std::vector<float> coverage(96, 0.5f);
  std::vector<std::uint8_t> clip(96, 191);  // levels: 0.75 of 255
  Compositor<std::uint8_t> comp;
  GaussianBlur blur;
  auto round = [&] {
    for (const Paint* p : {&solid, &linear, &radial, &conic, &pattern, &dithered}) {
      for (CompositeOp op : {CompositeOp::SourceOver, CompositeOp::Multiply, CompositeOp::Copy}) {
        comp.set(ImageView<std::uint8_t>::of(image), *p, Affine::scale(1.1), op, 0.9f);
        for (int y = 0; y < 64; ++y) {
          comp.span(y, 3, 90, 1.f);
          comp.row(y, 0, 96, coverage.data(), clip.data());
          comp.span(y, 10, 20, 0.4f, clip.data());
        }
      }
    }
    blur.apply(ImageView<std::uint8_t>::of(image), 2.0, 1.5);
  };
  const long start = g_allocations.load();
  round();  // the first round sizes every buffer
  const long before = g_allocations.load();
  EXPECT_GT(before - start, 0) << "the counter sees the first round's buffers";
  round();
  round();
  EXPECT_EQ(g_allocations.load() - before, 0);
}

// The canvas's clips: a pixel-aligned rectangle costs no mask (the same rectangle half a pixel off, which flattens to
// the same buffers, allocates the mask's three blocks: the object, its levels, its row extents), and save / clip /
// fill / restore reuses the mask it made before (steady state: no allocation more than an unclipped draw).
TEST(Canvas, PixelAlignedClipMakesNoMaskAndMasksAreReused) {
  Path circle, aligned, unaligned, shape;
  circle.add_circle({40, 30}, 25);
  aligned.add_rect({10, 5, 70, 50});
  unaligned.add_rect({10.5, 5, 70, 50});
  shape.add_ellipse({45, 35}, 30, 20);
  auto first_round_and_steady = [&](const Path* clip) {
    Image image(96, 64);
    Canvas c(image);
    c.set_fill_color({0.2f, 0.5f, 0.8f, 0.8f});
    auto round = [&] {
      c.save();
      if (clip) c.clip(*clip, FillRule::NonZero);
      c.fill(shape);
      c.restore();
    };
    const long start = g_allocations.load();
    round();
    const long first = g_allocations.load() - start;
    round();
    const long before = g_allocations.load();
    round();
    round();
    return std::pair<long, long>{first, g_allocations.load() - before};
  };
  const auto none = first_round_and_steady(nullptr);
  const auto rect = first_round_and_steady(&aligned);
  const auto off = first_round_and_steady(&unaligned);
  const auto mask = first_round_and_steady(&circle);
  EXPECT_GE(off.first - rect.first, 3) << "a pixel-aligned rectangle clip allocated a mask";
  EXPECT_EQ(rect.second, none.second);
  EXPECT_EQ(off.second, none.second) << "the clip mask is made anew each round";
  EXPECT_EQ(mask.second, none.second) << "the clip mask is made anew each round";
}

}  // namespace
}  // namespace vraster
