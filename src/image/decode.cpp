// Decoding images held in memory: the format is sniffed from the signature, then libpng (png.cpp), libjpeg
// (libjpeg-turbo), giflib or libwebp decodes it. Every decoder checks the size from the header against the image
// limits before it allocates pixels. libjpeg reports errors by longjmp: as in png.cpp, the setjmp function
// creates no C++ object and writes its output through a reference to the caller's.
#include "vraster/image_io.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gif_lib.h>
#include <jpeglib.h>
#include <webp/decode.h>

#include "vraster/error.hpp"

namespace vraster {
namespace {

bool starts_with(std::span<const std::uint8_t> bytes, std::size_t at, const char* magic) {
  const std::size_t n = std::strlen(magic);
  return bytes.size() >= at + n && std::memcmp(bytes.data() + at, magic, n) == 0;
}

/// Throws unless width x height is within the image limits (the header's claim, checked before allocating).
void check_declared_size(const char* format, std::uint64_t width, std::uint64_t height) {
  if (width == 0 || height == 0 || width > static_cast<std::uint64_t>(kMaxImageSide) ||
      height > static_cast<std::uint64_t>(kMaxImageSide) || width * height > static_cast<std::uint64_t>(kMaxImagePixels)) {
    throw Error(std::string(format) + " image of " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels is empty or above the limits (" + std::to_string(kMaxImageSide) + " a side, " +
                std::to_string(kMaxImagePixels) + " pixels)");
  }
}

/// Straight RGBA8 -> premultiplied, in place.
void premultiply(Image& image) {
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    const unsigned a = image.data[i + 3];
    if (a == 255) continue;
    for (int c = 0; c < 3; ++c) image.data[i + c] = static_cast<std::uint8_t>((image.data[i + c] * a + 127) / 255);
  }
}

// ---- JPEG ----

struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "unknown libjpeg error";
};

[[noreturn]] void on_jpeg_error(j_common_ptr info) {
  auto* err = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, err->message);
  std::longjmp(err->jump, 1);
}

void on_jpeg_message(j_common_ptr) {}  // warnings (corrupt but decodable data) are not printed

/// A progressive JPEG can hold any number of scans, each a pass over the whole image: past this many the data is
/// refused (libjpeg-turbo's own tools use the same kind of cap against such "scan bombs").
constexpr int kMaxJpegScans = 256;

void on_jpeg_progress(j_common_ptr info) {
  const auto* d = reinterpret_cast<j_decompress_ptr>(info);
  if (d->global_state >= 0 && d->input_scan_number > kMaxJpegScans) {
    auto* err = reinterpret_cast<JpegError*>(info->err);
    std::snprintf(err->message, sizeof err->message, "more than %d scans in a progressive JPEG", kMaxJpegScans);
    std::longjmp(err->jump, 1);
  }
}

struct JpegResult {
  int width = 0, height = 0;
  bool cmyk = false, inverted = false;  ///< CMYK data; Adobe's inverted CMYK
  bool too_large = false;
};

