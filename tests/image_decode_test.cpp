// decode_image (vraster/image_io.hpp): each format from bytes its own encoder made, sniffing by content, and
// hostile input (sizes above the limits declared in headers, truncated and corrupt data).
#include <gtest/gtest.h>

#include <string>

#include "support/encode_images.hpp"
#include "vraster/error.hpp"
#include "vraster/image_io.hpp"

namespace vraster {
namespace {

using test::Bytes;

void expect_pixel(const Image& image, int x, int y, int r, int g, int b, int a, int tolerance = 0) {
  const std::uint8_t* p = image.pixel(x, y);
  EXPECT_NEAR(p[0], r, tolerance) << "at " << x << "," << y;
  EXPECT_NEAR(p[1], g, tolerance) << "at " << x << "," << y;
  EXPECT_NEAR(p[2], b, tolerance) << "at " << x << "," << y;
  EXPECT_NEAR(p[3], a, tolerance) << "at " << x << "," << y;
}

TEST(ImageDecode, PngRoundTripKeepsPremultipliedPixels) {
  Image image(3, 2);
  image.clear(Color::rgb8(255, 0, 0));
  image.pixel(1, 0)[0] = 0, image.pixel(1, 0)[1] = 64, image.pixel(1, 0)[2] = 0, image.pixel(1, 0)[3] = 128;
  image.pixel(2, 1)[0] = image.pixel(2, 1)[1] = image.pixel(2, 1)[2] = image.pixel(2, 1)[3] = 0;
  const Bytes png = test::png_bytes(image);
  EXPECT_EQ(sniff_image_format(png), ImageFormat::Png);
  const Image decoded = decode_image(png);
  ASSERT_EQ(decoded.width, 3);
  ASSERT_EQ(decoded.height, 2);
  expect_pixel(decoded, 0, 0, 255, 0, 0, 255);
  expect_pixel(decoded, 1, 0, 0, 64, 0, 128, 1);
  expect_pixel(decoded, 2, 1, 0, 0, 0, 0);
}

TEST(ImageDecode, JpegColourAndGrey) {
  const Bytes rgb = test::jpeg_bytes(16, 8, 200, 100, 50);
  EXPECT_EQ(sniff_image_format(rgb), ImageFormat::Jpeg);
  const Image colour = decode_image(rgb);
  ASSERT_EQ(colour.width, 16);
  ASSERT_EQ(colour.height, 8);
  expect_pixel(colour, 5, 5, 200, 100, 50, 255, 3);
  const Image grey = decode_image(test::jpeg_bytes(8, 8, 90, 0, 0, true));
  expect_pixel(grey, 3, 3, 90, 90, 90, 255, 2);
}

TEST(ImageDecode, GifFirstFrameWithTransparency) {
  const GifColorType palette[4] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {9, 9, 9}};
  const Bytes gif = test::gif_bytes(2, 2, {0, 1, 2, 3}, palette, 3);
  EXPECT_EQ(sniff_image_format(gif), ImageFormat::Gif);
  const Image image = decode_image(gif);
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 2);
  expect_pixel(image, 0, 0, 255, 0, 0, 255);
  expect_pixel(image, 1, 0, 0, 255, 0, 255);
  expect_pixel(image, 0, 1, 0, 0, 255, 255);
  expect_pixel(image, 1, 1, 0, 0, 0, 0);  // the transparent index
}

TEST(ImageDecode, WebpLosslessIsPremultiplied) {
  const Bytes webp = test::webp_bytes(2, 1, {255, 0, 0, 255, 0, 200, 100, 102});
  EXPECT_EQ(sniff_image_format(webp), ImageFormat::Webp);
  const Image image = decode_image(webp);
  ASSERT_EQ(image.width, 2);
  expect_pixel(image, 0, 0, 255, 0, 0, 255);
  expect_pixel(image, 1, 0, 0, 80, 40, 102, 1);  // 200 * 102 / 255, 100 * 102 / 255
}

TEST(ImageDecode, FormatComesFromTheBytesNotAName) {
  EXPECT_EQ(sniff_image_format(Bytes{'G', 'I', 'F', '8', '9', 'a'}), ImageFormat::Gif);
  EXPECT_EQ(sniff_image_format(Bytes{'<', 's', 'v', 'g'}), ImageFormat::Unknown);
  EXPECT_EQ(sniff_image_format(Bytes{}), ImageFormat::Unknown);
  EXPECT_THROW(decode_image(Bytes{'h', 'e', 'l', 'l', 'o'}), Error);
}

