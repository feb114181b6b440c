// libFuzzer target: the PNG reader (read_png, read_png16: every colour type, bit depth, palette, tRNS, interlace).
// A corrupt file throws a vraster::Error naming the file; a file that reads gives the size its header declares
// and premultiplied pixels (no colour channel above alpha), in both depths.
//
// The reader takes a path, so each input is written to a per-process temporary file first.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "vraster/error.hpp"
#include "vraster/png.hpp"

namespace {

const std::string& scratch_file() {
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("vraster_fuzz_png_" + std::to_string(getpid()) + ".png")).string();
  return path;
}

std::uint32_t be32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

template <class Image>
void check(const Image& image, std::uint32_t width, std::uint32_t height) {
  if (image.width != static_cast<int>(width) || image.height != static_cast<int>(height)) std::abort();
  if (image.data.size() != static_cast<std::size_t>(width) * height * 4) std::abort();
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    const auto* p = &image.data[i];
    if (p[0] > p[3] || p[1] > p[3] || p[2] > p[3]) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 65536) return 0;  // size cap
  // Declared sizes above 2^20 pixels are skipped: the reader accepts up to 2^28 (1 GiB of pixels), which only
  // measures the allocator. The header's width and height sit at bytes 16..23 (signature, IHDR length and type).
  std::uint32_t width = 0, height = 0;
  if (size >= 24) {
    width = be32(data + 16), height = be32(data + 20);
    if (static_cast<std::uint64_t>(width) * height > (1u << 20)) return 0;
  }
  {
    std::ofstream out(scratch_file(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    check(vraster::read_png(scratch_file()), width, height);
  } catch (const vraster::Error& e) {
    if (std::string(e.what()).find(scratch_file()) == std::string::npos) std::abort();  // names the file
  }
  try {
    check(vraster::read_png16(scratch_file()), width, height);
  } catch (const vraster::Error& e) {
    if (std::string(e.what()).find(scratch_file()) == std::string::npos) std::abort();
  }
  return 0;
}