/// Decodes into `pixels` (4 bytes a pixel: RGBA, or CMYK when out.cmyk). Returns false with err.message set.
bool read_jpeg(std::span<const std::uint8_t> bytes, JpegError& err, JpegResult& out, std::vector<std::uint8_t>& pixels) {
  jpeg_decompress_struct info;
  info.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = on_jpeg_error;
  err.mgr.output_message = on_jpeg_message;
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  info.mem->max_memory_to_use = std::size_t{1} << 30;
  jpeg_progress_mgr progress{};
  progress.progress_monitor = on_jpeg_progress;
  info.progress = &progress;
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  const std::uint64_t w = info.image_width, h = info.image_height;
  if (w == 0 || h == 0 || w > static_cast<std::uint64_t>(kMaxImageSide) || h > static_cast<std::uint64_t>(kMaxImageSide) ||
      w * h > static_cast<std::uint64_t>(kMaxImagePixels)) {
    out.width = static_cast<int>(std::min<std::uint64_t>(w, 1u << 30));
    out.height = static_cast<int>(std::min<std::uint64_t>(h, 1u << 30));
    out.too_large = true;
    jpeg_destroy_decompress(&info);
    return false;
  }
  out.cmyk = info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK;
  out.inverted = out.cmyk && info.saw_Adobe_marker;
  info.out_color_space = out.cmyk ? JCS_CMYK : JCS_EXT_RGBA;  // libjpeg-turbo expands grey and YCbCr to RGBA
  jpeg_start_decompress(&info);
  if (info.output_components != 4) {
    std::snprintf(err.message, sizeof err.message, "unexpected JPEG output layout");
    jpeg_destroy_decompress(&info);
    return false;
  }
  out.width = static_cast<int>(info.output_width);
  out.height = static_cast<int>(info.output_height);
  pixels.resize(static_cast<std::size_t>(out.width) * out.height * 4);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = pixels.data() + static_cast<std::size_t>(info.output_scanline) * out.width * 4;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

Image decode_jpeg(std::span<const std::uint8_t> bytes) {
  JpegError err;
  JpegResult r;
  std::vector<std::uint8_t> pixels;
  if (!read_jpeg(bytes, err, r, pixels)) {
    if (r.too_large) check_declared_size("JPEG", static_cast<std::uint64_t>(r.width), static_cast<std::uint64_t>(r.height));
    throw Error(std::string("corrupt JPEG data: ") + err.message);
  }
  Image image(r.width, r.height);
  image.data = std::move(pixels);
  if (r.cmyk) {
    // Plain CMYK -> RGB: each ink takes away its share of its colour (Adobe files store the inks inverted).
    for (std::size_t i = 0; i < image.data.size(); i += 4) {
      unsigned c = image.data[i], m = image.data[i + 1], y = image.data[i + 2], k = image.data[i + 3];
      if (!r.inverted) {
        c = 255 - c, m = 255 - m, y = 255 - y, k = 255 - k;
      }
      image.data[i] = static_cast<std::uint8_t>((c * k + 127) / 255);
      image.data[i + 1] = static_cast<std::uint8_t>((m * k + 127) / 255);
      image.data[i + 2] = static_cast<std::uint8_t>((y * k + 127) / 255);
      image.data[i + 3] = 255;
    }
  }
  return image;  // opaque: already premultiplied
}

// ---- GIF ----

struct GifSource {
  std::span<const std::uint8_t> bytes;
  std::size_t pos = 0;
};

int read_gif(GifFileType* gif, GifByteType* out, int length) {
  auto* src = static_cast<GifSource*>(gif->UserData);
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(std::max(length, 0)), src->bytes.size() - src->pos);
  std::memcpy(out, src->bytes.data() + src->pos, n);
  src->pos += n;
  return static_cast<int>(n);
}

struct GifCloser {
  GifFileType* gif;
  ~GifCloser() {
    int ignored = 0;
    if (gif) DGifCloseFile(gif, &ignored);
  }
};

[[noreturn]] void gif_failed(int code) {
  const char* why = GifErrorString(code);
  throw Error(std::string("corrupt GIF data: ") + (why ? why : "unknown giflib error"));
}