TEST(ImageDecode, CorruptAndTruncatedDataThrow) {
  Image image(8, 8);
  image.clear(Color::rgb8(10, 20, 30));
  const GifColorType palette[4] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {9, 9, 9}};
  const std::vector<Bytes> inputs = {test::png_bytes(image), test::jpeg_bytes(8, 8, 1, 2, 3),
                                     test::gif_bytes(2, 2, {0, 1, 2, 3}, palette, -1),
                                     test::webp_bytes(1, 1, {1, 2, 3, 255})};
  for (const Bytes& whole : inputs) {
    for (const std::size_t keep : {std::size_t{4}, whole.size() / 2, whole.size() - 3}) {
      const Bytes cut(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(keep));
      try {
        const Image partial = decode_image(cut);
        // libjpeg fills a truncated JPEG with grey (with a warning): an image, not a crash, is fine too.
        EXPECT_EQ(sniff_image_format(cut), ImageFormat::Jpeg) << "decoded a truncated image of " << keep << " bytes";
      } catch (const Error&) {
      }
    }
  }
}

TEST(ImageDecode, HugeDeclaredSizesAreRefusedBeforeAllocating) {
  Image one(1, 1);
  one.clear(Color::rgb8(1, 2, 3));
  const Bytes png = test::png_bytes(one);
  EXPECT_THROW(decode_image(test::png_with_size(png, 100000, 100000)), Error);  // beyond the side limit
  EXPECT_THROW(decode_image(test::png_with_size(png, 30000, 30000)), Error);    // 9e8 pixels > 2^26
  // GIF: a 65535 x 65535 logical screen with a matching frame.
  const Bytes gif = {'G', 'I', 'F', '8', '9', 'a', 0xFF, 0xFF, 0xFF, 0xFF, 0x80, 0, 0, 0, 0, 0, 255, 255, 255,
                     ',', 0, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0, 2, 2, 0x4C, 0x01, 0, ';'};
  EXPECT_THROW(decode_image(gif), Error);
  // JPEG: the frame header (SOF0) patched to 60000 x 60000.
  Bytes jpeg = test::jpeg_bytes(8, 8, 1, 2, 3);
  for (std::size_t i = 0; i + 8 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      jpeg[i + 5] = jpeg[i + 7] = 0xEA;
      jpeg[i + 6] = jpeg[i + 8] = 0x60;
      break;
    }
  }
  EXPECT_THROW(decode_image(jpeg), Error);
  // WebP lossless: the 14-bit sizes in the VP8L header set to 16384 x 16384 (2^28 pixels).
  Bytes webp = test::webp_bytes(1, 1, {1, 2, 3, 255});
  ASSERT_EQ(std::string(webp.begin() + 12, webp.begin() + 16), "VP8L");
  webp[21] = webp[22] = webp[23] = 0xFF;
  webp[24] |= 0x0F;
  EXPECT_THROW(decode_image(webp), Error);
}

TEST(ImageDecode, ProgressiveJpegWithEndlessScansIsRefused) {
  Bytes jpeg = test::jpeg_bytes(16, 16, 200, 100, 50, false, true);
  EXPECT_NO_THROW(decode_image(jpeg));
  // Repeat the last scan (from its SOS marker to the end-of-image marker) 400 times: every repeat is another
  // pass over the whole image.
  std::size_t sos = 0;
  for (std::size_t i = 0; i + 1 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xDA) sos = i;
  }
  ASSERT_GT(sos, 0u);
  ASSERT_EQ(jpeg[jpeg.size() - 2], 0xFF);
  const Bytes scan(jpeg.begin() + static_cast<std::ptrdiff_t>(sos), jpeg.end() - 2);
  Bytes bomb(jpeg.begin(), jpeg.end() - 2);
  for (int i = 0; i < 400; ++i) bomb.insert(bomb.end(), scan.begin(), scan.end());
  bomb.push_back(0xFF);
  bomb.push_back(0xD9);
  try {
    decode_image(bomb);
    ADD_FAILURE() << "decoded a JPEG of more than 400 scans";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scans"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vraster
