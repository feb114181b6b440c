// vraster: PNG files through libpng.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vraster/image.hpp"
#include "vraster/files.hpp"

namespace vraster {

/// Writes an 8-bit RGBA PNG (channels un-premultiplied), row by row (no second copy of the image). The file
/// appears whole or not at all, keeps an existing file's permissions, and a device or FIFO is written into
/// (see OutputFile). Throws vraster::Error on failure.
void write_png(const std::string& path, const Image& image);
/// Writes a 16-bit RGBA PNG.
void write_png(const std::string& path, const Image16& image);
/// Encodes a PNG into `file` without committing it (for several files that must all appear or none).
void write_png(OutputFile& file, const Image& image);
void write_png(OutputFile& file, const Image16& image);
/// The PNG file write_png would write, in memory (8 or 16 bits), e.g. to send it down a pipe only once it is
/// whole. Throws vraster::Error on failure.
std::vector<std::uint8_t> png_bytes(const Image& image);
std::vector<std::uint8_t> png_bytes(const Image16& image);

/// Reads any PNG (palette, grey, with or without alpha, 8 or 16 bits) as 8-bit premultiplied RGBA.
/// Throws vraster::Error naming the file and libpng's complaint for a missing or corrupt file.
Image read_png(const std::string& path);
/// Reads any PNG as 16-bit premultiplied RGBA.
Image16 read_png16(const std::string& path);

}  // namespace vraster