/// The first frame, drawn on the logical screen (transparent where the frame does not cover it). Reads records
/// one at a time, so the frames after the first are never decoded.
Image decode_gif(std::span<const std::uint8_t> bytes) {
  GifSource src{bytes, 0};
  int code = 0;
  GifFileType* opened = DGifOpen(&src, read_gif, &code);
  if (!opened) gif_failed(code);
  GifCloser closer{opened};
  GifFileType* gif = opened;
  if (gif->SWidth > 0 && gif->SHeight > 0)
    check_declared_size("GIF", static_cast<std::uint64_t>(gif->SWidth), static_cast<std::uint64_t>(gif->SHeight));
  int transparent = -1;
  for (;;) {
    GifRecordType type = UNDEFINED_RECORD_TYPE;
    if (DGifGetRecordType(gif, &type) == GIF_ERROR) gif_failed(gif->Error);
    if (type == TERMINATE_RECORD_TYPE) throw Error("GIF data without an image");
    if (type == EXTENSION_RECORD_TYPE) {
      int ext_code = 0;
      GifByteType* ext = nullptr;
      if (DGifGetExtension(gif, &ext_code, &ext) == GIF_ERROR) gif_failed(gif->Error);
      if (ext_code == GRAPHICS_EXT_FUNC_CODE && ext && ext[0] >= 4) {
        GraphicsControlBlock gcb;
        if (DGifExtensionToGCB(ext[0], ext + 1, &gcb) == GIF_OK) transparent = gcb.TransparentColor;
      }
      while (ext) {
        if (DGifGetExtensionNext(gif, &ext) == GIF_ERROR) gif_failed(gif->Error);
      }
      continue;
    }
    if (type != IMAGE_DESC_RECORD_TYPE) continue;
    if (DGifGetImageDesc(gif) == GIF_ERROR) gif_failed(gif->Error);
    const GifImageDesc& desc = gif->Image;
    const int fw = desc.Width, fh = desc.Height;
    // A zero logical screen takes the frame's size.
    const int sw = gif->SWidth > 0 ? gif->SWidth : desc.Left + fw;
    const int sh = gif->SHeight > 0 ? gif->SHeight : desc.Top + fh;
    check_declared_size("GIF", static_cast<std::uint64_t>(std::max(sw, 0)), static_cast<std::uint64_t>(std::max(sh, 0)));
    check_declared_size("GIF frame of a", static_cast<std::uint64_t>(std::max(fw, 0)), static_cast<std::uint64_t>(std::max(fh, 0)));
    const ColorMapObject* map = desc.ColorMap ? desc.ColorMap : gif->SColorMap;
    if (!map) throw Error("corrupt GIF data: no colour table");
    Image image(sw, sh);  // transparent
    std::vector<GifPixelType> line(static_cast<std::size_t>(fw));
    auto put_row = [&](int y) {
      const int sy = desc.Top + y;
      if (sy < 0 || sy >= sh) return;
      for (int x = 0; x < fw; ++x) {
        const int sx = desc.Left + x;
        const int index = line[static_cast<std::size_t>(x)];
        if (sx < 0 || sx >= sw || index == transparent || index >= map->ColorCount) continue;
        std::uint8_t* px = image.pixel(sx, sy);
        px[0] = map->Colors[index].Red;
        px[1] = map->Colors[index].Green;
        px[2] = map->Colors[index].Blue;
        px[3] = 255;
      }
    };
    if (desc.Interlace) {
      static constexpr int kStart[] = {0, 4, 2, 1}, kStep[] = {8, 8, 4, 2};
      for (int pass = 0; pass < 4; ++pass) {
        for (int y = kStart[pass]; y < fh; y += kStep[pass]) {
          if (DGifGetLine(gif, line.data(), fw) == GIF_ERROR) gif_failed(gif->Error);
          put_row(y);
        }
      }
    } else {
      for (int y = 0; y < fh; ++y) {
        if (DGifGetLine(gif, line.data(), fw) == GIF_ERROR) gif_failed(gif->Error);
        put_row(y);
      }
    }
    return image;  // alpha is 0 or 255: premultiplied already
  }
}

// ---- WebP ----

Image decode_webp(std::span<const std::uint8_t> bytes) {
  WebPBitstreamFeatures features;
  if (WebPGetFeatures(bytes.data(), bytes.size(), &features) != VP8_STATUS_OK) throw Error("corrupt WebP data");
  if (features.has_animation) throw Error("animated WebP images are not supported");
  check_declared_size("WebP", static_cast<std::uint64_t>(std::max(features.width, 0)),
                      static_cast<std::uint64_t>(std::max(features.height, 0)));
  Image image(features.width, features.height);
  const int stride = features.width * 4;
  if (!WebPDecodeRGBAInto(bytes.data(), bytes.size(), image.data.data(), image.data.size(), stride))
    throw Error("corrupt WebP data");
  premultiply(image);
  return image;
}

}  // namespace

ImageFormat sniff_image_format(std::span<const std::uint8_t> bytes) {
  if (starts_with(bytes, 0, "\x89PNG\r\n\x1a\n")) return ImageFormat::Png;
  if (starts_with(bytes, 0, "\xff\xd8\xff")) return ImageFormat::Jpeg;
  if (starts_with(bytes, 0, "GIF87a") || starts_with(bytes, 0, "GIF89a")) return ImageFormat::Gif;
  if (starts_with(bytes, 0, "RIFF") && starts_with(bytes, 8, "WEBP")) return ImageFormat::Webp;
  return ImageFormat::Unknown;
}

const char* image_format_name(ImageFormat format) {
  switch (format) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::Gif: return "GIF";
    case ImageFormat::Webp: return "WebP";
    case ImageFormat::Unknown: break;
  }
  return "unknown";
}

Image decode_image(std::span<const std::uint8_t> bytes) {
  switch (sniff_image_format(bytes)) {
    case ImageFormat::Png: return decode_png(bytes);
    case ImageFormat::Jpeg: return decode_jpeg(bytes);
    case ImageFormat::Gif: return decode_gif(bytes);
    case ImageFormat::Webp: return decode_webp(bytes);
    case ImageFormat::Unknown: break;
  }
  throw Error("not an image format vraster reads (PNG, JPEG, GIF, WebP)");
}

}  // namespace vraster
