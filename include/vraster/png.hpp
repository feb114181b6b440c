// vraster: PNG files through libpng.
#pragma once

#include <string>

#include "vraster/image.hpp"

namespace vraster {

/// Writes an 8-bit RGBA PNG (channels un-premultiplied). The file appears whole or not at all: the data goes to
/// a temporary file in the same folder that is renamed at the end. Throws vraster::Error on failure.
void write_png(const std::string& path, const Image& image);
/// Writes a 16-bit RGBA PNG.
void write_png(const std::string& path, const Image16& image);

/// Reads any PNG (palette, grey, with or without alpha, 8 or 16 bits) as 8-bit premultiplied RGBA.
/// Throws vraster::Error naming the file and libpng's complaint for a missing or corrupt file.
Image read_png(const std::string& path);
/// Reads any PNG as 16-bit premultiplied RGBA.
Image16 read_png16(const std::string& path);

}  // namespace vraster
