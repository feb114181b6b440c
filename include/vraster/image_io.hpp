// vraster: decoding raster images held in memory (PNG, JPEG, GIF, WebP) into premultiplied RGBA8.
#pragma once

#include <cstdint>
#include <span>

#include "vraster/image.hpp"

namespace vraster {

/// Raster formats decode_image() reads.
enum class ImageFormat : std::uint8_t { Unknown, Png, Jpeg, Gif, Webp };

/// The format of encoded bytes, from their signature (never from a file name or a MIME type).
ImageFormat sniff_image_format(std::span<const std::uint8_t> bytes);

/// "PNG", "JPEG", "GIF", "WebP" or "unknown".
const char* image_format_name(ImageFormat format);

/// Decodes PNG (any colour type and depth, 16 bits reduced to 8), JPEG (baseline and progressive; grey, RGB
/// and CMYK), GIF (the first frame on its transparent logical screen) or WebP (still images) into 8-bit
/// premultiplied RGBA. Throws vraster::Error for an unknown format, corrupt data, or an image above the limits of
/// image.hpp (checked from the header, before any pixel is allocated).
Image decode_image(std::span<const std::uint8_t> bytes);

/// decode_image() for PNG data only (used by it; in png.cpp with the rest of libpng).
Image decode_png(std::span<const std::uint8_t> bytes);

}  // namespace vraster
