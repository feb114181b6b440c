// svg_subset: what <image> needs apart from the element walk: data: URLs, the folder rule for files, SVG image
// sniffing and .svgz, and where an image lands under preserveAspectRatio.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "svg_subset/svg.hpp"
#include "vraster/geometry.hpp"

namespace vraster::svg::detail {

/// A parsed preserveAspectRatio: alignment fractions (xMin 0, xMid 0.5, xMax 1) and meet / slice / none.
struct AspectRatio {
  double align_x = 0.5, align_y = 0.5;
  bool none = false, slice = false;
};

/// Where content of size `width` x `height` lands in `view` (meet: fits inside; slice: covers; none: stretched).
Rect fit_rect(const Rect& view, double width, double height, const AspectRatio& aspect);

/// A decoded data: URL (RFC 2397): the media type (lower case, parameters dropped; may be empty) and the bytes.
struct DataUrl {
  std::string mime;
  std::vector<std::uint8_t> bytes;
};

/// Decodes "data:[type][;params][;base64],payload" (percent-escapes decoded; base64 may hold whitespace and
/// may lack padding). Nothing, with `why` set, for malformed data.
std::optional<DataUrl> parse_data_url(std::string_view href, std::string& why);

/// The file a relative href names, when it lies inside the allowed folder (options.allowed_dir, else
/// options.base_dir) once `..` and symbolic links are resolved. Nothing, with `why` set, for URLs with a scheme
/// (the network is never used), absolute paths, paths that leave the folder, or when files may not be read at
/// all (no base_dir: a document held in memory, or an SVG image, which SVG loads in secure mode).
std::optional<std::string> resolve_image_file(std::string_view href, const ParseOptions& options, std::string& why);

/// The folder of a file path ("." for a bare name).
std::string folder_of(const std::string& path);

/// Whether bytes that are no raster format look like an SVG document (XML text, or gzip: .svgz).
bool looks_like_svg(std::span<const std::uint8_t> bytes, std::string_view mime);

/// Inflates gzip data (.svgz) up to `max_bytes` of output. Nothing, with `why` set, when corrupt or too large.
std::optional<std::string> gunzip(std::span<const std::uint8_t> bytes, std::size_t max_bytes, std::string& why);

/// Whether bytes start with the gzip signature.
bool is_gzip(std::span<const std::uint8_t> bytes);

}  // namespace vraster::svg::detail
