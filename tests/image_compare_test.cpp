// The conformance comparison (vraster compare): the pass rule on hand-made images.
#include <gtest/gtest.h>

#include "cli/image_compare.hpp"

namespace vraster::cli {
namespace {

Image filled(int w, int h, Color c) {
  Image image(w, h);
  image.clear(c);
  return image;
}

void set(Image& image, int x, int y, int r, int g, int b, int a) {
  std::uint8_t* p = image.pixel(x, y);
  p[0] = static_cast<std::uint8_t>(r), p[1] = static_cast<std::uint8_t>(g), p[2] = static_cast<std::uint8_t>(b);
  p[3] = static_cast<std::uint8_t>(a);
}

TEST(ImageCompare, IdenticalImagesPass) {
  const Image a = filled(20, 10, Color::rgb8(10, 200, 30));
  const CompareResult r = compare_images(a, a);
  EXPECT_TRUE(r.passed);
  EXPECT_EQ(r.off, 0);
  EXPECT_EQ(r.far_off, 0);
  EXPECT_EQ(r.pixels, 200);
}

TEST(ImageCompare, ThresholdIsSixteenLevels) {
  const Image a = filled(10, 10, Color::rgb8(100, 100, 100));
  EXPECT_TRUE(compare_images(a, filled(10, 10, Color::rgb8(116, 100, 100))).passed);
  const CompareResult r = compare_images(a, filled(10, 10, Color::rgb8(117, 100, 100)));
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.off, 100);
  EXPECT_EQ(r.far_off, 0);
  EXPECT_EQ(r.max_error, 17);
}

TEST(ImageCompare, AllowsOneThousandthOfThePixels) {
  const Image a = filled(100, 100, Color::transparent());
  Image b = a;
  for (int i = 0; i < 10; ++i) set(b, 5 * i + 2, 50, 0, 200, 0, 200);  // 10 isolated pixels: 0.1%
  CompareResult r = compare_images(a, b);
  EXPECT_EQ(r.off, 10);
  EXPECT_EQ(r.far_off, 10);
  EXPECT_TRUE(r.passed);
  set(b, 90, 90, 0, 200, 0, 200);
  r = compare_images(a, b);
  EXPECT_EQ(r.off, 11);
  EXPECT_FALSE(r.passed);
}

TEST(ImageCompare, EdgeMovedByAPixelIsExcusedButCountsAsFarOff) {
  Image a = filled(100, 100, Color::transparent()), b = a;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 50; ++x) set(a, x, y, 0, 0, 255, 255);
    for (int x = 0; x < 51; ++x) set(b, x, y, 0, 0, 255, 255);
  }
  const CompareResult r = compare_images(a, b);
  EXPECT_EQ(r.off, 0);        // each image's value at x = 50 is found next to it in the other
  EXPECT_EQ(r.far_off, 100);  // but the raw 96/255 bound sees the whole column
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(neighbourhood_error(a, b, 50, 10), 0);
  EXPECT_EQ(neighbourhood_error(a, b, 52, 10), 0);
}

TEST(ImageCompare, ExcuseNeedsBothDirections) {
  // Ours is a blur of a one-pixel line; ours lies within the reference's range, but the reference's line value
  // is not within ours' neighbourhood range.
  Image a = filled(9, 9, Color::transparent()), b = a;
  for (int y = 0; y < 9; ++y) {
    set(a, 4, y, 0, 0, 0, 255);
    for (int x = 3; x <= 5; ++x) set(b, x, y, 0, 0, 0, 85);
  }
  EXPECT_EQ(neighbourhood_error(b, a, 4, 4), 0);
  EXPECT_EQ(neighbourhood_error(a, b, 4, 4), 255 - 85);
  EXPECT_EQ(compare_images(a, b).off, 9);
}

TEST(ImageCompare, DifferentSizesFail) {
  const CompareResult r = compare_images(filled(10, 10, Color::transparent()), filled(10, 11, Color::transparent()));
  EXPECT_FALSE(r.same_size);
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.off, 100);
}

TEST(ImageCompare, DiffImageMarksOffPixels) {
  const Image a = filled(5, 5, Color::transparent());
  Image b = a;
  set(b, 2, 2, 255, 255, 255, 255);
  Image diff;
  compare_images(a, b, CompareRule{}, &diff);
  ASSERT_EQ(diff.width, 5);
  EXPECT_EQ(diff.pixel(2, 2)[0], 255);  // red
  EXPECT_EQ(diff.pixel(2, 2)[1], 0);
  EXPECT_EQ(diff.pixel(0, 0)[0], 255);  // transparent reference: white
  EXPECT_EQ(diff.pixel(0, 0)[1], 255);
}

}  // namespace
}  // namespace vraster::cli
