// PNG files: 8- and 16-bit round trips, 16-bit precision end to end, and failures that name the file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

#include "vraster/vraster.hpp"

namespace vraster::test {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test (ctest runs tests in parallel processes).
class PngFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("vraster_png_" + std::string(info->name()) + "_" + std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t files_in_dir() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }

  fs::path dir_;
};

// Random valid premultiplied pixels (colour channels <= alpha), with some fully opaque and fully clear ones.
template <class T>
BasicImage<T> random_image(int w, int h, unsigned seed) {
  BasicImage<T> img(w, h);
  std::mt19937 rng(seed);
  const std::uint32_t max = BasicImage<T>::kMax;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      T* px = img.pixel(x, y);
      const int kind = (x + y) % 4;
      const std::uint32_t a = kind == 0 ? max : kind == 1 ? 0 : std::uniform_int_distribution<std::uint32_t>(1, max)(rng);
      for (int c = 0; c < 3; ++c) px[c] = static_cast<T>(std::uniform_int_distribution<std::uint32_t>(0, a)(rng));
      px[3] = static_cast<T>(a);
    }
  }
  return img;
}

template <class T>
void expect_round_trip(const BasicImage<T>& in, const BasicImage<T>& out) {
  ASSERT_EQ(out.width, in.width);
  ASSERT_EQ(out.height, in.height);
  const std::uint32_t max = BasicImage<T>::kMax;
  int opaque = 0;
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      const T* a = in.pixel(x, y);
      const T* b = out.pixel(x, y);
      ASSERT_EQ(a[3], b[3]) << "alpha at " << x << "," << y;
      for (int c = 0; c < 3; ++c) {
        if (a[3] == max) {
          ASSERT_EQ(a[c], b[c]) << "opaque pixel " << x << "," << y << " channel " << c;
        } else {
          ASSERT_LE(std::abs(int(a[c]) - int(b[c])), 1) << "pixel " << x << "," << y << " channel " << c;
          ASSERT_LE(b[c], b[3]) << "not premultiplied at " << x << "," << y;
        }
      }
      opaque += a[3] == max;
    }
  }
  EXPECT_GT(opaque, 0);
}

TEST_F(PngFile, EightBitRoundTripKeepsPremultipliedPixels) {
  const Image in = random_image<std::uint8_t>(37, 23, 1);
  write_png(file("a.png"), in);
  expect_round_trip(in, read_png(file("a.png")));
  EXPECT_EQ(files_in_dir(), 1u) << "no temporary file left behind";
}

TEST_F(PngFile, SixteenBitRoundTripKeepsPremultipliedPixels) {
  const Image16 in = random_image<std::uint16_t>(29, 31, 2);
  write_png(file("b.png"), in);
  expect_round_trip(in, read_png16(file("b.png")));
}

TEST_F(PngFile, ReadingAtTheOtherDepthConvertsChannelsByScaling) {
  Image16 in(2, 1);
  in.pixel(0, 0)[0] = in.pixel(0, 0)[3] = 65535;  // opaque red
  in.pixel(0, 0)[1] = 257 * 100;
  in.pixel(1, 0)[3] = 65535;  // opaque black
  write_png(file("c.png"), in);
  const Image eight = read_png(file("c.png"));
  EXPECT_EQ(eight.pixel(0, 0)[0], 255);
  EXPECT_EQ(eight.pixel(0, 0)[1], 100);
  EXPECT_EQ(eight.pixel(0, 0)[3], 255);
  Image in8(1, 1);
  in8.pixel(0, 0)[0] = 10, in8.pixel(0, 0)[3] = 255;
  write_png(file("d.png"), in8);
  const Image16 sixteen = read_png16(file("d.png"));
  EXPECT_EQ(sixteen.pixel(0, 0)[0], 2570);
  EXPECT_EQ(sixteen.pixel(0, 0)[3], 65535);
}

