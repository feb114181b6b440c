// Hostile paint parameters: huge, tiny and degenerate geometry and transforms never crash, never write outside
// the shape's pixels, and always leave valid premultiplied pixels (every colour channel <= alpha).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "vraster/composite.hpp"

namespace vraster {
namespace {

template <class T>
void draw_and_check(const Paint& paint, const Affine& device, CompositeOp op) {
  BasicImage<T> image(24, 16);
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    image.data[i] = image.data[i + 3] = static_cast<T>(BasicImage<T>::kMax / 2);
  }
  Compositor<T> comp;
  comp.set(ImageView<T>::of(image), paint, device, op, 0.8f);
  std::vector<float> cov(24, 0.6f);
  for (int y = 2; y < 14; ++y) {
    comp.span(y, 1, 23, 1.f);
    comp.row(y, 0, 24, cov.data());
  }
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    for (int c = 0; c < 3; ++c) ASSERT_LE(image.data[i + c], image.data[i + 3]) << "pixel " << i / 4;
  }
  for (int x = 0; x < 24; ++x) {  // rows 0, 1, 14 and 15 were never touched
    for (int y : {0, 1, 14, 15}) ASSERT_EQ(image.pixel(x, y)[3], BasicImage<T>::kMax / 2);
  }
}

TEST(PaintHostile, ExtremeGeometryAndTransformsStayValid) {
  const double big = 1e300, tiny = 1e-300, inf = std::numeric_limits<double>::infinity();
  std::vector<Paint> paints = {
      Paint::linear({0, 0}, {big, big}), Paint::linear({-big, 0}, {big, 0}), Paint::linear({0, 0}, {tiny, 0}),
      Paint::linear({0, 0}, {inf, 0}), Paint::radial({0, 0}, 0, {0, 0}, big), Paint::radial({big, 0}, 1, {0, 0}, 2),
      Paint::radial({0, 0}, tiny, {tiny, 0}, 0), Paint::radial({5, 5}, 3, {5, 5}, 3), Paint::radial({0, 0}, -1, {1, 1}, 4),
      Paint::conic(big, {0, 0}), Paint::conic(0, {big, -big}), Paint::conic(NAN, {1, 1}),
  };
  for (Paint& p : paints) {
    p.add_stop(0, {1, 0, 0, 1});
    p.add_stop(0.5, {0, 1, 0, 0.3f});
    p.add_stop(1, {0, 0, 1, 0.9f});
  }
  auto tile = std::make_shared<const Image>(3, 2);
  for (Extend e : {Extend::None, Extend::Pad, Extend::Repeat, Extend::Reflect}) {
    for (ImageFilter f : {ImageFilter::Nearest, ImageFilter::Bilinear, ImageFilter::Bicubic}) {
      Paint p = Paint::pattern(tile);
      p.set_extend(e);
      p.set_filter(f);
      paints.push_back(p);
    }
  }
  const Affine transforms[] = {Affine{}, Affine::scale(1e-300), Affine::scale(1e300), Affine::translate(1e300, -1e300),
                               Affine{1, 1, 1, 1, 0, 0}, Affine{1e-160, 0, 0, 1e-160, 0, 0}, Affine{NAN, 0, 0, 1, 0, 0}};
  for (const Affine& own : transforms) {
    for (Extend e : {Extend::Pad, Extend::Repeat, Extend::Reflect}) {
      for (Paint p : paints) {
        if (p.kind() != Paint::Kind::Pattern) p.set_extend(e);
        p.set_transform(own);
        for (const Affine& device : {Affine{}, Affine::scale(1e-200), Affine::rotate(33) * Affine::scale(1e250)}) {
          for (CompositeOp op : {CompositeOp::SourceOver, CompositeOp::Copy, CompositeOp::Hue}) {
            draw_and_check<std::uint8_t>(p, device, op);
            draw_and_check<std::uint16_t>(p, device, op);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace vraster
