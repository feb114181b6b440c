// PNG files through libpng. libpng reports errors by longjmp; each libpng call sequence lives in a function with
// no C++ objects that need destructors, and failures come back as a message that the caller turns into an Error.
#include "vraster/png.hpp"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "vraster/error.hpp"
#include "vraster/files.hpp"
#include "vraster/image_io.hpp"

namespace vraster {
namespace {

struct ErrorState {
  char message[256] = "unknown libpng error";
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp msg) {
  auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof state->message, "%s", msg);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// One row as straight (un-premultiplied) big-endian RGBA for libpng.
template <class T>
void straight_row(const BasicImage<T>& image, int y, png_byte* out) {
  constexpr std::uint32_t kMax = BasicImage<T>::kMax;
  const T* px = image.pixel(0, y);
  std::size_t o = 0;
  for (int x = 0; x < image.width; ++x, px += 4) {
    const std::uint32_t a = px[3];
    for (int c = 0; c < 4; ++c) {
      std::uint32_t v = px[c];
      if (c < 3) v = a == 0 ? 0 : static_cast<std::uint32_t>((std::uint64_t{v} * kMax + a / 2) / a);
      if (v > kMax) v = kMax;
      if constexpr (sizeof(T) == 2) out[o++] = static_cast<png_byte>(v >> 8);
      out[o++] = static_cast<png_byte>(v & 0xFF);
    }
  }
}

// Appends encoded bytes to the std::vector<std::uint8_t> that is the io pointer.
void write_memory(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  bool stored = true;
  try {
    out->insert(out->end(), data, data + length);
  } catch (...) {
    stored = false;
  }
  if (!stored) png_error(png, "out of memory");  // no C++ object alive here: the longjmp is safe
}

void flush_memory(png_structp) {}

// Writes to `file`, or else appends to `memory`. Returns false and fills `state` on a libpng error. Rows are
// converted one at a time into `row` (one row of memory beside the image, not a second copy of it).
template <class T>
bool write_rows(FILE* file, std::vector<std::uint8_t>* memory, const BasicImage<T>& image, png_byte* row,
                ErrorState& state) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  if (file) {
    png_init_io(png, file);
  } else {
    png_set_write_fn(png, memory, write_memory, flush_memory);
  }
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height),
               8 * static_cast<int>(sizeof(T)), PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // One filter (Up) instead of libpng's per-row trial of all five: encoding takes about half the time (it was
  // most of the time of large renders) for files 0-6% larger on our pictures.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    straight_row(image, y, row);
    png_write_row(png, row);
  }
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

template <class T>
void encode_png(OutputFile& file, const BasicImage<T>& image) {
  std::vector<png_byte> row(static_cast<std::size_t>(image.width) * 4 * sizeof(T));
  ErrorState state;
  if (!write_rows(file.stream(), nullptr, image, row.data(), state)) {
    // libpng says only "Write Error" when fwrite fails; errno says why (no space, file too large).
    const std::string reason = std::ferror(file.stream()) ? std::strerror(errno) : state.message;
    throw Error("cannot write " + quoted(file.path(), 1024) + ": " + reason);
  }
}

template <class T>
std::vector<std::uint8_t> encode_png_in_memory(const BasicImage<T>& image) {
  std::vector<png_byte> row(static_cast<std::size_t>(image.width) * 4 * sizeof(T));
  std::vector<std::uint8_t> bytes;
  ErrorState state;
  if (!write_rows(nullptr, &bytes, image, row.data(), state)) throw Error(std::string("cannot encode a PNG: ") + state.message);
  return bytes;
}

template <class T>
void write_png_any(const std::string& path, const BasicImage<T>& image) {
  OutputFile file(path);
  encode_png(file, image);
  file.commit();
}

struct Decoded {
  int width = 0, height = 0, depth = 8;
};

// Encoded PNG bytes in memory, read through libpng's read callback.
struct MemorySource {
  const png_byte* data = nullptr;
  std::size_t size = 0, pos = 0;
};

void read_memory(png_structp png, png_bytep out, png_size_t length) {
  auto* src = static_cast<MemorySource*>(png_get_io_ptr(png));
  if (length > src->size - src->pos) png_error(png, "truncated PNG data");
  std::memcpy(out, src->data + src->pos, length);
  src->pos += length;
}