TEST_F(PngFile, SixteenBitRenderingKeepsMoreThanEightBitsOfCoverage) {
  // A quarter of pixel (0,0) covered by opaque white: coverage 0.25 -> 0.25 * 65535 = 16383.75 -> 16384, which no
  // 8-bit value scaled by 257 gives (16384 / 257 = 63.75).
  Image16 image(3, 1);
  Path p;
  p.add_rect({0, 0, 0.25, 1});
  p.add_rect({1, 0, 2.1, 1});  // pixel 1 full, pixel 2 a tenth: 6553.5 -> 6554 (or 6553)
  Renderer r;
  r.fill(image, p, Affine{}, Color{1, 1, 1, 1}, FillOptions{});
  EXPECT_EQ(image.pixel(0, 0)[3], 16384);
  EXPECT_EQ(image.pixel(0, 0)[0], 16384);
  EXPECT_EQ(image.pixel(1, 0)[3], 65535);
  EXPECT_NEAR(image.pixel(2, 0)[3], 6553.5, 1.0);
  EXPECT_NE(image.pixel(0, 0)[3] % 257, 0);
  EXPECT_NE(image.pixel(2, 0)[3] % 257, 0);
  // ... and the 16-bit file keeps them.
  write_png(file("e.png"), image);
  const Image16 back = read_png16(file("e.png"));
  for (int x = 0; x < 3; ++x)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(back.pixel(x, 0)[c], image.pixel(x, 0)[c]) << "pixel " << x << " ch " << c;
  // Read as 8 bits: 16384 / 257 = 63.75 -> 64.
  EXPECT_EQ(read_png(file("e.png")).pixel(0, 0)[3], 64);
}

::testing::AssertionResult throws_naming(const std::function<void()>& f, const std::string& name) {
  try {
    f();
  } catch (const Error& e) {
    if (std::string(e.what()).find(name) == std::string::npos) {
      return ::testing::AssertionFailure() << "message does not name " << name << ": " << e.what();
    }
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no vraster::Error thrown";
}

TEST_F(PngFile, ReadingAMissingTruncatedOrNonPngFileThrowsNamingTheFile) {
  const std::string missing = file("missing.png");
  EXPECT_TRUE(throws_naming([&] { (void)read_png(missing); }, missing));
  EXPECT_TRUE(throws_naming([&] { (void)read_png16(missing); }, missing));

  const std::string good = file("good.png");
  write_png(good, random_image<std::uint8_t>(40, 40, 3));
  const auto size = fs::file_size(good);
  for (std::uintmax_t keep : {size / 2, std::uintmax_t{40}, std::uintmax_t{8}, size - 13}) {
    const std::string cut = file("cut" + std::to_string(keep) + ".png");
    fs::copy_file(good, cut);
    fs::resize_file(cut, keep);
    EXPECT_TRUE(throws_naming([&] { (void)read_png(cut); }, cut)) << "truncated to " << keep << " of " << size;
    EXPECT_TRUE(throws_naming([&] { (void)read_png16(cut); }, cut)) << "truncated to " << keep;
  }

  const std::string text = file("text.png");
  std::ofstream(text) << "this is not a PNG file, just text that is long enough\n";
  EXPECT_TRUE(throws_naming([&] { (void)read_png(text); }, text));
  const std::string empty = file("empty.png");
  std::ofstream{empty};
  EXPECT_TRUE(throws_naming([&] { (void)read_png(empty); }, empty));
  // A PNG signature followed by garbage.
  const std::string garbage = file("garbage.png");
  std::ofstream(garbage, std::ios::binary) << "\x89PNG\r\n\x1a\n" << std::string(100, 'x');
  EXPECT_TRUE(throws_naming([&] { (void)read_png(garbage); }, garbage));
  // A directory.
  EXPECT_TRUE(throws_naming([&] { (void)read_png(dir_.string()); }, dir_.string()));
}

TEST_F(PngFile, WritingWhereNoFileCanBeCreatedThrowsAndLeavesNoFile) {
  const Image img = random_image<std::uint8_t>(4, 4, 4);
  // A folder that does not exist (works as root too, unlike a read-only folder).
  const std::string in_missing_dir = file("no/such/dir/out.png");
  EXPECT_TRUE(throws_naming([&] { write_png(in_missing_dir, img); }, in_missing_dir));
  // A "folder" that is a regular file.
  std::ofstream(file("plain")) << "x";
  const std::string under_file = file("plain/out.png");
  EXPECT_TRUE(throws_naming([&] { write_png(under_file, img); }, under_file));
  // The target is an existing folder: the temporary file is written, the rename fails, nothing is left.
  fs::create_directory(file("target.png"));
  EXPECT_TRUE(throws_naming([&] { write_png(file("target.png"), img); }, file("target.png")));
  EXPECT_TRUE(fs::is_directory(file("target.png")));
  EXPECT_TRUE(fs::is_empty(file("target.png")));
  // Only "plain" and the "target.png" folder: no output, no temporary files.
  EXPECT_EQ(files_in_dir(), 2u);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_TRUE(entry.path().filename() == "plain" || entry.path().filename() == "target.png") << entry.path();
  }
}

}  // namespace
}  // namespace vraster::test
