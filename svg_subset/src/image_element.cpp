// svg_subset: data: URLs, the folder rule for image files, .svgz, and image placement (image_element.hpp).
#include "image_element.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "scan.hpp"

namespace vraster::svg::detail {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// %XX escapes decoded; a '%' not followed by two hex digits stays as it is (as browsers do).
std::string percent_decode(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hex_value(s[i + 1]) >= 0 && hex_value(s[i + 2]) >= 0) {
      out.push_back(static_cast<char>(hex_value(s[i + 1]) * 16 + hex_value(s[i + 2])));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;  // '-' and '_': the URL-safe alphabet
  if (c == '/' || c == '_') return 63;
  return -1;
}

bool is_ascii_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

std::optional<std::vector<std::uint8_t>> base64_decode(std::string_view s) {
  std::vector<std::uint8_t> out;
  out.reserve(s.size() / 4 * 3 + 3);
  std::uint32_t bits = 0;
  int count = 0;
  bool padding = false;
  for (const char c : s) {
    if (is_ascii_space(c)) continue;
    if (c == '=') {
      padding = true;
      continue;
    }
    const int v = base64_value(c);
    if (v < 0 || padding) return std::nullopt;  // a stray character, or data after the padding
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    if (++count == 4) {
      out.push_back(static_cast<std::uint8_t>(bits >> 16));
      out.push_back(static_cast<std::uint8_t>(bits >> 8));
      out.push_back(static_cast<std::uint8_t>(bits));
      bits = 0;
      count = 0;
    }
  }
  if (count == 1) return std::nullopt;
  if (count == 2) out.push_back(static_cast<std::uint8_t>(bits >> 4));
  if (count == 3) {
    out.push_back(static_cast<std::uint8_t>(bits >> 10));
    out.push_back(static_cast<std::uint8_t>(bits >> 2));
  }
  return out;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

Rect fit_rect(const Rect& view, double width, double height, const AspectRatio& aspect) {
  const double vw = view.x1 - view.x0, vh = view.y1 - view.y0;
  if (aspect.none || !(width > 0) || !(height > 0)) return view;
  const double sx = vw / width, sy = vh / height;
  const double s = aspect.slice ? std::max(sx, sy) : std::min(sx, sy);
  const double w = width * s, h = height * s;
  const double x = view.x0 + aspect.align_x * (vw - w), y = view.y0 + aspect.align_y * (vh - h);
  return Rect{x, y, x + w, y + h};
}

std::optional<DataUrl> parse_data_url(std::string_view href, std::string& why) {
  href = trim(href);
  if (!istarts_with(href, "data:")) {
    why = "not a data: URL";
    return std::nullopt;
  }
  href.remove_prefix(5);
  const std::size_t comma = href.find(',');
  if (comma == std::string_view::npos) {
    why = "data: URL without a ','";
    return std::nullopt;
  }
  std::string_view header = trim(href.substr(0, comma));
  const std::string_view payload = href.substr(comma + 1);
  bool base64 = false;
  if (header.size() >= 7 && iequals(trim(header.substr(header.size() - 7)), ";base64")) {
    base64 = true;
    header = trim(header.substr(0, header.size() - 7));
  }
  DataUrl url;
  url.mime = lower(trim(header.substr(0, header.find(';'))));
  const std::string decoded = percent_decode(payload);
  if (base64) {
    std::optional<std::vector<std::uint8_t>> bytes = base64_decode(decoded);
    if (!bytes) {
      why = "invalid base64 in a data: URL";
      return std::nullopt;
    }
    url.bytes = std::move(*bytes);
  } else {
    url.bytes.assign(decoded.begin(), decoded.end());
  }
  return url;
}

std::optional<std::string> resolve_image_file(std::string_view href, const ParseOptions& options, std::string& why) {
  namespace fs = std::filesystem;
  href = trim(href);
  if (options.base_dir.empty()) {
    why = "external files are not read here (an SVG image, or a document without a folder)";
    return std::nullopt;
  }
  // A scheme ("http:", "file:", "c:") is a URL or a drive, never read: only relative paths are files here.
  const std::size_t colon = href.find(':');
  const std::size_t slash = href.find('/');
  if (colon != std::string_view::npos && (slash == std::string_view::npos || colon < slash)) {
    why = "only data: URLs and relative file paths are read (no network, no other schemes)";
    return std::nullopt;
  }
  std::string relative = percent_decode(href.substr(0, href.find_first_of("?#")));
  if (relative.empty() || relative.find('\0') != std::string::npos) {
    why = "empty or invalid file path";
    return std::nullopt;
  }
  if (relative[0] == '/' || relative[0] == '\\') {
    why = "absolute file paths are refused";
    return std::nullopt;
  }
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(fs::path(options.allowed_dir.empty() ? options.base_dir : options.allowed_dir), ec);
  if (ec) {
    why = "the document's folder cannot be resolved";
    return std::nullopt;
  }
  const fs::path file = fs::weakly_canonical(fs::path(options.base_dir) / relative, ec);
  if (ec) {
    why = "the file path cannot be resolved";
    return std::nullopt;
  }
  // Inside the root: the path relative to it neither climbs out nor is empty (the root itself).
  const fs::path inside = file.lexically_relative(root);
  if (inside.empty() || *inside.begin() == ".." || inside == ".") {
    why = "the file lies outside the document's folder (refused)";
    return std::nullopt;
  }
  // Only regular files: a FIFO would block the reader, a device could be endless.
  if (!fs::is_regular_file(file, ec)) {
    why = "no such file (or not a regular file)";
    return std::nullopt;
  }
  return file.string();
}

std::string folder_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

bool is_gzip(std::span<const std::uint8_t> bytes) { return bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b; }

bool looks_like_svg(std::span<const std::uint8_t> bytes, std::string_view mime) {
  if (mime == "image/svg+xml" || is_gzip(bytes)) return true;
  std::size_t i = 0;
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;  // UTF-8 BOM
  while (i < bytes.size() && is_ascii_space(static_cast<char>(bytes[i]))) ++i;
  return i < bytes.size() && bytes[i] == '<';
}

std::optional<std::string> gunzip(std::span<const std::uint8_t> bytes, std::size_t max_bytes, std::string& why) {
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) {
    why = "zlib cannot start";
    return std::nullopt;
  }
  std::string out;
  z.next_in = const_cast<Bytef*>(bytes.data());
  z.avail_in = static_cast<uInt>(std::min<std::size_t>(bytes.size(), 0xFFFFFFFFu));
  int status = Z_OK;
  char chunk[16384];
  while (status == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(chunk);
    z.avail_out = sizeof chunk;
    status = inflate(&z, Z_NO_FLUSH);
    if (status != Z_OK && status != Z_STREAM_END) break;
    out.append(chunk, sizeof chunk - z.avail_out);
    if (out.size() > max_bytes) {
      inflateEnd(&z);
      why = "compressed SVG image larger than " + std::to_string(max_bytes >> 20) + " MiB once inflated";
      return std::nullopt;
    }
    if (status == Z_OK && z.avail_in == 0 && z.avail_out != 0) status = Z_BUF_ERROR;  // truncated
  }
  inflateEnd(&z);
  if (status != Z_STREAM_END) {
    why = "corrupt gzip data";
    return std::nullopt;
  }
  return out;
}

}  // namespace vraster::svg::detail