// Reads any PNG as straight RGBA, 8 or 16 bits (`want16`), into `pixels`, from `file` or else from `memory`. No
// C++ object is created between setjmp and the end, so a libpng error can jump out safely.
bool read_rows(FILE* file, MemorySource* memory, bool want16, Decoded& out, std::vector<png_byte>& pixels, ErrorState& state) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  if (file)
    png_init_io(png, file);
  else
    png_set_read_fn(png, memory, read_memory);
  png_set_user_limits(png, kMaxImageSide, kMaxImageSide);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (static_cast<std::uint64_t>(w) * h > static_cast<std::uint64_t>(kMaxImagePixels)) {
    png_error(png, "image too large");
  }
  const int color = png_get_color_type(png, info);
  const int bits = png_get_bit_depth(png, info);
  png_set_expand(png);  // palette -> RGB, grey < 8 bits -> 8 bits, tRNS -> alpha
  if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (!(color & PNG_COLOR_MASK_ALPHA)) png_set_add_alpha(png, want16 ? 0xFFFF : 0xFF, PNG_FILLER_AFTER);
  if (want16 && bits < 16) png_set_expand_16(png);
  if (!want16 && bits == 16) png_set_strip_16(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out.width = static_cast<int>(w);
  out.height = static_cast<int>(h);
  out.depth = want16 ? 16 : 8;
  const std::size_t stride = png_get_rowbytes(png, info);
  if (stride != static_cast<std::size_t>(w) * 4 * (want16 ? 2 : 1)) png_error(png, "unexpected row layout");
  pixels.resize(stride * h);
  for (int pass = 0; pass < passes; ++pass) {
    for (png_uint_32 y = 0; y < h; ++y) png_read_row(png, pixels.data() + stride * y, nullptr);
  }
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// Straight RGBA rows from read_rows -> a premultiplied image.
template <class T>
BasicImage<T> premultiplied(const Decoded& d, const std::vector<png_byte>& pixels) {
  BasicImage<T> image(d.width, d.height);
  constexpr std::uint64_t kMax = BasicImage<T>::kMax;
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    std::uint64_t px[4];
    for (int c = 0; c < 4; ++c) {
      px[c] = sizeof(T) == 2 ? (std::uint64_t{pixels[(i + c) * 2]} << 8 | pixels[(i + c) * 2 + 1]) : pixels[i + c];
    }
    for (int c = 0; c < 3; ++c) image.data[i + c] = static_cast<T>((px[c] * px[3] + kMax / 2) / kMax);
    image.data[i + 3] = static_cast<T>(px[3]);
  }
  return image;
}

template <class T>
BasicImage<T> read_png_any(const std::string& path) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw Error("cannot read " + path + ": " + std::strerror(errno));
  png_byte sig[8] = {};
  const bool is_png = std::fread(sig, 1, 8, file) == 8 && png_sig_cmp(sig, 0, 8) == 0;
  if (!is_png) {
    std::fclose(file);
    throw Error("cannot read " + path + ": not a PNG file");
  }
  std::rewind(file);
  ErrorState state;
  Decoded d;
  std::vector<png_byte> pixels;
  const bool ok = read_rows(file, nullptr, sizeof(T) == 2, d, pixels, state);
  std::fclose(file);
  if (!ok) throw Error("cannot read " + path + ": " + state.message);
  return premultiplied<T>(d, pixels);
}

}  // namespace

void write_png(const std::string& path, const Image& image) { write_png_any(path, image); }
void write_png(OutputFile& file, const Image& image) { encode_png(file, image); }
void write_png(OutputFile& file, const Image16& image) { encode_png(file, image); }
std::vector<std::uint8_t> png_bytes(const Image& image) { return encode_png_in_memory(image); }
std::vector<std::uint8_t> png_bytes(const Image16& image) { return encode_png_in_memory(image); }
void write_png(const std::string& path, const Image16& image) { write_png_any(path, image); }
Image read_png(const std::string& path) { return read_png_any<std::uint8_t>(path); }
Image16 read_png16(const std::string& path) { return read_png_any<std::uint16_t>(path); }

Image decode_png(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) throw Error("not PNG data");
  MemorySource memory{bytes.data(), bytes.size(), 0};
  ErrorState state;
  Decoded d;
  std::vector<png_byte> pixels;
  if (!read_rows(nullptr, &memory, false, d, pixels, state)) throw Error(std::string("corrupt PNG data: ") + state.message);
  return premultiplied<std::uint8_t>(d, pixels);
}

}  // namespace vraster
