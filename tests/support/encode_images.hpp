// Test inputs for the image decoders: tiny images encoded with the codecs' own encoders (libpng through
// vraster's writer, libjpeg, giflib, libwebp), base64 for data: URLs, and a few hand-made hostile headers.
#pragma once

#include <gif_lib.h>
#include <jpeglib.h>
#include <unistd.h>
#include <webp/encode.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "vraster/image.hpp"
#include "vraster/png.hpp"

namespace vraster::test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// A PNG of `image` (premultiplied) through vraster's own writer.
inline Bytes png_bytes(const Image& image) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("vraster_encode_" + std::to_string(static_cast<long>(::getpid())) + ".png")).string();
  write_png(path, image);
  Bytes bytes = read_bytes(path);
  std::filesystem::remove(path);
  return bytes;
}

/// A JPEG of one colour (quality 100), 3 components, or 1 (greyscale: only `r` is used); baseline or progressive.
inline Bytes jpeg_bytes(int w, int h, int r, int g, int b, bool grey = false, bool progressive = false) {
  jpeg_compress_struct info;
  jpeg_error_mgr err;
  info.err = jpeg_std_error(&err);
  jpeg_create_compress(&info);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&info, &out, &size);
  info.image_width = static_cast<JDIMENSION>(w);
  info.image_height = static_cast<JDIMENSION>(h);
  info.input_components = grey ? 1 : 3;
  info.in_color_space = grey ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 100, TRUE);
  if (progressive) jpeg_simple_progression(&info);
  jpeg_start_compress(&info, TRUE);
  std::vector<JSAMPLE> row(static_cast<std::size_t>(w) * (grey ? 1 : 3));
  for (int x = 0; x < w; ++x) {
    if (grey) {
      row[static_cast<std::size_t>(x)] = static_cast<JSAMPLE>(r);
    } else {
      row[static_cast<std::size_t>(x) * 3] = static_cast<JSAMPLE>(r);
      row[static_cast<std::size_t>(x) * 3 + 1] = static_cast<JSAMPLE>(g);
      row[static_cast<std::size_t>(x) * 3 + 2] = static_cast<JSAMPLE>(b);
    }
  }
  while (info.next_scanline < info.image_height) {
    JSAMPROW p = row.data();
    jpeg_write_scanlines(&info, &p, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  Bytes bytes(out, out + size);
  std::free(out);
  return bytes;
}

inline int gif_write(GifFileType* gif, const GifByteType* data, int length) {
  auto* out = static_cast<Bytes*>(gif->UserData);
  out->insert(out->end(), data, data + length);
  return length;
}

/// A GIF of `indices` (w x h) with a four-colour palette; index `transparent` (or -1) is transparent.
inline Bytes gif_bytes(int w, int h, const std::vector<GifPixelType>& indices, const GifColorType (&palette)[4],
                       int transparent) {
  Bytes out;
  int error = 0;
  GifFileType* gif = EGifOpen(&out, gif_write, &error);
  if (!gif) throw std::runtime_error("EGifOpen failed");
  EGifSetGifVersion(gif, true);
  ColorMapObject* map = GifMakeMapObject(4, palette);
  EGifPutScreenDesc(gif, w, h, 8, 0, map);
  if (transparent >= 0) {
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSAL_UNSPECIFIED;
    gcb.DelayTime = 0;
    gcb.TransparentColor = transparent;
    GifByteType ext[4];
    const std::size_t n = EGifGCBToExtension(&gcb, ext);
    EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(n), ext);
  }
  EGifPutImageDesc(gif, 0, 0, w, h, false, nullptr);
  std::vector<GifPixelType> row(static_cast<std::size_t>(w));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) row[static_cast<std::size_t>(x)] = indices[static_cast<std::size_t>(y * w + x)];
    EGifPutLine(gif, row.data(), w);
  }
  EGifCloseFile(gif, &error);
  GifFreeMapObject(map);
  return out;
}

/// A lossless WebP of straight RGBA pixels.
inline Bytes webp_bytes(int w, int h, const std::vector<std::uint8_t>& rgba) {
  std::uint8_t* out = nullptr;
  const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), w, h, w * 4, &out);
  if (size == 0) throw std::runtime_error("WebP encoding failed");
  Bytes bytes(out, out + size);
  WebPFree(out);
  return bytes;
}

/// A copy of PNG `bytes` whose header claims width x height (the header's CRC made right again).
inline Bytes png_with_size(Bytes bytes, std::uint32_t width, std::uint32_t height) {
  for (int i = 0; i < 4; ++i) {
    bytes[16 + i] = static_cast<std::uint8_t>(width >> (24 - 8 * i));
    bytes[20 + i] = static_cast<std::uint8_t>(height >> (24 - 8 * i));
  }
  const uLong crc = crc32(0, bytes.data() + 12, 17);  // chunk type and the 13 bytes of IHDR data
  for (int i = 0; i < 4; ++i) bytes[29 + i] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
  return bytes;
}

inline std::string base64(const Bytes& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = bytes[i] << 16 | bytes[i + 1] << 8 | bytes[i + 2];
    for (int k = 18; k >= 0; k -= 6) out.push_back(kAlphabet[(v >> k) & 63]);
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = bytes[i] << 16;
    out += {kAlphabet[v >> 18], kAlphabet[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = bytes[i] << 16 | bytes[i + 1] << 8;
    out += {kAlphabet[v >> 18], kAlphabet[(v >> 12) & 63], kAlphabet[(v >> 6) & 63], '='};
  }
  return out;
}

inline std::string data_url(const std::string& mime, const Bytes& bytes) { return "data:" + mime + ";base64," + base64(bytes); }

}  // namespace vraster::test
